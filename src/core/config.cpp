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
  if (skin && !(*skin >= 0.0 && std::isfinite(*skin))) return std::nullopt;
  return skin;
}

// The one wording of a refused value.
std::string refusal(const ConfigField& inField, const ConfigValue& inValue) {
  return std::string(inField.name) + " must be " + inField.allowed + ", not " + valueText(inValue);
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
      {"threads", ConfigFieldType::kInteger, "0", 0.0, kLargestInt,
       "an integer >= 0 (0 = all cores)",
       "worker threads; 0 = all cores, or one where one is measured faster (method auto)",
       getInteger<&C::threads>, setInteger<&C::threads>},
      {"method", ConfigFieldType::kMethod, "auto", 0.0, 0.0, "auto, parallel, sequential or brute",
       "auto: one thread below parallel_min_boxes boxes or with one thread, else parallel; brute: "
       "every pair tested (the oracle)",
       getMethod, setMethod},
      {"primary_axis", ConfigFieldType::kAxis, "x", 0.0, 2.0, "x, y or z (or 0, 1, 2)",
       "first sweep axis", getAxis<&C::primary_axis>, setAxis<&C::primary_axis>},
      {"secondary_axis", ConfigFieldType::kAxis, "y", 0.0, 2.0, "x, y or z (or 0, 1, 2)",
       "second sweep axis; must differ from primary_axis", getAxis<&C::secondary_axis>,
       setAxis<&C::secondary_axis>},
      {"axis_swapping", ConfigFieldType::kBool, "true", 0.0, 1.0, "true or false",
       "swap a clustered sweep axis with the unused one (section 5 of the paper)",
       getBool<&C::axis_swapping>, setBool<&C::axis_swapping>},
      {"axis_swap_threshold", ConfigFieldType::kNumber, "0.25", 0.0, kInfinity, "a number >= 0",
       "dispersion D above which a sweep axis is swapped", getNumber<&C::axis_swap_threshold>,
       setNumber<&C::axis_swap_threshold>},
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
       getInteger<&C::parallel_min_boxes>, setInteger<&C::parallel_min_boxes>},
      {"third_axis_slabs", ConfigFieldType::kInteger, "0", 0.0,
       static_cast<double>(kMaxThirdAxisSlabs), "an integer in 0..64 (0 = auto)",
       "active lists per slab of the unused axis: 0 = auto, 1 = the paper's single list",
       getInteger<&C::third_axis_slabs>, setInteger<&C::third_axis_slabs>},
      {"reuse_unchanged_frames", ConfigFieldType::kBool, "true", 0.0, 1.0, "true or false",
       "a frame bit for bit equal to the previous one returns its pairs",
       getBool<&C::reuse_unchanged_frames>, setBool<&C::reuse_unchanged_frames>},
      {"skin", ConfigFieldType::kSkin, "auto", 0.0, kInfinity,
       "auto, off (or 0) or a finite skin >= 0 in the boxes' units",
       "kept candidates: sweep boxes grown by skin / 2 a side; auto chooses it from the motion",
       getSkin, setSkin},
      {"exact_final_test", ConfigFieldType::kBool, "true", 0.0, 1.0, "true or false",
       "false: report pairs whose float32 keys overlap (faster, may report extra pairs)",
       getBool<&C::exact_final_test>, setBool<&C::exact_final_test>},
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

}  // namespace sap_broadphase
