#include "fuzz_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/text_io.h"
#include "stress_sequences.h"

namespace sap_broadphase::fuzz {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Values where float32 keys and float64 comparisons are most likely to disagree.
const double kSpecials[] = {0.0,
                            -0.0,
                            kInf,
                            -kInf,
                            1.0,
                            -1.0,
                            0x1p24,
                            -0x1p24,
                            0x1p53,
                            -0x1p53,
                            1e300,
                            -1e300,
                            1e-300,
                            -1e-300,
                            std::numeric_limits<double>::max(),
                            -std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::min(),
                            std::numeric_limits<double>::denorm_min(),
                            -std::numeric_limits<double>::denorm_min(),
                            static_cast<double>(std::numeric_limits<float>::max()),
                            static_cast<double>(std::numeric_limits<float>::min()),
                            static_cast<double>(std::numeric_limits<float>::denorm_min()),
                            std::numeric_limits<double>::quiet_NaN(),
                            0.1};
constexpr std::size_t kSpecialCount = sizeof(kSpecials) / sizeof(kSpecials[0]);

double stepUlps(double inValue, int inSteps) {
  for (int k = 0; k < std::abs(inSteps); ++k) inValue = std::nextafter(inValue, inSteps * kInf);
  return inValue;
}

// Keys-only output: canonical, contains the oracle, extras overlap in key space (small n).
std::string checkSuperset(const BoxSet& inBoxes, const PairList& inOracle,
                          const PairList& inKeysOnly) {
  for (std::size_t k = 0; k < inKeysOnly.size(); ++k) {
    if (!(inKeysOnly[k].a < inKeysOnly[k].b) || (k > 0 && !(inKeysOnly[k - 1] < inKeysOnly[k])))
      return "keys-only pairs not canonical at " + std::to_string(k);
  }
  if (!std::includes(inKeysOnly.begin(), inKeysOnly.end(), inOracle.begin(), inOracle.end()))
    return pairsDiffer("keys-only mode missed a pair", inOracle, inKeysOnly);
  const KeyOrigin origin = stress::firstFrameKeyOrigin(inBoxes);
  for (const IdPair& pair : inKeysOnly) {
    if (std::binary_search(inOracle.begin(), inOracle.end(), pair)) continue;
    const auto a = std::find(inBoxes.ids.begin(), inBoxes.ids.end(), pair.a) - inBoxes.ids.begin();
    const auto b = std::find(inBoxes.ids.begin(), inBoxes.ids.end(), pair.b) - inBoxes.ids.begin();
    if (a == static_cast<long>(inBoxes.size()) || b == static_cast<long>(inBoxes.size()))
      return "keys-only pair names an unknown id";
    // Keys from the origin 0 or from the frame's centre (used for frames far from 0).
    const bool keys_overlap = stress::keysOverlap(KeyOrigin(), inBoxes, a, b) ||
                              stress::keysOverlap(origin, inBoxes, a, b);
    if (!keys_overlap || !filtersAllow(inBoxes, a, b))
      return "keys-only extra pair (" + std::to_string(pair.a) + "," + std::to_string(pair.b) +
             ") does not even overlap in key space";
  }
  return "";
}

// What validate() should say, by the simplest possible means: a refusal and, for coordinate
// and duplicate-id problems, the box index it should name (the lowest index of a box with a
// bad coordinate or an id an earlier box has).
bool referenceRefusal(const BoxSet& inBoxes, std::size_t& outIndex, bool& outIndexKnown) {
  const std::size_t n = inBoxes.ids.size();
  outIndexKnown = false;
  if (inBoxes.bounds.size() != kBoundsPerBox * n) return true;
  if ((!inBoxes.groups.empty() && inBoxes.groups.size() != n) ||
      (!inBoxes.masks.empty() && inBoxes.masks.size() != n))
    return true;
  outIndexKnown = true;
  std::set<uint32_t> seen;
  for (std::size_t i = 0; i < n; ++i) {
    bool bad = !seen.insert(inBoxes.ids[i]).second;
    for (int axis = 0; axis < 3; ++axis) {
      const double low = inBoxes.lo(axis, i);
      const double high = inBoxes.hi(axis, i);
      bad = bad || std::isnan(low) || std::isnan(high) || low > high;
    }
    if (bad) {
      outIndex = i;
      return true;
    }
  }
  return false;
}

bool sameBits(double inA, double inB) {
  return std::memcmp(&inA, &inB, sizeof inA) == 0;
}

}  // namespace

int reportProblem(const char* inTarget, const std::string& inProblem) {
  if (inProblem.empty()) return 0;
  std::fprintf(stderr, "%s: %s\n", inTarget, inProblem.c_str());
  std::abort();
}

