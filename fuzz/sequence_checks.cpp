#include "sequence_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "fuzz_checks.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/brute_force.h"
#include "stress_sequences.h"

namespace sap_broadphase::fuzz {
namespace {

// The oracle is O(n^2) a frame and a sequence runs up to kMaxFrames frames.
constexpr std::size_t kMaxBoxes = 128;
constexpr std::size_t kMaxFirstBoxes = 64;
constexpr std::size_t kMaxSceneryBoxes = 32;
constexpr int kMaxFrames = 64;

using stress::SequenceBox;

// What the first bytes ask for.
struct SequenceSetup {
  BroadphaseConfig config;
  bool declared_scenery = false;
  bool filters = false;
};

SequenceSetup decodeSetup(ByteReader& ioReader) {
  static const Method kMethods[4] = {Method::kAuto, Method::kParallel, Method::kSequential,
                                     Method::kBruteForce};
  static const std::optional<double> kSkins[4] = {0.0, std::nullopt, 0.25, 2.0};
  static const int kSlabs[4] = {0, 1, 3, 64};
  static const int kAxisPairs[6][2] = {{0, 1}, {1, 2}, {2, 0}, {1, 0}, {2, 1}, {0, 2}};
  const uint8_t switches = ioReader.byte();
  const uint8_t layout = ioReader.byte();
  SequenceSetup setup;
  BroadphaseConfig& config = setup.config;
  config.reuse_unchanged_frames = switches & 0x1;
  config.skin = kSkins[(switches >> 2) & 0x3];
  setup.declared_scenery = switches & 0x10;
  setup.filters = switches & 0x20;
  config.method = kMethods[switches >> 6];
  config.threads = 1 + (layout & 0x3);
  config.third_axis_slabs = kSlabs[(layout >> 2) & 0x3];
  config.primary_axis = kAxisPairs[(layout >> 4) % 6][0];
  config.secondary_axis = kAxisPairs[(layout >> 4) % 6][1];
  config.parallel_min_boxes = 4;  // kAuto goes parallel on these small frames too
  return setup;
}

// A coordinate that validate() accepts: NaN becomes 0.
double validCoordinate(ByteReader& ioReader) {
  const double value = decodeCoordinate(ioReader);
  return std::isnan(value) ? 0.0 : value;
}

void orderBounds(SequenceBox& ioBox) {
  for (int axis = 0; axis < 3; ++axis)
    if (ioBox.lo[axis] > ioBox.hi[axis]) std::swap(ioBox.lo[axis], ioBox.hi[axis]);
}

SequenceBox decodeBox(ByteReader& ioReader, uint32_t inId) {
  SequenceBox box{inId, {}, {}, kDefaultGroup, kDefaultMask};
  for (int axis = 0; axis < 3; ++axis) box.lo[axis] = validCoordinate(ioReader);
  for (int axis = 0; axis < 3; ++axis) box.hi[axis] = validCoordinate(ioReader);
  orderBounds(box);
  return box;
}

void decodeFilters(ByteReader& ioReader, SequenceBox& ioBox) {
  ioBox.group = ioReader.byte() & 0x7;  // 0 included: collides with nothing
  const uint8_t mask = ioReader.byte();
  ioBox.mask = mask == 0xFF ? kDefaultMask : (mask & 0x7);
}

BoxSet toBoxSet(const std::vector<SequenceBox>& inBoxes, bool inFilters) {
  BoxSet boxes;
  boxes.reserve(inBoxes.size());
  for (const SequenceBox& box : inBoxes) stress::appendBox(boxes, box, inFilters);
  return boxes;
}

// The world the edits change, frame after frame.
class FuzzWorld {
 public:
  FuzzWorld(ByteReader& ioReader, bool inFilters) : reader_(ioReader), filters_(inFilters) {}

  void addBox() {
    if (boxes_.size() >= kMaxBoxes) return;
    SequenceBox box = decodeBox(reader_, next_id_);
    next_id_ += 1 + reader_.byte();  // sparse ids now and then; below kFirstSceneryId
    if (filters_) decodeFilters(reader_, box);
    const std::size_t at = boxes_.empty() ? 0 : reader_.byte() % (boxes_.size() + 1);
    boxes_.insert(boxes_.begin() + static_cast<std::ptrdiff_t>(at), box);
  }
  /// Applies the edit inEdit names (its low four bits); 8 and above edit nothing (an identical
  /// frame follows).
  void edit(uint8_t inEdit) {
    const int kind = inEdit & 0xF;
    if (kind == 2) return addBox();
    if (kind == 6) return flipSignedZeros();
    if (kind == 7)
      return translate(static_cast<double>(static_cast<int>(reader_.byte()) - 128) * 0.25);
    if (kind > 7 || boxes_.empty()) return;
    const std::size_t index = reader_.byte() % boxes_.size();
    switch (kind) {
      case 0:
        moveBound(boxes_[index]);
        break;
      case 1:
        stepBoundByUlps(boxes_[index]);
        break;
      case 3:
        boxes_.erase(boxes_.begin() + static_cast<std::ptrdiff_t>(index));
        break;
      case 4:
        std::swap(boxes_[index], boxes_[reader_.byte() % boxes_.size()]);
        break;
      default:
        filters_ = true;  // a set without filters gains them
        decodeFilters(reader_, boxes_[index]);
        break;
    }
  }
  BoxSet boxes() const { return toBoxSet(boxes_, filters_); }
  std::size_t size() const { return boxes_.size(); }

