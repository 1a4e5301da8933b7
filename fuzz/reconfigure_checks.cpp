#include "reconfigure_checks.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <vector>

#include <dynamic_reconfigure/Config.h>

#include "fuzz_checks.h"
#include "node_params.h"
#include "sap_broadphase/BroadphaseNodeConfig.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/brute_force.h"

namespace sap_broadphase::fuzz {
namespace {

using Description = BroadphaseNodeConfig::AbstractParamDescriptionConstPtr;

const std::vector<Description>& descriptions() {
  return BroadphaseNodeConfig::__getParamDescriptions__();
}

/// Integers at the edges of the table's ranges and of int32.
const int kIntegers[] = {0,
                         1,
                         -1,
                         2,
                         63,
                         64,
                         65,
                         1000000,
                         1000001,
                         4096,
                         4097,
                         std::numeric_limits<int>::max(),
                         std::numeric_limits<int>::min()};
/// Numbers at the edges: the limits of skin, swap threshold and line width among them.
const double kNumbers[] = {0.0,
                           -0.0,
                           0.25,
                           1.0,
                           -1.0,
                           1e6,
                           1e6 + 1.0,
                           1e300,
                           HUGE_VAL,
                           -HUGE_VAL,
                           NAN,
                           std::numeric_limits<double>::denorm_min(),
                           std::numeric_limits<double>::max()};
/// Texts the string parameters (method, axes, skin) are given, good and bad.
const char* const kTexts[] = {
    "auto", "parallel", "sequential", "brute", "x",   "y",   "z",    "Z",    "w",    "",     "off",
    "0",    "0.05",     "-0.05",      "1e300", "inf", "nan", "0x10", "1e-5", " 0.1", "0.1 ", "X"};

template <typename T, std::size_t N>
T pick(ByteReader& ioReader, const T (&inChoices)[N]) {
  return inChoices[ioReader.byte() % N];
}

std::string decodeText(ByteReader& ioReader) {
  if (ioReader.byte() < 200) return pick(ioReader, kTexts);
  std::string text;
  const std::size_t length = ioReader.byte() % 12;
  for (std::size_t i = 0; i < length; ++i) text += static_cast<char>(ioReader.byte());
  return text;
}

/// One entry of a request: a parameter of the .cfg (or an unknown name), a value of its own
/// kind mostly, sometimes of another.
void addEntry(ByteReader& ioReader, dynamic_reconfigure::Config& ioRequest) {
  const uint8_t which = ioReader.byte();
  const std::string name =
      which == 255 ? "unknown" : descriptions()[which % descriptions().size()]->name;
  std::string type = descriptions()[which % descriptions().size()]->type;
  if (ioReader.byte() % 16 == 0) {
    const char* const kTypes[] = {"int", "double", "str", "bool"};
    type = pick(ioReader, kTypes);
  }
  if (type == "int") {
    dynamic_reconfigure::IntParameter entry;
    entry.name = name;
    entry.value =
        ioReader.byte() % 2 ? pick(ioReader, kIntegers) : static_cast<int>(ioReader.u32());
    ioRequest.ints.push_back(entry);
  } else if (type == "double") {
    dynamic_reconfigure::DoubleParameter entry;
    entry.name = name;
    entry.value = ioReader.byte() % 2 ? pick(ioReader, kNumbers) : ioReader.f64();
    ioRequest.doubles.push_back(entry);
  } else if (type == "str") {
    dynamic_reconfigure::StrParameter entry;
    entry.name = name;
    entry.value = decodeText(ioReader);
    ioRequest.strs.push_back(entry);
  } else {
    dynamic_reconfigure::BoolParameter entry;
    entry.name = name;
    entry.value = ioReader.byte() & 1;
    ioRequest.bools.push_back(entry);
  }
}

bool sameSettings(const NodeParams& inA, const NodeParams& inB) {
  return sameConfig(inA.engine, inB.engine) && sameMarkerSettings(inA, inB);
}

/// A refusal names a parameter of the .cfg.
bool namesAParameter(const std::string& inProblem) {
  return std::any_of(descriptions().begin(), descriptions().end(), [&](const Description& inD) {
    return inProblem.find(inD->name) != std::string::npos;
  });
}

/// Accepted settings: within the rules and rows, read back unchanged from what the server
/// reports to its clients.
std::string checkAccepted(const NodeParams& inSettings) {
  const std::string what = describeNodeParams(inSettings);
  if (const auto problem = configProblem(inSettings.engine))
    return "accepted, then configProblem says " + *problem + ": " + what;
  const double width = inSettings.markers.line_width;
  if (limitProblem(*findLimit("dynamic_reconfigure", "marker_line_width"), width) ||
      limitProblem(*findLimit("dynamic_reconfigure", "max_marker_boxes"),
                   static_cast<double>(inSettings.markers.max_boxes)))
    return "accepted marker settings outside the limits table: " + what;
  BroadphaseNodeConfig reported;
  toReconfigureConfig(inSettings, reported);
  NodeParams again = inSettings;
  const std::string problem = fromReconfigureConfig(reported, again);
  if (!problem.empty()) return "the settings reported back are refused: " + problem + ": " + what;
  if (!sameSettings(again, inSettings))
    return "the settings reported back read differently: " + what;
  return "";
}

/// The engine built from accepted settings on one small frame, against the oracle.
std::string checkEngineRuns(BroadphaseConfig inConfig, ByteReader& ioReader) {
  inConfig.threads = std::min(inConfig.threads, 2);  // the fuzzer's own cores, not the cap's
  const BoxSet boxes = smallGridBoxes(ioReader, 32);
  Broadphase engine(inConfig);
  const PairList expected = bruteForcePairs(boxes);
  PairList pairs;
  if (auto refusal = updateWithinMaxPairs(engine, boxes, inConfig, expected, pairs))
    return *refusal == "refused" ? "" : *refusal;
  if (inConfig.exact_final_test) {
    if (pairs != expected) return pairsDiffer(describeConfig(inConfig).c_str(), expected, pairs);
  } else if (!std::includes(pairs.begin(), pairs.end(), expected.begin(), expected.end())) {
    return "keys-only misses a pair: " + describeConfig(inConfig);
  }
  return "";
}

std::string checkRequests(ByteReader& ioReader) {
  NodeParams accepted;  // the node's defaults, as at start-up
  const int requests = 1 + ioReader.byte() % 3;
  for (int r = 0; r < requests; ++r) {
    dynamic_reconfigure::Config request;
    const std::size_t entries = ioReader.byte() % 8;
    for (std::size_t i = 0; i < entries; ++i) addEntry(ioReader, request);
    // dynamic_reconfigure's server: the request over the settings in force, then clamped to
    // the .cfg's bounds (which span each type, so that the node's check decides).
    BroadphaseNodeConfig config;
    toReconfigureConfig(accepted, config);
    config.__fromMessage__(request);
    config.__clamp__();
    NodeParams settings = accepted;
    const std::string problem = fromReconfigureConfig(config, settings);
    if (!problem.empty()) {
      if (!sameSettings(settings, accepted)) return "refused but changed: " + problem;
      if (!namesAParameter(problem)) return "refusal names no parameter: " + problem;
      continue;
    }
    const std::string wrong = checkAccepted(settings);
    if (!wrong.empty()) return wrong;
    accepted = settings;
  }
  return checkEngineRuns(accepted.engine, ioReader);
}

}  // namespace

std::string checkReconfigureInput(const uint8_t* inData, std::size_t inSize) {
  ByteReader reader(inData, inSize);
  try {
    return checkRequests(reader);
  } catch (const std::exception& error) {
    return std::string("exception: ") + error.what();
  }
}

}  // namespace sap_broadphase::fuzz
