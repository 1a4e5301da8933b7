// The node's tables against the copies that cannot be generated from them: msg/FrameStats.msg
// (catkin generates it, C++ cannot) against the engine report's `topic` column
// (frame_report.h), the node's counters and its own fields; the node's fill of the message
// against the report's rows; the node's parameters (nodeParamRows()) against docs/NODE.md,
// config/default.yaml, the launch files' arguments and every param the launch and rostest
// files give the node. Each failure names the field or parameter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <ros/serialization.h>

#include "node_params.h"
#include "node_status.h"
#include "sap_broadphase/core/config.h"

namespace sap_broadphase {
namespace {

std::string readSource(const std::string& inPath) {
  std::ifstream file(std::string(SAP_SOURCE_DIR) + "/" + inPath);
  EXPECT_TRUE(file) << "cannot read " << inPath;
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

/// The field names of a .msg file, in order (comments and constants left out).
std::vector<std::string> msgFields(const std::string& inPath) {
  std::istringstream text(readSource(inPath));
  std::vector<std::string> fields;
  for (std::string line; std::getline(text, line);) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string type;
    std::string name;
    if (words >> type >> name && name.find('=') == std::string::npos) fields.push_back(name);
  }
  return fields;
}

/// Every FrameStats field the node's tables say it fills, with who fills it.
std::map<std::string, std::string> tableStatsFields() {
  std::map<std::string, std::string> fields;
  for (const ReportField& field : kReportFields)
    if (*field.topic != '\0') fields[field.topic] = std::string("report field ") + field.name;
  for (const NodeCounterRow& row : nodeCounterRows()) fields[row.stats_field] = "node counter";
  for (const std::string& name : nodeStatsFields()) fields[name] = "node field";
  return fields;
}

TEST(NodeTables, FrameStatsMsgHasEveryFieldOfTheTables) {
  const std::vector<std::string> msg = msgFields("msg/FrameStats.msg");
  ASSERT_FALSE(msg.empty());
  const std::set<std::string> inMsg(msg.begin(), msg.end());
  for (const auto& [name, source] : tableStatsFields())
    EXPECT_TRUE(inMsg.count(name))
        << "msg/FrameStats.msg has no field " << name << " (" << source << ")";
}

TEST(NodeTables, EveryFrameStatsFieldIsFilledByATable) {
  const auto fields = tableStatsFields();
  for (const std::string& name : msgFields("msg/FrameStats.msg"))
    EXPECT_TRUE(fields.count(name))
        << "msg/FrameStats.msg's " << name
        << " is in no table: the report's topic column (frame_report.h), nodeCounterRows() or "
           "nodeStatsFields() (node_status.cpp)";
}

TEST(NodeTables, DiagnosticsKeysAreDistinct) {
  std::set<std::string> keys;
  for (const NodeCounterRow& row : nodeCounterRows()) {
    if (*row.diagnostics_key == '\0') continue;  // not shown in /diagnostics
    EXPECT_TRUE(keys.insert(row.diagnostics_key).second)
        << "diagnostics key '" << row.diagnostics_key << "' twice";
  }
}

std::vector<uint8_t> serialized(const FrameStats& inStats) {
  std::vector<uint8_t> bytes(ros::serialization::serializationLength(inStats));
  ros::serialization::OStream stream(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::serialize(stream, inStats);
  return bytes;
}

/// Sets the field named inName of ioReport to a value unlike its default.
void changeField(FrameReport& ioReport, const std::string& inName) {
#define SAP_CHANGE_REPORT_FIELD(type, name, init, unit, topic, doc) \
  if (inName == #name) ioReport.name = changed(ioReport.name);
  const auto changed = [](auto inValue) {
    using Value = decltype(inValue);
    if constexpr (std::is_same_v<Value, FramePath>)
      return FramePath::kParallel;
    else if constexpr (std::is_same_v<Value, SkinChoice>)
      return SkinChoice::kChosen;
    else if constexpr (std::is_same_v<Value, bool>)
      return true;
    else
      return static_cast<Value>(inValue + 2);
  };
  SAP_FRAME_REPORT_FIELDS(SAP_CHANGE_REPORT_FIELD)
#undef SAP_CHANGE_REPORT_FIELD
}

TEST(NodeTables, EveryReportFieldOnTheTopicReachesTheMessage) {
  const std::vector<uint8_t> unchanged = serialized([] {
    FrameStats stats;
    fillEngineStats(FrameReport{}, stats);
    return stats;
  }());
  for (const ReportField& field : kReportFields) {
    if (*field.topic == '\0') continue;
    FrameReport report;
    changeField(report, field.name);
    FrameStats stats;
    fillEngineStats(report, stats);
    EXPECT_NE(serialized(stats), unchanged)
        << "report field " << field.name << " does not reach FrameStats." << field.topic;
  }
}

// ---- The node's parameters ----

/// A row's default in NodeParams, as default.yaml writes it (a number compared as a number).
::testing::AssertionResult defaultIsTheRows(const NodeParamRow& inRow) {
  NodeParams params;
  const std::string expected = inRow.default_text;
  const bool same = std::visit(
      [&](auto inAccess) {
        const auto& value = inAccess(params);
        using Value = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<Value, bool>)
          return expected == (value ? "true" : "false");
        else if constexpr (std::is_same_v<Value, std::string>)
          return expected == "\"" + value + "\"";
        else if constexpr (std::is_same_v<Value, std::vector<SourceSpec>>)
          return value.size() == 1 && expected == "[" + value.front().topic + "]";
        else
          return static_cast<double>(value) == std::strtod(expected.c_str(), nullptr);
      },
      inRow.access);
  if (same) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "~" << inRow.name << ": NodeParams' default is not the table's " << expected;
}

TEST(NodeTables, ParameterDefaultsAreTheStructs) {
  for (const NodeParamRow& row : nodeParamRows()) EXPECT_TRUE(defaultIsTheRows(row));
}

TEST(NodeTables, NumberParametersHaveALimitsRow) {
  NodeParams params;
  for (const NodeParamRow& row : nodeParamRows()) {
    const bool number = std::visit(
        [&](auto inAccess) {
          return std::is_arithmetic_v<std::decay_t<decltype(inAccess(params))>>;
        },
        row.access);
    const bool flag = std::holds_alternative<bool& (*)(NodeParams&)>(row.access);
    if (!number || flag) continue;  // switches, text and lists have no range
    EXPECT_NE(findLimit("node parameter", std::string("~") + row.name), nullptr)
        << "~" << row.name << " has no row in the limits table (src/core/frame/config.cpp)";
  }
}

TEST(NodeTables, NodeDocListsEveryParameterAsTheTable) {
  std::string doc = readSource("docs/NODE.md");
  // The node's own section: its Parameters up to Dynamic reconfigure (scene_publisher's come
  // later).
  const std::size_t from = doc.find("### Parameters");
  const std::size_t to = doc.find("### Dynamic reconfigure", from);
  ASSERT_NE(to, std::string::npos) << "docs/NODE.md has no node Parameters section";
  doc = doc.substr(from, to - from);
  const std::regex entry(R"(\n\* \*\*`~([a-z_0-9]+)`\*\* \(([^\n]*)\))");
  std::map<std::string, std::string> entries;
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), entry); it != std::sregex_iterator();
       ++it)
    entries[(*it)[1]] = (*it)[2];
  for (const NodeParamRow& row : nodeParamRows()) {
    const auto found = entries.find(row.name);
    ASSERT_NE(found, entries.end()) << "no `~" << row.name << "` entry in docs/NODE.md";
    EXPECT_EQ(found->second, std::string(row.type) + ", default: " + row.default_text)
        << "~" << row.name;
  }
  for (const auto& [name, text] : entries)
    EXPECT_TRUE(findConfigField(name) ||
                std::any_of(nodeParamRows().begin(), nodeParamRows().end(),
                            [&](const NodeParamRow& inRow) { return name == inRow.name; }))
        << "docs/NODE.md lists ~" << name << ", which no table has";
}

