// The node's tables against the copies that cannot be generated from them: msg/FrameStats.msg
// (catkin generates it, C++ cannot) against the engine report's `topic` column
// (frame_report.h), the node's counters and its own fields; the node's fill of the message
// against the report's rows. Each failure names the field.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <ros/serialization.h>

#include "node_status.h"

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

}  // namespace
}  // namespace sap_broadphase
