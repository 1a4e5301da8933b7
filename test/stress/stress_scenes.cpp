#include "stress_scenes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "stress_support.h"

namespace sap_broadphase::stress {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Ten to the power inDecade, for decades within [-300, 300].
double decade(int inDecade) {
  return std::pow(10.0, inDecade);
}

void appendBox(BoxSet& ioBoxes, const double inLow[3], const double inHigh[3]) {
  ioBoxes.add(static_cast<uint32_t>(ioBoxes.size()), inLow, inHigh);
}

// The values inBase + k ulps for k in [-inBelow, inAbove], in ascending order.
std::vector<double> ulpTable(double inBase, int inBelow, int inAbove) {
  std::vector<double> table;
  table.reserve(inBelow + inAbove + 1);
  double value = ulpStep(inBase, -inBelow);
  for (int k = -inBelow; k <= inAbove; ++k) {
    table.push_back(value);
    value = std::nextafter(value, kInf);
  }
  return table;
}

}  // namespace

BoxSet magnitudeScene(std::size_t inCount, uint64_t inSeed) {
  SplitMix64 random(inSeed);
  BoxSet boxes;
  boxes.reserve(inCount);
  // Clusters: one decade and sign each; boxes of a cluster live in a cube about 20 of their
  // own extents wide, so each cluster has some pairs.
  constexpr int kClusters = 61;  // decades -300, -290, ..., 300
  const std::size_t spanning = std::min<std::size_t>(inCount, 4);
  for (std::size_t i = 0; i < inCount - spanning; ++i) {
    const int cluster = static_cast<int>(random.below(kClusters));
    const double scale = decade(-300 + 10 * cluster);
    const double sign = (cluster % 2 == 0) ? 1.0 : -1.0;
    double low[3];
    double high[3];
    for (int axis = 0; axis < 3; ++axis) {
      const double center = sign * scale * (10.0 + random.between(0.0, 20.0));
      const double half = scale * random.between(0.0, 3.0);
      low[axis] = center - half;
      high[axis] = center + half;
    }
    appendBox(boxes, low, high);
  }
  for (std::size_t k = 0; k < spanning; ++k) {
    // Spans every decade on one axis; tiny on the others, around a cluster-free point 0 or
    // around the positive clusters' corner.
    double low[3];
    double high[3];
    for (int axis = 0; axis < 3; ++axis) {
      const double scale = decade(-300 + 10 * static_cast<int>(random.below(kClusters)));
      low[axis] = scale * 5.0;
      high[axis] = scale * 40.0;
    }
    low[k % 3] = -1e300;
    high[k % 3] = 1e300;
    appendBox(boxes, low, high);
  }
  return boxes;
}

BoxSet subnormalScene(std::size_t inCount, uint64_t inSeed) {
  SplitMix64 random(inSeed);
  const double unit = std::numeric_limits<double>::denorm_min();
  const double smallest_normal = std::numeric_limits<double>::min();
  BoxSet boxes;
  boxes.reserve(inCount);
  for (std::size_t i = 0; i < inCount; ++i) {
    double low[3];
    double high[3];
    for (int axis = 0; axis < 3; ++axis) {
      if (random.chance(0.1)) {
        // Straddles the subnormal/normal border.
        low[axis] = ulpStep(smallest_normal, -static_cast<int>(random.below(4)));
        high[axis] = ulpStep(smallest_normal, static_cast<int>(random.below(4)));
        continue;
      }
      const double corner = (static_cast<double>(random.below(40)) - 20.0) * unit;
      low[axis] = corner;
      high[axis] = corner + static_cast<double>(random.below(4)) * unit;
    }
    appendBox(boxes, low, high);
  }
  return boxes;
}

BoxSet signedZeroScene(std::size_t inCount, uint64_t inSeed) {
  SplitMix64 random(inSeed);
  BoxSet boxes;
  boxes.reserve(inCount);
  for (std::size_t i = 0; i < inCount; ++i) {
    double low[3];
    double high[3];
    for (int axis = 0; axis < 3; ++axis) {
      low[axis] = static_cast<double>(random.below(7)) - 3.0;
      high[axis] = low[axis] + static_cast<double>(random.below(2));
      if (low[axis] == 0.0 && random.chance(0.5)) low[axis] = -0.0;
      if (high[axis] == 0.0 && random.chance(0.5)) high[axis] = -0.0;
    }
    appendBox(boxes, low, high);
  }
  return boxes;
}

