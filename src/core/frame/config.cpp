// The configuration table (config.h): one row per field, and the checks, texts and
// comparisons that walk it.
#include "sap_broadphase/core/config.h"

#include <omp.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <type_traits>

namespace sap_broadphase {

const char* methodName(Method inMethod) {
  switch (inMethod) {
    case Method::kAuto:
      return "auto";
    case Method::kParallel:
      return "parallel";
    case Method::kSequential:
      return "sequential";
    case Method::kBruteForce:
      return "brute";
  }
  return "unknown";
}

std::optional<Method> parseMethod(const std::string& inName) {
  for (Method method : kMethods)
    if (inName == methodName(method)) return method;
  if (inName == "sap") return Method::kAuto;
  return std::nullopt;
}

std::string methodList(const std::vector<Method>& inMethods, const char* (*inName)(Method)) {
  std::string text;
  for (std::size_t i = 0; i < inMethods.size(); ++i) {
    if (i > 0) text += i + 1 == inMethods.size() ? " or " : ", ";
    text += inName(inMethods[i]);
  }
  return text;
}

const char* axisName(int inAxis) {
  static const char* const kNames[3] = {"x", "y", "z"};
  return inAxis >= 0 && inAxis < 3 ? kNames[inAxis] : "?";
}

std::optional<int> parseAxis(const std::string& inText) {
  if (inText.size() != 1) return std::nullopt;
  const char letter = static_cast<char>(std::tolower(static_cast<unsigned char>(inText[0])));
  if (letter >= 'x' && letter <= 'z') return letter - 'x';
  if (letter >= '0' && letter <= '2') return letter - '0';
  return std::nullopt;
}

std::string skinToText(const std::optional<double>& inSkin) {
  if (!inSkin) return "auto";
  if (*inSkin == 0.0) return "off";
  for (int digits = 6; digits < 17; ++digits) {
    std::ostringstream text;
    text.precision(digits);
    text << *inSkin;
    if (std::strtod(text.str().c_str(), nullptr) == *inSkin) return text.str();
  }
  std::ostringstream text;
  text.precision(17);
  text << *inSkin;
  return text.str();
}

bool skinFromText(const std::string& inText, std::optional<double>& outSkin) {
  if (inText.empty() || inText == "auto") {
    outSkin.reset();
    return true;
  }
  if (inText == "off") {
    outSkin = 0.0;
    return true;
  }
  char* end = nullptr;
  const double value = std::strtod(inText.c_str(), &end);
  if (end == inText.c_str() || *end != '\0') return false;
  outSkin = value;
  return true;
}

std::string valueText(const ConfigValue& inValue) {
  if (const bool* flag = std::get_if<bool>(&inValue)) return *flag ? "true" : "false";
  if (const int64_t* integer = std::get_if<int64_t>(&inValue)) return std::to_string(*integer);
  if (const std::string* text = std::get_if<std::string>(&inValue)) return *text;
  std::ostringstream text;
  text.precision(17);
  text << std::get<double>(inValue);
  // The shortest form that reads back as the same double ("0.25", not "0.25000000000000000").
  for (int digits = 1; digits < 17; ++digits) {
    std::ostringstream shorter;
    shorter.precision(digits);
    shorter << std::get<double>(inValue);
    if (std::strtod(shorter.str().c_str(), nullptr) == std::get<double>(inValue))
      return shorter.str();
  }
  return text.str();
}

namespace {

// ---- Reading a ConfigValue as the type a field wants ----

std::optional<bool> asBool(const ConfigValue& inValue) {
  if (const bool* flag = std::get_if<bool>(&inValue)) return *flag;
  return std::nullopt;
}

std::optional<double> asNumber(const ConfigValue& inValue) {
  if (const double* number = std::get_if<double>(&inValue)) return *number;
  if (const int64_t* integer = std::get_if<int64_t>(&inValue)) return static_cast<double>(*integer);
  return std::nullopt;
}

std::optional<int64_t> asInteger(const ConfigValue& inValue) {
  if (const int64_t* integer = std::get_if<int64_t>(&inValue)) return *integer;
  if (const double* number = std::get_if<double>(&inValue))
    if (std::isfinite(*number) && std::trunc(*number) == *number && std::fabs(*number) < 9.0e15)
      return static_cast<int64_t>(*number);
  return std::nullopt;
}

std::optional<std::string> asText(const ConfigValue& inValue) {
  if (const std::string* text = std::get_if<std::string>(&inValue)) return *text;
  return std::nullopt;
}

std::optional<int> asAxis(const ConfigValue& inValue) {
  if (const auto text = asText(inValue)) return parseAxis(*text);
  if (const auto integer = asInteger(inValue))
    if (*integer >= 0 && *integer <= 2) return static_cast<int>(*integer);
  return std::nullopt;
}

std::optional<std::optional<double>> asSkin(const ConfigValue& inValue) {
  std::optional<double> skin;
  if (const auto text = asText(inValue)) {
    if (!skinFromText(*text, skin)) return std::nullopt;
  } else if (const auto number = asNumber(inValue)) {
    skin = *number;
  } else {
    return std::nullopt;
  }
  if (skin && !(*skin >= 0.0 && *skin <= kMaxSkin)) return std::nullopt;
  return skin;
}

// The one wording of a refused value. A bound that depends on the machine (threads) is
// named as it is here.
std::string refusal(const ConfigField& inField, const ConfigValue& inValue) {
  std::string text =
      std::string(inField.name) + " must be " + inField.allowed + ", not " + valueText(inValue);
  if (std::string(inField.name) == "threads")
    text += " (at most " + std::to_string(maxThreads()) + " on this machine)";
  return text;
}

bool inRange(const ConfigField& inField, double inValue) {
  return inValue >= inField.min && inValue <= inField.max;
}

// ---- The fields' accessors: one get and one set per member, by kind ----
// A setter finds its own row (for the name, range and wording) through its getter.

template <typename Getter>
const ConfigField& rowOf(Getter inGetter) {
  for (const ConfigField& field : configFields())
    if (field.get == inGetter) return field;
  return configFields().front();  // unreachable: every getter has its row
}

template <auto kMember>
ConfigValue getBool(const BroadphaseConfig& inConfig) {
  return inConfig.*kMember;
}
template <auto kMember>
std::optional<std::string> setBool(BroadphaseConfig& ioConfig, const ConfigValue& inValue) {
  const auto value = asBool(inValue);
  if (!value) return refusal(rowOf(&getBool<kMember>), inValue);
  ioConfig.*kMember = *value;
  return std::nullopt;
}

template <auto kMember>
ConfigValue getInteger(const BroadphaseConfig& inConfig) {
  return static_cast<int64_t>(inConfig.*kMember);
}
template <auto kMember>
std::optional<std::string> setInteger(BroadphaseConfig& ioConfig, const ConfigValue& inValue) {
  const ConfigField& field = rowOf(&getInteger<kMember>);
  const auto value = asInteger(inValue);
  if (!value || !inRange(field, static_cast<double>(*value))) return refusal(field, inValue);
  using Member = std::remove_reference_t<decltype(ioConfig.*kMember)>;
  ioConfig.*kMember = static_cast<Member>(*value);
  return std::nullopt;
}

template <auto kMember>
ConfigValue getNumber(const BroadphaseConfig& inConfig) {
  return inConfig.*kMember;
}
template <auto kMember>
std::optional<std::string> setNumber(BroadphaseConfig& ioConfig, const ConfigValue& inValue) {
  const ConfigField& field = rowOf(&getNumber<kMember>);
  const auto value = asNumber(inValue);
  if (!value || !inRange(field, *value)) return refusal(field, inValue);
  ioConfig.*kMember = *value;
  return std::nullopt;
}

template <auto kMember>
ConfigValue getAxis(const BroadphaseConfig& inConfig) {
  const int axis = inConfig.*kMember;
  return axis >= 0 && axis <= 2 ? std::string(axisName(axis)) : std::to_string(axis);
}
template <auto kMember>
std::optional<std::string> setAxis(BroadphaseConfig& ioConfig, const ConfigValue& inValue) {
  const auto value = asAxis(inValue);
  if (!value) return refusal(rowOf(&getAxis<kMember>), inValue);
  ioConfig.*kMember = *value;
  return std::nullopt;
}

ConfigValue getMethod(const BroadphaseConfig& inConfig) {
  return std::string(methodName(inConfig.method));
}
std::optional<std::string> setMethod(BroadphaseConfig& ioConfig, const ConfigValue& inValue) {
  const auto text = asText(inValue);
  const auto method = text ? parseMethod(*text) : std::nullopt;
  if (!method) return refusal(rowOf(&getMethod), inValue);
  ioConfig.method = *method;
  return std::nullopt;
}

ConfigValue getSkin(const BroadphaseConfig& inConfig) {
  return skinToText(inConfig.skin);
}
std::optional<std::string> setSkin(BroadphaseConfig& ioConfig, const ConfigValue& inValue) {
  const auto skin = asSkin(inValue);
  if (!skin) return refusal(rowOf(&getSkin), inValue);
  ioConfig.skin = *skin;
  return std::nullopt;
}

using C = BroadphaseConfig;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kLargestInt = std::numeric_limits<int>::max();
// Counts of boxes: any size_t a double holds exactly.
constexpr double kLargestCount = 9007199254740992.0;

std::vector<ConfigField> makeConfigFields() {
  return {
      {"threads", ConfigFieldType::kInteger, "0", 0.0, static_cast<double>(maxThreads()),
       "an integer from 0 to 4 a processor (0 = all cores)",
       "worker threads; 0 = all cores (one for a frame below parallel_min_boxes, method auto)",
       "at most 4 a processor (kMaxThreadsPerProcessor x omp_get_num_procs): more only wait at "
       "the sweep's barriers, and OpenMP starts every one (999 on 2 cores: 110 s a frame; "
       "100000: no address space left)",
       getInteger<&C::threads>, setInteger<&C::threads>},
      {"method", ConfigFieldType::kMethod, "auto", 0.0, 0.0, "auto, parallel, sequential or brute",
       "auto: one thread below parallel_min_boxes boxes; the small-frame kernel (no fixed skin) at "
       "any size on up to 2 threads, else the sweep (parallel from parallel_min_boxes boxes); "
       "brute: "
       "every pair tested (the oracle)",
       "the engine's methods", getMethod, setMethod},
      {"primary_axis", ConfigFieldType::kAxis, "x", 0.0, 2.0, "x, y or z (or 0, 1, 2)",
       "first sweep axis", "three axes", getAxis<&C::primary_axis>, setAxis<&C::primary_axis>},
      {"secondary_axis", ConfigFieldType::kAxis, "y", 0.0, 2.0, "x, y or z (or 0, 1, 2)",
       "second sweep axis; must differ from primary_axis", "three axes",
       getAxis<&C::secondary_axis>, setAxis<&C::secondary_axis>},
      {"axis_swapping", ConfigFieldType::kBool, "true", 0.0, 1.0, "true or false",
       "swap a clustered sweep axis with the unused one (section 5 of the paper)", "a switch",
       getBool<&C::axis_swapping>, setBool<&C::axis_swapping>},
      {"axis_swap_threshold", ConfigFieldType::kNumber, "0.25", 0.0, kInfinity, "a number >= 0",
       "dispersion D above which a sweep axis is swapped",
       "D is >= 0; +inf never swaps; NaN and negatives mean nothing",
       getNumber<&C::axis_swap_threshold>, setNumber<&C::axis_swap_threshold>},
      // The one cut-off of method auto. Measured against the one-thread engine with
      // sap_microbench's BM_SmallFrame (uniform scenes, CPU time of one thread): the small
      // frame stays ahead up to 2^15 boxes at density 0.35 and beyond 2^16 at 0.05. Against the
      // parallel engine on two threads with `sap_bench -e skips` (uniform, density 0.2, every
      // frame swept, 2 cores idle): it leads 2.04x at 2^13, 1.53x at 2^14 and 1.15x at 2^15
      // and trails from 2^16. Since the kernel keeps candidates under a skin too, a steady
      // frame of 2^14 boxes costs it 0.32 ms on one thread against 0.42 ms for the parallel
      // sweep on two, and a first frame 0.99 against 2.1 ms; with another process on the
      // second core a two-thread frame of 2^14 boxes waited 30-130 ms for it (the closing
      // barrier of each OpenMP region), one thread none. 2^15 (where two threads still win
      // the steady state on an idle machine, 0.50 against 0.68 ms) keeps 2^14 frames on one.
      {"parallel_min_boxes", ConfigFieldType::kInteger, "32768", 0.0, kLargestCount,
       "an integer >= 0",
       "method auto: frames below this many boxes run on one thread (the small-frame path, or "
       "the sequential sweep under a fixed skin)",
       "a count of boxes (2^53: every count a double holds exactly)",
       getInteger<&C::parallel_min_boxes>, setInteger<&C::parallel_min_boxes>},
      {"third_axis_slabs", ConfigFieldType::kInteger, "0", 0.0,
       static_cast<double>(kMaxThirdAxisSlabs), "an integer in 0..64 (0 = auto)",
       "active lists per slab of the unused axis: 0 = auto, 1 = the paper's single list",
       "slab numbers are stored in 8 bits, and more slabs cost inserts for large boxes",
       getInteger<&C::third_axis_slabs>, setInteger<&C::third_axis_slabs>},
      {"reuse_unchanged_frames", ConfigFieldType::kBool, "true", 0.0, 1.0, "true or false",
       "a frame bit for bit equal to the previous one returns its pairs", "a switch",
       getBool<&C::reuse_unchanged_frames>, setBool<&C::reuse_unchanged_frames>},
      {"skin", ConfigFieldType::kSkin, "auto", 0.0, kMaxSkin,
       "auto, off (or 0) or a skin in 0..3e38 in the boxes' units",
       "kept candidates: sweep boxes grown by skin / 2 a side; auto chooses it from the motion",
       "grown keys are float32 (3e38 is below their largest); what a skin may cost in kept "
       "candidates is the engine's budget (kMaxKeptCandidatesPerBox), past which it sweeps "
       "plainly",
       getSkin, setSkin},
      {"exact_final_test", ConfigFieldType::kBool, "true", 0.0, 1.0, "true or false",
       "false: report pairs whose float32 keys overlap (faster, may report extra pairs)",
       "a switch", getBool<&C::exact_final_test>, setBool<&C::exact_final_test>},
      {"max_pairs", ConfigFieldType::kInteger, "268435456", 1.0, kLargestCount, "an integer >= 1",
       "most pairs a frame may have: a frame with more is refused (TooManyPairs), its pairs "
       "dropped",
       "8 bytes a pair in each list a frame holds (the threads', the sorted one, the last "
       "frame's, a PairArray): 2^28 (the default) is 2 GiB a list; the sweeps stop once past it "
       "instead of growing until memory runs out",
       getInteger<&C::max_pairs>, setInteger<&C::max_pairs>},
  };
}

}  // namespace

const std::vector<ConfigField>& configFields() {
  static const std::vector<ConfigField> fields = makeConfigFields();
  return fields;
}

const ConfigField* findConfigField(const std::string& inName) {
  for (const ConfigField& field : configFields())
    if (inName == field.name) return &field;
  return nullptr;
}

std::string describeConfig(const BroadphaseConfig& inConfig) {
  std::string text;
  for (const ConfigField& field : configFields()) {
    if (!text.empty()) text += ", ";
    text += std::string(field.name) + " " + valueText(field.get(inConfig));
  }
  return text;
}

bool sameConfig(const BroadphaseConfig& inA, const BroadphaseConfig& inB) {
  for (const ConfigField& field : configFields())
    if (field.get(inA) != field.get(inB)) return false;
  return true;
}

int maxThreads() {
  return kMaxThreadsPerProcessor * std::max(1, omp_get_num_procs());
}

int resolveThreadCount(int inRequested) {
  return inRequested > 0 ? inRequested : std::max(1, omp_get_max_threads());
}

std::optional<std::string> configProblem(const BroadphaseConfig& inConfig) {
  // Every field is checked by storing its own value again: set() holds the field's rule.
  for (const ConfigField& field : configFields()) {
    BroadphaseConfig scratch = inConfig;
    if (auto problem = field.set(scratch, field.get(inConfig))) return problem;
  }
  if (inConfig.primary_axis == inConfig.secondary_axis)
    return std::string("primary_axis and secondary_axis must differ, not both ") +
           axisName(inConfig.primary_axis);
  return std::nullopt;
}

// ---- The limits table ----

namespace {

constexpr const char* kEngineEntry = "engine setting";
constexpr const char* kNodeEntry = "node parameter";
constexpr const char* kReconfigureEntry = "dynamic_reconfigure";
constexpr const char* kTextEntry = "box text reader";
constexpr const char* kMessageEntry = "topics and services";

constexpr const char* kEngineViolation =
    "start-up: FATAL, exit 1; reconfigure: refused, the old value returned; Python: ValueError; "
    "C++: std::invalid_argument";
constexpr const char* kNodeViolation = "FATAL naming it at start-up, the node exits 1";
constexpr const char* kReconfigureViolation =
    "refused with a warning naming it; the returned config holds the settings in force";
constexpr const char* kScenePublisherEntry = "scene_publisher parameter";
constexpr const char* kScenePublisherViolation =
    "FATAL naming it at start-up, scene_publisher exits 1 (the nodelet publishes nothing)";
constexpr const char* kCliViolation = "exit 2, the flag and its range on stderr, nothing on stdout";

// ros::Duration keeps whole seconds in an int32: the longest span it holds.
constexpr double kLongestDuration = 2147483647.0;
constexpr double kLargestInt32 = 2147483647.0;
// The most boxes one BoxArray without ids carries under roscpp's 10^9-byte message limit.
constexpr double kMostBoxArrayBoxes = 20833333.0;

// The engine's fields as rows of the limits table.
void addEngineLimits(std::vector<Limit>& ioLimits) {
  for (const ConfigField& field : configFields()) {
    const bool ranged = field.type == ConfigFieldType::kInteger ||
                        field.type == ConfigFieldType::kNumber ||
                        field.type == ConfigFieldType::kSkin;
    ioLimits.push_back({kEngineEntry, field.name, ranged ? field.min : 0.0,
                        ranged ? field.max : 0.0, false, field.allowed, field.reason,
                        kEngineViolation});
  }
}

std::vector<Limit> makeLimits() {
  std::vector<Limit> rows;
  addEngineLimits(rows);
  const std::vector<Limit> others = {
      {kNodeEntry, "~rate", 1e-9, 1e6, true, "0 (a frame per delivery) or 1e-9..1e6 Hz",
       "the period 1 / rate is a ros::Duration (at most 2^31 - 1 s; below 4.7e-10 Hz roscpp "
       "aborts); above 1 MHz a timer only fires as fast as it can",
       kNodeViolation},
      {kNodeEntry, "~source_timeout", 0.0, kLongestDuration, false,
       "0 (never) or up to 2147483647 s", "a ros::Duration", kNodeViolation},
      {kNodeEntry, "~transform_timeout", 0.0, kLongestDuration, false, "0..2147483647 s",
       "a ros::Duration", kNodeViolation},
      {kNodeEntry, "~refusal_log_period", 0.0, kLongestDuration, false, "0..2147483647 s",
       "a ros::Duration", kNodeViolation},
      {kNodeEntry, "~boxes_queue_size", 1.0, 1000.0, false, "1..1000",
       "each queued message may hold a whole frame (up to 1 GB); 0 is roscpp's unbounded queue",
       kNodeViolation},
      {kNodeEntry, "~pairs_queue_size", 1.0, 1000.0, false, "1..1000",
       "each queued message holds a frame's pairs; 0 is roscpp's unbounded queue", kNodeViolation},
      {kNodeEntry, "~max_marker_boxes", 0.0, 1000000.0, false, "0..1000000",
       "a marker array of a million boxes is some 400 MB; rviz draws far fewer", kNodeViolation},
      {kNodeEntry, "~marker_line_width", 0.0, 1e6, false,
       "0 (10 % of the mean edge) or up to "
       "1e6 m",
       "a width in metres; NaN and infinity draw nothing", kNodeViolation},
      {kReconfigureEntry, "max_marker_boxes", 0.0, 1000000.0, false, "0..1000000",
       "as ~max_marker_boxes", kReconfigureViolation},
      {kReconfigureEntry, "marker_line_width", 0.0, 1e6, false,
       "0 (10 % of the mean edge) or up to 1e6 m", "as ~marker_line_width", kReconfigureViolation},
      {kScenePublisherEntry, "~n", 0.0, kMostBoxArrayBoxes, false, "an integer from 0 to 20833333",
       "a frame is one BoxArray, and roscpp refuses a message over 10^9 bytes (48 bytes a box "
       "without ids)",
       kScenePublisherViolation},
      {kScenePublisherEntry, "~density", std::numeric_limits<double>::denorm_min(),
       std::numeric_limits<double>::max(), false, "a finite number > 0",
       "a volume fraction; 0 has no box size", kScenePublisherViolation},
      {kScenePublisherEntry, "~rate", 1e-9, 1e6, false, "1e-9..1e6 Hz",
       "the period 1 / rate is slept as a duration; 0 has none", kScenePublisherViolation},
      {kScenePublisherEntry, "~seed", 0.0, kLargestInt32, false, "an integer from 0 to 2147483647",
       "the parameter server's integers are 32 bits; a negative seed names no seed",
       kScenePublisherViolation},
      {kScenePublisherEntry, "~plane_axis", 0.0, 2.0, false, "0, 1 or 2", "three axes",
       kScenePublisherViolation},
      {kScenePublisherEntry, "~scene_frames", 1.0, kLargestInt32, false, "an integer >= 1",
       "the motion is timed over this many frames", kScenePublisherViolation},
      {kScenePublisherEntry, "~speed", -std::numeric_limits<double>::max(),
       std::numeric_limits<double>::max(), false, "a finite number",
       "mean box edges a frame; NaN or infinity would move every box to NaN or infinity",
       kScenePublisherViolation},
      {kScenePublisherEntry, "~max_frames", 0.0, kLargestInt32, false,
       "0 (until shut down) or up to 2147483647", "an int count of frames",
       kScenePublisherViolation},
      {"sap_pairs, sap_pairs_mpi", "--threads", 1.0, static_cast<double>(maxThreads()), false,
       "an integer from 1 to 4 a processor", "as the engine's threads", kCliViolation},
      {"sap_pairs, sap_pairs_mpi", "--max-pairs", 1.0, kLargestCount, false,
       "an integer from 1 to 2^53", "as the engine's max_pairs", kCliViolation},
      {"sap_scene", "--n", 0.0, 2147483647.0, false, "an integer from 0 to 2147483647",
       "the engine's most boxes a frame (kMaxBoxes)", kCliViolation},
      {"sap_scene", "--density", std::numeric_limits<double>::denorm_min(),
       std::numeric_limits<double>::max(), false, "a finite number > 0",
       "a volume fraction; 0 has no box size", kCliViolation},
      {"sap_scene", "--frame", 0.0, kLargestInt32, false, "an integer >= 0", "an int frame index",
       kCliViolation},
      {"sap_scene", "--frames", 2.0, kLargestInt32, false, "an integer >= 2",
       "the motion is timed over at least two frames", kCliViolation},
      {kTextEntry, "line length", 0.0, static_cast<double>(kMaxTextLineBytes), false,
       "at most 1048576 bytes",
       "a box line is about 200 bytes; checked while reading, so an endless line "
       "(/dev/zero) is refused without being held",
       "FILE:LINE: refused, sap_pairs exits 2"},
      {"query_boxes, Broadphase.query", "hits of one query", 0.0,
       static_cast<double>(kMaxQueryHits), false, "at most 16777216 (2^24)",
       "each hit is 8 bytes found, 8 in the answer and 8 in the response (kMaxQueryHits); a "
       "frame scan stops once past it",
       "the query refused naming the count: query_boxes success false, C++ std::length_error, "
       "Python ValueError"},
      {kMessageEntry, "message length", 0.0, 1e9, false, "at most 10^9 bytes",
       "roscpp's own limit (20 833 333 boxes a BoxArray without ids); checked before anything "
       "is allocated",
       "refused by roscpp, the connection dropped, logged; the node stays up"},
  };
  rows.insert(rows.end(), others.begin(), others.end());
  return rows;
}

// A number as a message writes it: "1e-10", "999", "nan".
std::string numberText(double inValue) {
  return valueText(ConfigValue(inValue));
}

}  // namespace

const std::vector<Limit>& limits() {
  static const std::vector<Limit> rows = makeLimits();
  return rows;
}

const Limit* findLimit(const std::string& inEntry, const std::string& inName) {
  for (const Limit& limit : limits())
    if (inEntry == limit.entry && inName == limit.name) return &limit;
  return nullptr;
}

std::optional<std::string> limitProblem(const Limit& inLimit, double inValue) {
  if ((inLimit.zero_allowed && inValue == 0.0) ||
      (inValue >= inLimit.min && inValue <= inLimit.max))
    return std::nullopt;
  return std::string(inLimit.name) + " must be " + inLimit.allowed + ", not " + numberText(inValue);
}

std::string limitsMarkdown() {
  std::string text = "| Entry point | Name | Valid | Why | Out of range |\n|---|---|---|---|---|\n";
  for (const Limit& limit : limits())
    text += std::string("| ") + limit.entry + " | `" + limit.name + "` | " + limit.allowed + " | " +
            limit.reason + " | " + limit.violation + " |\n";
  return text;
}

}  // namespace sap_broadphase
