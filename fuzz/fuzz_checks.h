// The properties the fuzzers check, as plain functions shared by the libFuzzer targets and the
// GoogleTest replay of their corpora (test/stress/test_fuzz_replay.cpp). Each returns an empty
// string when every property holds, else what went wrong. No ROS here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/config.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase::fuzz {

/// What every libFuzzer target does with its check's answer: nothing when it is empty, else
/// print it after inTarget's name and abort, the crash libFuzzer records with its input.
/// Returns 0, the value LLVMFuzzerTestOneInput must return.
int reportProblem(const char* inTarget, const std::string& inProblem);

/// Most boxes a fuzz input is run through the engine with (the oracle is O(n^2)).
constexpr std::size_t kMaxEngineBoxes = 256;

/// Bytes as a text file for readBoxText: a refusal must name a line and leave no boxes; an
/// accepted file must pass validate(), survive writeBoxText/readBoxText bit for bit, and (up
/// to kMaxEngineBoxes boxes) give the oracle's pairs in the engine.
std::string checkTextInput(const uint8_t* inData, std::size_t inSize);

/// Bytes decoded into a raw BoxSet (special values, NaN, duplicate ids, bad array lengths
/// possible): validate() must not crash and must refuse exactly the broken sets (checked
/// against a simple re-implementation); accepted sets must give the oracle's pairs.
std::string checkBoxSetBytes(const uint8_t* inData, std::size_t inSize);

/// The engine on inBoxes (valid) in the configuration inVariant selects, plus the sequential
/// path and the keys-only mode, against bruteForcePairs. Frames: reversed, as given, again.
std::string checkEngine(const BoxSet& inBoxes, uint32_t inVariant);

/// Decodes inData into boxes the way checkBoxSetBytes does (exposed for the ROS target).
/// outVariant receives the configuration selector.
BoxSet decodeBoxSet(const uint8_t* inData, std::size_t inSize, uint32_t& outVariant);

/// Reads bytes front to back; past the end it yields zeros.
class ByteReader {
 public:
  ByteReader(const uint8_t* inData, std::size_t inSize) : data_(inData), size_(inSize) {}
  bool empty() const { return used_ >= size_; }
  uint8_t byte() { return used_ < size_ ? data_[used_++] : 0; }
  uint32_t u32();
  double f64();

 private:
  const uint8_t* data_;
  std::size_t size_;
  std::size_t used_ = 0;
};

/// One coordinate: a small half-integer, a special value (NaN and the infinities among them),
/// a special value moved a few ulps, or raw bits.
double decodeCoordinate(ByteReader& ioReader);

/// inCount boxes with ids 0..inCount-1 on a small integer grid, so that many of them overlap:
/// each corner in [0, 16), each edge in [0, 4), read from ioReader (six bytes a box, zeros past
/// its end). The small random frame the settings and reconfigure targets run the engine on.
BoxSet smallGridBoxes(ByteReader& ioReader, uint32_t inCount);

/// inEngine's update() of inBoxes into outPairs, against the bound of inConfig.max_pairs:
/// nothing when the frame was answered within it; "refused" when it threw TooManyPairs and had
/// to (inExpected, the oracle's pairs, or in keys-only mode the superset, pass the bound);
/// else what went wrong.
std::optional<std::string> updateWithinMaxPairs(Broadphase& ioEngine, const BoxSet& inBoxes,
                                                const BroadphaseConfig& inConfig,
                                                const PairList& inExpected, PairList& outPairs);

/// "what: expected 3 pairs, got 4 [0] 1,2 vs 1,2 ..." for a failed comparison.
std::string pairsDiffer(const char* inWhat, const PairList& inExpected, const PairList& inActual);

}  // namespace sap_broadphase::fuzz
