// ~sources: topic names and {topic, type, id_offset, group, mask, timeout} entries.
#include "adapters_sources.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>

namespace sap_broadphase {

namespace {

using XmlRpc::XmlRpcValue;

const char* const kKeys[] = {"topic", "type", "id_offset", "group", "mask", "timeout", "ids"};

/// A number of the parameter server as a double: YAML gives 7 as an int, 0.5 as a double and
/// 4294967295 (past int32) as a double.
bool readNumber(const XmlRpcValue& inValue, double& outNumber) {
  if (inValue.getType() == XmlRpcValue::TypeInt) {
    outNumber = static_cast<int>(const_cast<XmlRpcValue&>(inValue));
    return true;
  }
  if (inValue.getType() == XmlRpcValue::TypeDouble) {
    outNumber = static_cast<double>(const_cast<XmlRpcValue&>(inValue));
    return true;
  }
  return false;
}

/// Reads text such as "0xFFFFFFFD" or "4294967293" (decimal, 0x hexadecimal or 0 octal).
bool readNumberText(const std::string& inText, double& outNumber) {
  if (inText.empty() || inText[0] == '-') return false;
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(inText.c_str(), &end, 0);
  if (errno != 0 || *end != '\0') return false;
  outNumber = static_cast<double>(value);
  return value <= 4294967295ull;
}

/// Reads key inKey of the entry as a whole number in [0, 2^32 - 1]. XML-RPC integers stop at
/// 2^31 - 1, so larger values (a mask such as 0xFFFFFFFD) come as a double (4294967293.0) or
/// as text ('0xFFFFFFFD').
std::string readUint32(const XmlRpcValue& inEntry, const char* inKey, const std::string& inWhere,
                       uint32_t& outValue) {
  XmlRpcValue& value = const_cast<XmlRpcValue&>(inEntry)[inKey];
  double number = 0.0;
  const bool read = value.getType() == XmlRpcValue::TypeString
                        ? readNumberText(static_cast<std::string>(value), number)
                        : readNumber(value, number);
  if (!read || !(number >= 0.0) || number > 4294967295.0 || std::floor(number) != number) {
    return inWhere + "." + inKey +
           " must be a whole number from 0 to 4294967295 (past 2147483647 as a float or as "
           "text, e.g. 4294967293.0 or '0xFFFFFFFD')";
  }
  outValue = static_cast<uint32_t>(number);
  return "";
}

std::string readEntry(const XmlRpcValue& inEntry, const std::string& inWhere, SourceSpec& outSpec) {
  XmlRpcValue& entry = const_cast<XmlRpcValue&>(inEntry);
  if (inEntry.getType() == XmlRpcValue::TypeString) {
    outSpec.topic = static_cast<std::string>(entry);
    return "";
  }
  if (inEntry.getType() != XmlRpcValue::TypeStruct) {
    return inWhere + " must be a topic name or a dict {topic: ..., type: ...} (keys topic, type, " +
           "id_offset, group, mask, timeout, ids)";
  }
  for (auto it = entry.begin(); it != entry.end(); ++it) {
    bool known = false;
    for (const char* key : kKeys) known = known || it->first == key;
    if (!known) {
      return inWhere + " has an unknown key '" + it->first +
             "' (keys: topic, type, id_offset, group, mask, timeout, ids)";
    }
  }
  if (!entry.hasMember("topic") || entry["topic"].getType() != XmlRpcValue::TypeString)
    return inWhere + ".topic must be a topic name (a string)";
  outSpec.topic = static_cast<std::string>(entry["topic"]);
  if (entry.hasMember("type")) {
    if (entry["type"].getType() != XmlRpcValue::TypeString)
      return inWhere + ".type must be a message type name (" + inputTypeNames() + ")";
    const std::string type = static_cast<std::string>(entry["type"]);
    const std::optional<InputType> known = inputTypeByName(type);
    if (!known) return inWhere + ".type '" + type + "' is none of " + inputTypeNames();
    outSpec.type = *known;
  }
  std::string problem;
  if (entry.hasMember("id_offset") &&
      !(problem = readUint32(inEntry, "id_offset", inWhere, outSpec.id_offset)).empty())
    return problem;
  uint32_t bits = 0;
  if (entry.hasMember("group")) {
    if (!(problem = readUint32(inEntry, "group", inWhere, bits)).empty()) return problem;
    outSpec.group = bits;
  }
  if (entry.hasMember("mask")) {
    if (!(problem = readUint32(inEntry, "mask", inWhere, bits)).empty()) return problem;
    outSpec.mask = bits;
  }
  if (entry.hasMember("timeout")) {
    double seconds = 0.0;
    if (!readNumber(entry["timeout"], seconds) || !(seconds >= 0.0) || !std::isfinite(seconds))
      return inWhere + ".timeout must be a number of seconds >= 0 (0 = never)";
    outSpec.timeout = seconds;
  }
  if (entry.hasMember("ids")) {
    const bool text = entry["ids"].getType() == XmlRpcValue::TypeString;
    const std::string ids = text ? static_cast<std::string>(entry["ids"]) : "";
    if (ids != "marker" && ids != "first_seen")
      return inWhere + ".ids must be 'first_seen' (the default) or 'marker'";
    if (ids == "marker" && outSpec.type != InputType::kMarkerArray)
      return inWhere + ".ids 'marker' needs type visualization_msgs/MarkerArray";
    outSpec.marker_ids = ids == "marker";
  }
  return "";
}

std::string hexText(uint32_t inBits) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%X", inBits);
  return text;
}

}  // namespace