BoxSet infiniteSlabScene(std::size_t inCount, uint64_t inSeed) {
  SplitMix64 random(inSeed);
  BoxSet boxes;
  boxes.reserve(inCount);
  // The special boxes first: each line is min x y z, max x y z.
  const double specials[][6] = {
      {-kInf, -kInf, -kInf, kInf, kInf, 0.0},      // ground plane z <= 0
      {-kInf, -kInf, 50.0, kInf, kInf, kInf},      // ceiling z >= 50
      {60.0, -kInf, -kInf, kInf, kInf, kInf},      // half-space x >= 60
      {-kInf, -kInf, -kInf, 10.0, kInf, kInf},     // half-space x <= 10
      {-kInf, 20.0, -kInf, kInf, 21.0, kInf},      // wall 20 <= y <= 21
      {30.0, -kInf, 30.0, 31.0, kInf, 31.0},       // rod along y
      {-kInf, -kInf, -kInf, kInf, kInf, kInf},     // everything
      {kInf, kInf, kInf, kInf, kInf, kInf},        // the point at +infinity
      {-kInf, -kInf, -kInf, -kInf, -kInf, -kInf},  // the point at -infinity
      {kInf, 0.0, 0.0, kInf, 100.0, 100.0},        // a face at x = +infinity
      {-kInf, 40.0, 40.0, -kInf, 41.0, 41.0},      // a patch at x = -infinity
      {0.0, -kInf, 0.0, 100.0, -kInf, 100.0},      // a face at y = -infinity
      {99.0, 99.0, 99.0, kInf, kInf, kInf},        // an octant
  };
  for (const auto& special : specials) {
    if (boxes.size() >= inCount) break;
    appendBox(boxes, &special[0], &special[3]);
  }
  while (boxes.size() < inCount) {
    double low[3];
    double high[3];
    for (int axis = 0; axis < 3; ++axis) {
      low[axis] = random.between(0.0, 100.0);
      high[axis] = low[axis] + random.between(0.0, 3.0);
    }
    // A few more random infinite slabs, each infinite on one to three axes.
    if (random.chance(0.01)) {
      for (int axis = 0; axis < 3; ++axis) {
        if (random.chance(0.5)) low[axis] = -kInf;
        if (random.chance(0.5)) high[axis] = kInf;
      }
    }
    appendBox(boxes, low, high);
  }
  return boxes;
}

BoxSet ulpLatticeScene(double inBase, std::size_t inCount, int inCells, int inMaxEdge,
                       uint64_t inSeed) {
  SplitMix64 random(inSeed);
  const std::vector<double> table = ulpTable(inBase, inCells, inCells + inMaxEdge);
  BoxSet boxes;
  boxes.reserve(inCount);
  for (std::size_t i = 0; i < inCount; ++i) {
    double low[3];
    double high[3];
    for (int axis = 0; axis < 3; ++axis) {
      const std::size_t corner = random.below(2 * inCells + 1);
      low[axis] = table[corner];
      high[axis] = table[corner + random.below(inMaxEdge + 1)];
    }
    appendBox(boxes, low, high);
  }
  return boxes;
}

BoxSet specialValueScene(std::size_t inCount, uint64_t inSeed) {
  SplitMix64 random(inSeed);
  const double anchors[] = {kInf,
                            1e300,
                            std::numeric_limits<double>::max(),
                            0x1p53,
                            0x1p24,
                            1.0,
                            1e-300,
                            std::numeric_limits<double>::min(),
                            std::numeric_limits<double>::denorm_min(),
                            0.0,
                            static_cast<double>(std::numeric_limits<float>::max()),
                            static_cast<double>(std::numeric_limits<float>::min())};
  std::vector<double> pool;
  for (double anchor : anchors) {
    for (double sign : {1.0, -1.0}) {
      for (int step = -1; step <= 1; ++step) pool.push_back(ulpStep(sign * anchor, step));
    }
  }
  pool.push_back(-0.0);
  std::sort(pool.begin(), pool.end());
  BoxSet boxes;
  boxes.reserve(inCount);
  for (std::size_t i = 0; i < inCount; ++i) {
    double low[3];
    double high[3];
    for (int axis = 0; axis < 3; ++axis) {
      const std::size_t first = random.below(pool.size());
      const std::size_t last = std::min(pool.size() - 1, first + random.below(3));
      low[axis] = pool[first];
      high[axis] = pool[last];
    }
    appendBox(boxes, low, high);
  }
  return boxes;
}

BoxSet translated(const BoxSet& inBoxes, const double inOffset[3]) {
  BoxSet moved = inBoxes;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      moved.lo(axis, i) += inOffset[axis];
      moved.hi(axis, i) += inOffset[axis];
    }
  }
  return moved;
}

void addRandomFilters(BoxSet& ioBoxes, uint64_t inSeed) {
  SplitMix64 random(inSeed);
  ioBoxes.groups.resize(ioBoxes.size());
  ioBoxes.masks.resize(ioBoxes.size());
  for (std::size_t i = 0; i < ioBoxes.size(); ++i) {
    ioBoxes.groups[i] = static_cast<uint32_t>(random.below(8));  // 0 never collides
    ioBoxes.masks[i] = random.chance(0.1) ? 0xFFFFFFFFu : static_cast<uint32_t>(random.below(8));
  }
}

}  // namespace sap_broadphase::stress