TEST(NodeTables, YamlDefaultsAreTheTables) {
  std::istringstream yaml(readSource("config/default.yaml"));
  std::map<std::string, std::string> values;
  const std::regex line(R"(^([a-z_0-9]+): *(.*?) *#.*$)");
  std::smatch match;
  for (std::string text; std::getline(yaml, text);)
    if (std::regex_match(text, match, line)) values[match[1]] = match[2];
  for (const NodeParamRow& row : nodeParamRows()) {
    const auto found = values.find(row.name);
    ASSERT_NE(found, values.end()) << "~" << row.name << " is missing from config/default.yaml";
    EXPECT_EQ(found->second, row.default_text) << "~" << row.name;
  }
}

TEST(NodeTables, LaunchArgumentsAreTheTables) {
  const std::regex argument(R"re(<arg name="([a-z_0-9]+)" default="\(yaml\)" doc="([^"]*)"/>)re");
  for (const char* path : {"launch/sap_broadphase.launch", "launch/sap_broadphase_nodelet.launch",
                           "launch/include/sap_broadphase_params.launch.xml"}) {
    const std::string launch = readSource(path);
    std::map<std::string, std::string> arguments;
    for (auto it = std::sregex_iterator(launch.begin(), launch.end(), argument);
         it != std::sregex_iterator(); ++it)
      arguments[(*it)[1]] = (*it)[2];
    for (const NodeParamRow& row : nodeParamRows()) {
      const auto found = arguments.find(row.name);
      ASSERT_NE(found, arguments.end()) << path << " has no argument " << row.name;
      EXPECT_EQ(found->second, row.doc) << path << ": " << row.name;
    }
  }
}

/// The names of the <param>s inside every node element of type inType in inText.
std::vector<std::string> nodeParamNames(const std::string& inText, const std::string& inType) {
  std::vector<std::string> names;
  const std::regex node("<node\\b([^>]*)>([\\s\\S]*?)</node>");
  const std::regex param(R"re(<param\b[^>]*\bname="([^"$]+)")re");
  for (auto it = std::sregex_iterator(inText.begin(), inText.end(), node);
       it != std::sregex_iterator(); ++it) {
    const std::string attributes = (*it)[1];
    if (attributes.find("type=\"" + inType + "\"") == std::string::npos &&
        attributes.find("args=\"load sap_broadphase/BroadphaseNodelet") == std::string::npos)
      continue;
    const std::string body = (*it)[2];
    for (auto p = std::sregex_iterator(body.begin(), body.end(), param);
         p != std::sregex_iterator(); ++p)
      names.push_back((*p)[1]);
  }
  return names;
}

TEST(NodeTables, LaunchAndTestFilesGiveTheNodeOnlyItsParameters) {
  std::size_t checked = 0;
  for (const char* folder : {"launch", "test/ros"}) {
    for (const auto& file :
         std::filesystem::directory_iterator(std::string(SAP_SOURCE_DIR) + "/" + folder)) {
      const std::string extension = file.path().extension().string();
      if (extension != ".launch" && extension != ".test") continue;
      const std::string path = std::string(folder) + "/" + file.path().filename().string();
      for (const std::string& name : nodeParamNames(readSource(path), "node")) {
        ++checked;
        EXPECT_TRUE(findConfigField(name) ||
                    std::any_of(nodeParamRows().begin(), nodeParamRows().end(),
                                [&](const NodeParamRow& inRow) { return name == inRow.name; }))
            << path << " gives the node ~" << name << ", which no table has";
      }
    }
  }
  EXPECT_GT(checked, 0u) << "no <param> of the node found: the files were not read";
}

}  // namespace
}  // namespace sap_broadphase