 private:
  void moveBound(SequenceBox& ioBox) {
    const uint8_t where = reader_.byte();
    double& bound = (where & 0x4) ? ioBox.hi[where % 3] : ioBox.lo[where % 3];
    bound = validCoordinate(reader_);
    orderBounds(ioBox);
  }
  void stepBoundByUlps(SequenceBox& ioBox) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const uint8_t where = reader_.byte();
    double& bound = (where & 0x4) ? ioBox.hi[where % 3] : ioBox.lo[where % 3];
    const int steps = static_cast<int>(where >> 5) - 4;  // -4..3
    for (int k = 0; k < std::abs(steps); ++k) bound = std::nextafter(bound, steps * kInf);
    orderBounds(ioBox);
  }
  void flipSignedZeros() {
    for (SequenceBox& box : boxes_) stress::flipSignedZeros(box);
  }
  // A finite offset keeps lo <= hi (rounding is monotonic) and infinities infinite.
  void translate(double inOffset) {
    for (SequenceBox& box : boxes_)
      for (int axis = 0; axis < 3; ++axis) {
        box.lo[axis] += inOffset;
        box.hi[axis] += inOffset;
      }
  }

  ByteReader& reader_;
  bool filters_;
  std::vector<SequenceBox> boxes_;
  uint32_t next_id_ = 0;
};

BoxSet decodeScenery(ByteReader& ioReader, std::size_t inCount) {
  std::vector<SequenceBox> scenery;
  for (std::size_t i = 0; i < inCount; ++i) {
    scenery.push_back(decodeBox(ioReader, stress::kFirstSceneryId + static_cast<uint32_t>(i)));
    decodeFilters(ioReader, scenery.back());
  }
  return toBoxSet(scenery, true);
}

// A path the configuration cannot take means a skip ran where it was switched off.
std::string pathProblem(const BroadphaseConfig& inConfig, const FrameReport& inReport) {
  const FramePath path = inReport.path;
  if (path == FramePath::kReused && !inConfig.reuse_unchanged_frames)
    return "reused a frame with reuse off";
  if (path == FramePath::kSkin && inConfig.skin == 0.0) return "skin path with the skin off";
  if (path == FramePath::kBruteForce && inConfig.method != Method::kBruteForce)
    return "brute-force path without the brute method";
  if (path == FramePath::kParallel && inConfig.method == Method::kSequential)
    return "parallel path with the sequential method";
  if (path == FramePath::kSequential && inConfig.method == Method::kParallel)
    return "sequential path with the parallel method";
  if (path == FramePath::kEmpty && inReport.boxes - inReport.boxes_filtered_out >= 2)
    return "empty path with two or more collidable boxes";
  return "";
}

}  // namespace

std::string checkSequenceBytes(const uint8_t* inData, std::size_t inSize) {
  ByteReader reader(inData, inSize);
  const SequenceSetup setup = decodeSetup(reader);
  const std::size_t first_boxes = reader.byte() % (kMaxFirstBoxes + 1);
  const std::size_t scenery_boxes =
      setup.declared_scenery ? reader.byte() % (kMaxSceneryBoxes + 1) : 0;
  const BoxSet scenery = decodeScenery(reader, scenery_boxes);
  FuzzWorld world(reader, setup.filters);
  for (std::size_t i = 0; i < first_boxes; ++i) world.addBox();
  Broadphase engine(setup.config);
  bool scenery_declared = setup.declared_scenery;
  if (scenery_declared) engine.setStaticBoxes(scenery);
  for (int frame = 0; frame < kMaxFrames; ++frame) {
    const BoxSet boxes = world.boxes();
    const PairList oracle =
        scenery_declared ? stress::declaredSceneryOracle(scenery, boxes) : bruteForcePairs(boxes);
    const PairList& pairs = engine.update(boxes);
    const std::string where =
        "frame " + std::to_string(frame) + ", path " + framePathName(engine.stats().path);
    if (pairs != oracle) return pairsDiffer(where.c_str(), oracle, pairs);
    const std::string wrong_path = pathProblem(setup.config, engine.stats());
    if (!wrong_path.empty()) return where + ": " + wrong_path;
    if (reader.empty()) break;
    // Edits up to one that asks for a frame, or to the end of the input: a frame follows
    // either way. Edit 8 declares the scenery again or forgets it.
    bool frame_asked = false;
    while (!frame_asked && !reader.empty()) {
      const uint8_t edit = reader.byte();
      frame_asked = edit & 0x80;
      if ((edit & 0xF) == 8 && setup.declared_scenery) {
        scenery_declared = !scenery_declared;
        if (scenery_declared)
          engine.setStaticBoxes(scenery);
        else
          engine.clearStaticBoxes();
      } else {
        world.edit(edit);
      }
    }
  }
  return "";
}

}  // namespace sap_broadphase::fuzz