uint32_t ByteReader::u32() {
  uint32_t value = 0;
  for (int k = 0; k < 4; ++k) value = (value << 8) | byte();
  return value;
}

double ByteReader::f64() {
  uint64_t bits = 0;
  for (int k = 0; k < 8; ++k) bits = (bits << 8) | byte();
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

double decodeCoordinate(ByteReader& ioReader) {
  const uint8_t selector = ioReader.byte();
  if (selector < 64) return (static_cast<int>(selector) - 32) * 0.5;
  if (selector < 128) return kSpecials[(selector - 64) % kSpecialCount];
  if (selector < 192) {
    const uint8_t detail = ioReader.byte();
    return stepUlps(kSpecials[detail % kSpecialCount], static_cast<int>(selector % 7) - 3);
  }
  return ioReader.f64();
}

BoxSet smallGridBoxes(ByteReader& ioReader, uint32_t inCount) {
  BoxSet boxes;
  for (uint32_t i = 0; i < inCount; ++i) {
    // Braced lists are read left to right: the byte order of the corpora stays as it was.
    const double lo[3] = {static_cast<double>(ioReader.byte() % 16),
                          static_cast<double>(ioReader.byte() % 16),
                          static_cast<double>(ioReader.byte() % 16)};
    const double hi[3] = {lo[0] + ioReader.byte() % 4, lo[1] + ioReader.byte() % 4,
                          lo[2] + ioReader.byte() % 4};
    boxes.add(i, lo, hi);
  }
  return boxes;
}

std::optional<std::string> updateWithinMaxPairs(Broadphase& ioEngine, const BoxSet& inBoxes,
                                                const BroadphaseConfig& inConfig,
                                                const PairList& inExpected, PairList& outPairs) {
  try {
    outPairs = ioEngine.update(inBoxes);
  } catch (const TooManyPairs& refusal) {
    // Keys-only mode may report more pairs than the oracle's: any refusal may be due.
    if (inExpected.size() > inConfig.max_pairs || !inConfig.exact_final_test)
      return std::string("refused");
    return "refused " + std::to_string(inExpected.size()) + " pairs: " + refusal.what();
  }
  if (outPairs.size() > inConfig.max_pairs)
    return std::to_string(outPairs.size()) + " pairs answered past max_pairs " +
           std::to_string(inConfig.max_pairs);
  return std::nullopt;
}

std::string pairsDiffer(const char* inWhat, const PairList& inExpected, const PairList& inActual) {
  std::ostringstream text;
  text << inWhat << ": expected " << inExpected.size() << " pairs, got " << inActual.size();
  for (std::size_t k = 0; k < std::max(inExpected.size(), inActual.size()) && k < 4; ++k) {
    text << " [" << k << "] ";
    if (k < inExpected.size()) text << inExpected[k].a << "," << inExpected[k].b;
    text << " vs ";
    if (k < inActual.size()) text << inActual[k].a << "," << inActual[k].b;
  }
  return text.str();
}

BoxSet decodeBoxSet(const uint8_t* inData, std::size_t inSize, uint32_t& outVariant) {
  ByteReader reader(inData, inSize);
  const uint8_t flags = reader.byte();
  outVariant = reader.byte();
  BoxSet boxes;
  const bool with_groups = flags & 0x1;
  const bool with_masks = flags & 0x2;
  while (!reader.empty() && boxes.ids.size() < 4 * kMaxEngineBoxes) {
    const uint8_t id_byte = reader.byte();
    // Small ids collide often (duplicates); a set top bit reads a full 32-bit id.
    const uint32_t id = (id_byte & 0x80) ? reader.u32() : id_byte;
    boxes.ids.push_back(id);
    for (std::size_t k = 0; k < kBoundsPerBox; ++k)
      boxes.bounds.push_back(decodeCoordinate(reader));
    // Mostly valid intervals: swap a reversed pair unless the flags ask for raw ones.
    if (!(flags & 0x4)) {
      const std::size_t last = boxes.size() - 1;
      for (int axis = 0; axis < 3; ++axis) {
        double& low = boxes.lo(axis, last);
        double& high = boxes.hi(axis, last);
        if (low > high) std::swap(low, high);
      }
    }
    if (with_groups) boxes.groups.push_back(reader.byte() & 0x7);
    if (with_masks) {
      const uint8_t mask = reader.byte();
      boxes.masks.push_back(mask == 0xFF ? 0xFFFFFFFFu : (mask & 0x7));
    }
  }
  // Broken shapes on request: one array one entry short (the bounds: the last box's min or
  // max on one axis missing).
  if ((flags & 0x38) == 0x38 && !boxes.ids.empty()) {
    const auto lastBox = boxes.bounds.end() - kBoundsPerBox;
    switch (flags >> 6) {
      case 0:
        boxes.bounds.erase(lastBox + outVariant % 3);
        break;
      case 1:
        boxes.bounds.erase(lastBox + 3 + outVariant % 3);
        break;
      case 2:
        if (!boxes.groups.empty()) boxes.groups.pop_back();
        break;
      default:
        if (!boxes.masks.empty()) boxes.masks.pop_back();
        break;
    }
  }
  return boxes;
}

std::string checkEngine(const BoxSet& inBoxes, uint32_t inVariant) {
  static const Method kMethods[3] = {Method::kParallel, Method::kSequential, Method::kAuto};
  static const int kSlabs[4] = {0, 1, 7, 64};
  static const int kAxisPairs[6][2] = {{0, 1}, {1, 2}, {2, 0}, {1, 0}, {2, 1}, {0, 2}};
  const PairList oracle = bruteForcePairs(inBoxes);
  BroadphaseConfig config;
  config.method = kMethods[inVariant % 3];
  config.threads = 1 + static_cast<int>((inVariant / 3) % 3);
  config.third_axis_slabs = kSlabs[(inVariant / 9) % 4];
  config.primary_axis = kAxisPairs[(inVariant / 36) % 6][0];
  config.secondary_axis = kAxisPairs[(inVariant / 36) % 6][1];
  config.parallel_min_boxes = 1 + inVariant % 7;  // kAuto goes parallel on tiny frames too
  Broadphase engine(config);
  if (engine.update(stress::reversedOrder(inBoxes)) != oracle)
    return pairsDiffer("engine, reversed frame", oracle,
                       engine.update(stress::reversedOrder(inBoxes)));
  if (engine.update(inBoxes) != oracle)
    return pairsDiffer("engine, second frame", oracle, engine.update(inBoxes));
  if (engine.update(inBoxes) != oracle)
    return pairsDiffer("engine, unchanged frame", oracle, engine.update(inBoxes));

  config.exact_final_test = false;
  Broadphase keys_only(config);
  return checkSuperset(inBoxes, oracle, keys_only.update(inBoxes));
}

std::string checkTextInput(const uint8_t* inData, std::size_t inSize) {
  const std::string text(reinterpret_cast<const char*>(inData), inSize);
  std::istringstream input(text);
  BoxSet boxes;
  if (auto error = readBoxText(input, "fuzz", boxes)) {
    const std::size_t lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    if (error->reason.empty()) return "refusal without a reason";
    if (error->line == 0 || error->line > lines + 1)
      return "refusal names line " + std::to_string(error->line) + " of " +
             std::to_string(lines + 1);
    if (boxes.size() != 0) return "refusal left boxes behind";
    return "";
  }
  if (auto invalid = validate(boxes))
    return "parser accepted what validate() refuses: " + invalid->message();
  std::ostringstream written;
  writeBoxText(written, boxes);
  std::istringstream reread_input(written.str());
  BoxSet reread;
  if (auto error = readBoxText(reread_input, "rewritten", reread))
    return "writeBoxText output refused: " + error->message();
  if (reread.ids != boxes.ids) return "ids changed in the round trip";
  for (std::size_t k = 0; k < boxes.bounds.size(); ++k)
    if (!sameBits(boxes.bounds[k], reread.bounds[k]))
      return "coordinate of box " + std::to_string(k / kBoundsPerBox) +
             " changed in the round trip";
  if (boxes.size() > kMaxEngineBoxes) return "";
  return checkEngine(boxes, static_cast<uint32_t>(inSize));
}

std::string checkBoxSetBytes(const uint8_t* inData, std::size_t inSize) {
  uint32_t variant = 0;
  BoxSet boxes = decodeBoxSet(inData, inSize, variant);
  std::size_t expected_index = 0;
  bool index_known = false;
  const bool should_refuse = referenceRefusal(boxes, expected_index, index_known);
  const auto error = validate(boxes);
  if (should_refuse != error.has_value())
    return should_refuse ? "validate() accepted a broken set"
                         : "validate() refused a valid set: " + error->message();
  if (error) {
    if (error->reason.empty()) return "refusal without a reason";
    if (index_known && error->index != expected_index)
      return "validate() named box " + std::to_string(error->index) + ", the first bad one is " +
             std::to_string(expected_index) + ": " + error->message();
    return "";
  }
  if (boxes.size() > kMaxEngineBoxes) return "";
  return checkEngine(boxes, variant);
}

}  // namespace sap_broadphase::fuzz
