#include "settings_checks.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

#include "fuzz_checks.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/config.h"

namespace sap_broadphase::fuzz {
namespace {

/// A value of any kind a front end carries: dynamic_reconfigure's int32 and double, rosparam's
/// XML-RPC types, Python's int, float, str and bool.
ConfigValue decodeValue(ByteReader& ioReader) {
  switch (ioReader.byte() % 5) {
    case 0:
      return ConfigValue(static_cast<bool>(ioReader.byte() & 1));
    case 1: {
      const uint64_t high = ioReader.u32();
      return ConfigValue(static_cast<int64_t>(high << 32 | ioReader.u32()));
    }
    case 2:
      return ConfigValue(static_cast<int64_t>(static_cast<int8_t>(ioReader.byte())));
    case 3:
      return ConfigValue(ioReader.f64());
    default: {
      std::string text;
      const std::size_t length = ioReader.byte() % 24;
      for (std::size_t i = 0; i < length; ++i) text += static_cast<char>(ioReader.byte());
      return ConfigValue(text);
    }
  }
}

bool isRanged(const ConfigField& inField) {
  return inField.type == ConfigFieldType::kInteger || inField.type == ConfigFieldType::kNumber;
}

// One field, one value: refused untouched, or accepted within the row.
std::string checkOneField(ByteReader& ioReader) {
  const ConfigField& field = configFields()[ioReader.byte() % configFields().size()];
  const ConfigValue value = decodeValue(ioReader);
  BroadphaseConfig config;
  const auto problem = field.set(config, value);
  const std::string what = std::string(field.name) + " " + valueText(value);
  if (problem) {
    if (!sameConfig(config, BroadphaseConfig{})) return what + ": refused but changed";
    if (problem->rfind(std::string(field.name) + " must be", 0) != 0)
      return what + ": refusal does not name the field: " + *problem;
    return "";
  }
  const ConfigValue stored = field.get(config);
  if (isRanged(field)) {
    const double number = std::holds_alternative<int64_t>(stored)
                              ? static_cast<double>(std::get<int64_t>(stored))
                              : std::get<double>(stored);
    if (!(number >= field.min && number <= field.max)) return what + ": accepted out of range";
  }
  BroadphaseConfig again;
  if (field.set(again, stored)) return what + ": the stored value does not read back";
  const auto rules = configProblem(config);
  if (rules && rules->find("must differ") == std::string::npos)
    return what + ": accepted, then configProblem says " + *rules;
  return "";
}

// Every field in turn, as a reconfigure request carries them; a valid result runs.
std::string checkRequest(ByteReader& ioReader) {
  BroadphaseConfig config;
  for (const ConfigField& field : configFields()) {
    const BroadphaseConfig before = config;
    if (field.set(config, decodeValue(ioReader)) && !sameConfig(config, before))
      return std::string(field.name) + ": refused but changed";
  }
  if (configProblem(config)) return "";
  config.threads = std::min(config.threads, 2);  // the fuzzer's own cores, not the cap's
  const BoxSet boxes = smallGridBoxes(ioReader, 40);
  try {
    Broadphase engine(config);
    const PairList expected = bruteForcePairs(boxes);
    for (int frame = 0; frame < 2; ++frame) {
      PairList pairs;
      if (auto refusal = updateWithinMaxPairs(engine, boxes, config, expected, pairs))
        return *refusal == "refused" ? "" : *refusal;
      if (config.exact_final_test) {
        if (pairs != expected) return pairsDiffer(describeConfig(config).c_str(), expected, pairs);
      } else if (!std::includes(pairs.begin(), pairs.end(), expected.begin(), expected.end())) {
        return "keys-only misses a pair: " + describeConfig(config);
      }
    }
  } catch (const std::exception& error) {
    return "a valid config threw: " + describeConfig(config) + ": " + error.what();
  }
  return "";
}

// A row of the limits table: refused exactly outside its range.
std::string checkLimitRow(ByteReader& ioReader) {
  const Limit& limit = limits()[ioReader.byte() % limits().size()];
  const double value = ioReader.f64();
  if (!(limit.max > limit.min)) return "";  // not a number (method, axes, switches)
  const bool inside =
      (value >= limit.min && value <= limit.max) || (limit.zero_allowed && value == 0.0);
  const auto problem = limitProblem(limit, value);
  if (inside == static_cast<bool>(problem))
    return std::string(limit.entry) + " " + limit.name + " " + valueText(ConfigValue(value)) +
           (inside ? ": refused inside its range" : ": accepted outside its range");
  return "";
}

}  // namespace

std::string checkSettingsInput(const uint8_t* inData, std::size_t inSize) {
  ByteReader reader(inData, inSize);
  switch (reader.byte() % 3) {
    case 0:
      return checkOneField(reader);
    case 1:
      return checkRequest(reader);
    default:
      return checkLimitRow(reader);
  }
}

}  // namespace sap_broadphase::fuzz
