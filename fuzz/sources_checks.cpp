#include "sources_checks.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <set>
#include <vector>

#include <xmlrpcpp/XmlRpcException.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include "adapters_sources.h"
#include "fuzz_checks.h"
#include "node_params.h"

namespace sap_broadphase::fuzz {
namespace {

using XmlRpc::XmlRpcValue;

/// The namespace the check resolves topics in, as the node resolves them in its own.
constexpr const char* kNamespace = "/ns/";

const char* const kKeys[] = {"topic", "type",    "id_offset", "group",
                             "mask",  "timeout", "ids",       "unknown"};

/// Texts that reach the parser's branches: topic names (one topic spelled two ways, the
/// scenery), type names, the ids values, numbers as text.
const char* const kTexts[] = {"boxes",
                              "/ns/boxes",
                              "static_boxes",
                              "/ns/static_boxes",
                              "",
                              "other",
                              "sap_broadphase/BoxArray",
                              "visualization_msgs/MarkerArray",
                              "vision_msgs/BoundingBox3DArray",
                              "vision_msgs/Detection3DArray",
                              "jsk_recognition_msgs/BoundingBoxArray",
                              "std_msgs/String",
                              "marker",
                              "first_seen",
                              "0xFFFFFFFD",
                              "4294967295",
                              "4294967296",
                              "-1",
                              "010",
                              "1e3"};

/// Numbers at the edges of the uint32 and seconds readers.
const double kNumbers[] = {0.0,          -0.0,         0.5,          1.0,          -1.0,
                           2147483647.0, 2147483648.0, 4294967295.0, 4294967296.0, 4294967294.5,
                           1e300,        -1e-300,      HUGE_VAL,     -HUGE_VAL,    NAN};

std::string decodeText(ByteReader& ioReader) {
  const uint8_t pick = ioReader.byte();
  if (pick < 200) return kTexts[pick % (sizeof kTexts / sizeof kTexts[0])];
  std::string text;
  const std::size_t length = ioReader.byte() % 12;
  for (std::size_t i = 0; i < length; ++i) text += static_cast<char>(ioReader.byte());
  return text;
}

XmlRpcValue decodeValue(ByteReader& ioReader, int inDepth);

XmlRpcValue decodeStruct(ByteReader& ioReader, int inDepth) {
  XmlRpcValue value;
  value.begin();  // an empty dict stays a dict
  const std::size_t members = ioReader.byte() % 6;
  for (std::size_t i = 0; i < members; ++i) {
    const std::string key = kKeys[ioReader.byte() % (sizeof kKeys / sizeof kKeys[0])];
    value[key] = decodeValue(ioReader, inDepth + 1);
  }
  return value;
}

XmlRpcValue decodeValue(ByteReader& ioReader, int inDepth) {
  switch (ioReader.byte() % (inDepth < 3 ? 9 : 7)) {
    case 0:
      return XmlRpcValue(static_cast<int>(ioReader.u32()));
    case 1:
      return XmlRpcValue(static_cast<int>(static_cast<int8_t>(ioReader.byte())));
    case 2:
      return XmlRpcValue(ioReader.f64());
    case 3:
      return XmlRpcValue(kNumbers[ioReader.byte() % (sizeof kNumbers / sizeof kNumbers[0])]);
    case 4:
    case 5:
      return XmlRpcValue(decodeText(ioReader));
    case 6:
      return XmlRpcValue(static_cast<bool>(ioReader.byte() & 1));
    case 7: {
      XmlRpcValue list;
      const int size = ioReader.byte() % 4;
      list.setSize(size);
      for (int i = 0; i < size; ++i) list[i] = decodeValue(ioReader, inDepth + 1);
      return list;
    }
    default:
      return decodeStruct(ioReader, inDepth);
  }
}

/// A ~sources list: mostly a list of topic names and dicts, sometimes any value.
XmlRpcValue decodeSources(ByteReader& ioReader) {
  if (ioReader.byte() % 16 == 0) return decodeValue(ioReader, 0);
  XmlRpcValue list;
  const int size = ioReader.byte() % 6;
  list.setSize(size);
  for (int i = 0; i < size; ++i) {
    const uint8_t kind = ioReader.byte() % 4;
    list[i] = kind == 0   ? XmlRpcValue(decodeText(ioReader))
              : kind == 3 ? decodeValue(ioReader, 1)
                          : decodeStruct(ioReader, 1);
  }
  return list;
}

/// The number an accepted id_offset, group or mask was given as (int, double or text).
double givenNumber(XmlRpcValue& inValue) {
  switch (inValue.getType()) {
    case XmlRpcValue::TypeInt:
      return static_cast<int>(inValue);
    case XmlRpcValue::TypeDouble:
      return static_cast<double>(inValue);
    case XmlRpcValue::TypeString: {
      errno = 0;
      return static_cast<double>(
          std::strtoull(static_cast<std::string&>(inValue).c_str(), nullptr, 0));
    }
    default:
      return NAN;
  }
}

/// An accepted entry against what it was given as: every key read back, nothing invented.
std::string checkEntry(XmlRpcValue& inEntry, const SourceSpec& inSpec, const std::string& inWhere) {
  if (inEntry.getType() == XmlRpcValue::TypeString) {
    if (inSpec.topic != static_cast<std::string&>(inEntry)) return inWhere + ": topic differs";
    if (inSpec.type != InputType::kBoxArray || !inSpec.takesBoxArrayAsIs() || inSpec.timeout ||
        inSpec.marker_ids)
      return inWhere + ": a bare topic got settings";
    return "";
  }
  if (inEntry.getType() != XmlRpcValue::TypeStruct) return inWhere + ": accepted a non-entry";
  for (auto it = inEntry.begin(); it != inEntry.end(); ++it)
    if (it->first == "unknown") return inWhere + ": accepted an unknown key";
  if (inSpec.topic != static_cast<std::string&>(inEntry["topic"])) return inWhere + ": topic";
  const InputType expected_type = inEntry.hasMember("type")
                                      ? inputTypeByName(static_cast<std::string&>(inEntry["type"]))
                                            .value_or(InputType::kBoxArray)
                                      : InputType::kBoxArray;
  if (inSpec.type != expected_type) return inWhere + ": type differs";
  const double offset = inEntry.hasMember("id_offset") ? givenNumber(inEntry["id_offset"]) : 0.0;
  if (static_cast<double>(inSpec.id_offset) != offset) return inWhere + ": id_offset differs";
  for (const auto& [key, bits] :
       {std::pair{"group", inSpec.group}, std::pair{"mask", inSpec.mask}}) {
    if (inEntry.hasMember(key) != bits.has_value()) return inWhere + ": " + key + " presence";
    if (bits && static_cast<double>(*bits) != givenNumber(inEntry[key]))
      return inWhere + ": " + key + " differs";
  }
  if (inEntry.hasMember("timeout") != inSpec.timeout.has_value())
    return inWhere + ": timeout presence";
  if (inSpec.timeout && (!(*inSpec.timeout >= 0.0) || !std::isfinite(*inSpec.timeout) ||
                         *inSpec.timeout != givenNumber(inEntry["timeout"])))
    return inWhere + ": timeout differs or out of range";
  const bool marker_ids = inEntry.hasMember("ids") &&
                          inEntry["ids"].getType() == XmlRpcValue::TypeString &&
                          static_cast<std::string&>(inEntry["ids"]) == "marker";
  if (inSpec.marker_ids != marker_ids) return inWhere + ": ids differs";
  if (marker_ids && inSpec.type != InputType::kMarkerArray)
    return inWhere + ": ids marker on a non-MarkerArray entry";
  return "";
}

std::string resolve(const std::string& inTopic) {
  return !inTopic.empty() && inTopic[0] == '/' ? inTopic : kNamespace + inTopic;
}

/// The resolved check against its rule: refused exactly when two entries resolve alike or
/// one resolves to the scenery topic.
std::string checkResolved(const std::vector<SourceSpec>& inSpecs) {
  std::set<std::string> seen;
  bool clash = false;
  for (const SourceSpec& spec : inSpecs) {
    const std::string resolved = resolve(spec.topic);
    clash = clash || resolved == resolve("static_boxes") || !seen.insert(resolved).second;
  }
  const std::string problem = checkResolvedSourceTopics(inSpecs, resolve);
  if (clash == problem.empty())
    return clash ? "one topic twice or the scenery accepted"
                 : "refused without a clash: " + problem;
  if (clash && problem.rfind("~sources lists '", 0) != 0)
    return "resolved refusal does not name ~sources: " + problem;
  return "";
}

std::string checkValue(XmlRpcValue& ioValue) {
  const SourceSpec sentinel{"sentinel", InputType::kJskBoundingBoxArray, 7, 1u, 2u, 3.0, false};
  std::vector<SourceSpec> specs{sentinel};
  const std::string problem = parseSourceSpecs(ioValue, specs);
  if (!problem.empty()) {
    if (problem.rfind("~sources", 0) != 0) return "refusal does not name ~sources: " + problem;
    if (specs.size() != 1 || specs[0].topic != "sentinel" || specs[0].id_offset != 7)
      return "refused but changed the specs: " + problem;
    return "";
  }
  if (ioValue.getType() != XmlRpcValue::TypeArray || specs.empty() ||
      specs.size() != static_cast<std::size_t>(ioValue.size()))
    return "accepted, but not one spec per entry of a non-empty list";
  std::set<std::string> topics;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const std::string where = "~sources[" + std::to_string(i) + "]";
    if (specs[i].topic.empty()) return where + ": empty topic accepted";
    if (!topics.insert(specs[i].topic).second) return where + ": topic twice accepted";
    std::string entry = checkEntry(ioValue[static_cast<int>(i)], specs[i], where);
    if (!entry.empty()) return entry;
    const std::string text = describeSourceSpec(specs[i]);
    if (text.rfind(specs[i].topic, 0) != 0) return where + ": described as " + text;
  }
  return checkResolved(specs);
}

}  // namespace

std::string checkSourcesInput(const uint8_t* inData, std::size_t inSize) {
  ByteReader reader(inData, inSize);
  try {
    XmlRpcValue value;
    if (reader.byte() % 2 == 0) {
      const std::string text(reinterpret_cast<const char*>(inData) + (inSize ? 1 : 0),
                             inSize ? inSize - 1 : 0);
      const std::string problem = parseYamlParameter(text, value);
      if (!problem.empty()) {
        if (problem.find("is not YAML") == std::string::npos &&
            problem.find("nests deeper than") == std::string::npos)
          return "YAML refusal does not say why: " + problem;
        return "";
      }
    } else {
      value = decodeSources(reader);
    }
    return checkValue(value);
  } catch (const std::exception& error) {
    return std::string("exception: ") + error.what();
  } catch (const XmlRpc::XmlRpcException& error) {
    return "XmlRpcException: " + error.getMessage();
  }
}

}  // namespace sap_broadphase::fuzz
