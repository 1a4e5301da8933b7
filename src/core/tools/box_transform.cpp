// Moving boxes between frames: 8 corners, rounded outwards.
#include "core/tools/box_transform.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <utility>

#include "core/assert.h"

namespace sap_broadphase {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

using Matrix3 = double[3][3];

/// The rotation matrix of the quaternion (x, y, z, w), its length divided out: the same
/// products in the same order as tf2::Matrix3x3::setRotation, so a box moves here exactly as
/// tf2's own matrix would move it.
void rotationMatrix(const double inQuaternion[4], Matrix3& outMatrix) {
  const double x = inQuaternion[0], y = inQuaternion[1], z = inQuaternion[2];
  const double w = inQuaternion[3];
  const double s = 2.0 / (x * x + y * y + z * z + w * w);
  const double xs = x * s, ys = y * s, zs = z * s;
  const double wx = w * xs, wy = w * ys, wz = w * zs;
  const double xx = x * xs, xy = x * ys, xz = x * zs;
  const double yy = y * ys, yz = y * zs, zz = z * zs;
  const double rows[3][3] = {{1.0 - (yy + zz), xy - wz, xz + wy},
                             {xy + wz, 1.0 - (xx + zz), yz - wx},
                             {xz - wy, yz + wx, 1.0 - (xx + yy)}};
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 3; ++column) outMatrix[row][column] = rows[row][column];
}

/// Moves box i of ioBoxes (a box: lo <= hi on every axis).
void transformBox(const Matrix3& inRotation, const double inTranslation[3], std::size_t i,
                  BoxSet& ioBoxes) {
  const double lo[3] = {ioBoxes.lo(0, i), ioBoxes.lo(1, i), ioBoxes.lo(2, i)};
  const double hi[3] = {ioBoxes.hi(0, i), ioBoxes.hi(1, i), ioBoxes.hi(2, i)};
  for (int out = 0; out < 3; ++out) {
    // The extremes over the 8 corners of row `out` of R x + t separate per input axis: each
    // term takes the smaller (larger) of R[out][in] * lo and R[out][in] * hi.
    double low = inTranslation[out], high = inTranslation[out];
    double magnitude = std::fabs(inTranslation[out]);
    for (int in = 0; in < 3; ++in) {
      const double factor = inRotation[out][in];
      if (factor == 0.0) continue;  // 0 x inf would be NaN; the axis does not contribute
      const double a = factor * lo[in], b = factor * hi[in];
      low += std::min(a, b);
      high += std::max(a, b);
      magnitude += std::max(std::fabs(a), std::fabs(b));
    }
    // Three products and four sums round at most 4 x (DBL_EPSILON / 2) x magnitude away from
    // the exact corner; widen by that and one more ulp so the box only grows.
    const double slack = 2.0 * DBL_EPSILON * magnitude;
    low = std::isnan(low) ? -kInfinity : std::nextafter(low - slack, -kInfinity);
    high = std::isnan(high) ? kInfinity : std::nextafter(high + slack, kInfinity);
    ioBoxes.lo(out, i) = low;
    ioBoxes.hi(out, i) = high;
  }
}

}  // namespace

std::optional<std::string> nonFiniteTransform(const RigidTransform& inTransform) {
  const double* t = inTransform.translation;
  const double* q = inTransform.rotation;
  const std::pair<const char*, double> components[] = {
      {"translation.x", t[0]}, {"translation.y", t[1]}, {"translation.z", t[2]},
      {"rotation.x", q[0]},    {"rotation.y", q[1]},    {"rotation.z", q[2]},
      {"rotation.w", q[3]}};
  for (const auto& [name, value] : components) {
    if (!std::isfinite(value)) return std::string(name) + " is " + std::to_string(value);
  }
  return std::nullopt;
}

void transformBoxes(const RigidTransform& inTransform, BoxSet& ioBoxes) {
  SAP_ASSERT(!nonFiniteTransform(inTransform), "a transform that moves boxes is finite");
  Matrix3 rotation;
  rotationMatrix(inTransform.rotation, rotation);
  for (std::size_t i = 0; i < ioBoxes.size(); ++i) {
    // `lo <= hi` fails exactly for a NaN bound or min > max: moved, such a box could pass as
    // a box (NaN becomes infinite above), so it stays as published and the engine names it.
    const bool is_box = ioBoxes.lo(0, i) <= ioBoxes.hi(0, i) &&
                        ioBoxes.lo(1, i) <= ioBoxes.hi(1, i) &&
                        ioBoxes.lo(2, i) <= ioBoxes.hi(2, i);
    if (is_box) transformBox(rotation, inTransform.translation, i, ioBoxes);
  }
}

std::optional<std::string> moveBoxes(const RigidTransform& inTransform, BoxSet& ioBoxes) {
  if (auto problem = nonFiniteTransform(inTransform)) return problem;
  transformBoxes(inTransform, ioBoxes);
  return std::nullopt;
}

}  // namespace sap_broadphase