std::string parseSourceSpecs(const XmlRpc::XmlRpcValue& inValue,
                             std::vector<SourceSpec>& outSpecs) {
  if (inValue.getType() != XmlRpcValue::TypeArray || inValue.size() == 0) {
    return "~sources must be a non-empty list of topics or {topic, type, ...} entries, e.g. "
           "[boxes, {topic: obstacles, type: visualization_msgs/MarkerArray, id_offset: 1000}]";
  }
  std::vector<SourceSpec> specs;
  std::set<std::string> seen;
  for (int i = 0; i < inValue.size(); ++i) {
    const std::string where = "~sources[" + std::to_string(i) + "]";
    SourceSpec spec;
    std::string problem = readEntry(const_cast<XmlRpc::XmlRpcValue&>(inValue)[i], where, spec);
    if (!problem.empty()) return problem;
    if (spec.topic.empty()) return where + " has an empty topic name";
    if (!seen.insert(spec.topic).second) return "~sources lists '" + spec.topic + "' twice";
    specs.push_back(spec);
  }
  outSpecs = std::move(specs);
  return "";
}

std::string checkResolvedSourceTopics(
    const std::vector<SourceSpec>& inSpecs,
    const std::function<std::string(const std::string&)>& inResolve) {
  const std::string scenery = inResolve("static_boxes");
  std::map<std::string, std::string> entry_of;  // resolved name -> the entry's own spelling
  for (const SourceSpec& spec : inSpecs) {
    const std::string resolved = inResolve(spec.topic);
    if (resolved == scenery) {
      return "~sources lists '" + spec.topic + "', which is the scenery topic static_boxes (" +
             resolved + "): the scenery is read as static_boxes only";
    }
    const auto [earlier, added] = entry_of.emplace(resolved, spec.topic);
    if (!added) {
      return "~sources lists '" + earlier->second + "' and '" + spec.topic +
             "', one topic twice (" + resolved + ")";
    }
  }
  return "";
}

std::string describeSourceSpec(const SourceSpec& inSpec) {
  if (inSpec.type == InputType::kBoxArray && inSpec.takesBoxArrayAsIs() && !inSpec.timeout)
    return inSpec.topic;
  std::string text = inSpec.topic + " (" + inputTypeInfo(inSpec.type).name;
  if (inSpec.id_offset != 0) text += ", id_offset " + std::to_string(inSpec.id_offset);
  if (inSpec.group) text += ", group " + hexText(*inSpec.group);
  if (inSpec.mask) text += ", mask " + hexText(*inSpec.mask);
  if (inSpec.marker_ids) text += ", ids marker";
  if (inSpec.timeout) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", *inSpec.timeout);
    text += std::string(", timeout ") + seconds + " s";
  }
  return text + ")";
}

}  // namespace sap_broadphase
