// The engine's knobs are described once, in configFields() (config.h); the ROS front ends
// repeat them in files that cannot include it: the dynamic_reconfigure definition
// (cfg/BroadphaseNode.cfg), the YAML defaults (config/default.yaml), the launch files'
// arguments and the parameter list of docs/NODE.md. These tests read those files and fail on
// any difference from the table: a missing or extra knob, another type, default, range or
// description.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

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

// ---- cfg/BroadphaseNode.cfg ----

// The arguments of one call, split at the commas outside strings and brackets.
std::vector<std::string> splitArguments(const std::string& inText) {
  std::vector<std::string> arguments(1);
  int depth = 0;
  char quote = 0;
  for (char c : inText) {
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '(' || c == '[') {
      ++depth;
    } else if (c == ')' || c == ']') {
      --depth;
    } else if (c == ',' && depth == 0) {
      arguments.emplace_back();
      continue;
    }
    arguments.back() += c;
  }
  for (std::string& argument : arguments) {
    const auto first = argument.find_first_not_of(" \n");
    const auto last = argument.find_last_not_of(" \n");
    argument = first == std::string::npos ? "" : argument.substr(first, last - first + 1);
  }
  return arguments;
}

// Every `engine.add(...)` of the .cfg: name -> its arguments after the name.
std::map<std::string, std::vector<std::string>> cfgEngineEntries(const std::string& inCfg) {
  std::map<std::string, std::vector<std::string>> entries;
  const std::string call = "engine.add(";
  for (auto at = inCfg.find(call); at != std::string::npos; at = inCfg.find(call, at + 1)) {
    std::size_t end = at + call.size();
    int depth = 1;
    char quote = 0;
    for (; end < inCfg.size() && depth > 0; ++end) {
      const char c = inCfg[end];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '(') {
        ++depth;
      } else if (c == ')') {
        --depth;
      }
    }
    std::vector<std::string> arguments =
        splitArguments(inCfg.substr(at + call.size(), end - 1 - at - call.size()));
    const std::string name = arguments[0].substr(1, arguments[0].size() - 2);
    arguments.erase(arguments.begin());
    entries[name] = arguments;
  }
  return entries;
}

std::string unquoted(const std::string& inText) {
  if (inText.size() >= 2 && (inText.front() == '"' || inText.front() == '\'') &&
      inText.back() == inText.front())
    return inText.substr(1, inText.size() - 2);
  return inText;
}

const char* cfgType(ConfigFieldType inType) {
  switch (inType) {
    case ConfigFieldType::kBool:
      return "bool_t";
    case ConfigFieldType::kInteger:
      return "int_t";
    case ConfigFieldType::kNumber:
      return "double_t";
    case ConfigFieldType::kMethod:
    case ConfigFieldType::kAxis:
    case ConfigFieldType::kSkin:
      return "str_t";
  }
  return "?";
}

// The default as the .cfg writes it: Python's True/False, numbers, quoted strings.
::testing::AssertionResult sameDefault(const ConfigField& inField, const std::string& inCfg) {
  const std::string expected = inField.default_text;
  bool same = false;
  switch (inField.type) {
    case ConfigFieldType::kBool:
      same = inCfg == (expected == "true" ? "True" : "False");
      break;
    case ConfigFieldType::kInteger:
    case ConfigFieldType::kNumber:
      same = std::strtod(inCfg.c_str(), nullptr) == std::strtod(expected.c_str(), nullptr);
      break;
    default:
      same = inCfg == "\"" + expected + "\"";
  }
  if (same) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << inField.name << ": default " << inCfg << " in the .cfg, "
                                       << expected << " in configFields()";
}

// dynamic_reconfigure's int_t is 32 bits; an omitted double bound is infinite.
double cfgBound(const std::vector<std::string>& inArguments, std::size_t inIndex,
                double inOmitted) {
  if (inIndex >= inArguments.size() || inArguments[inIndex].find('=') != std::string::npos)
    return inOmitted;
  return std::strtod(inArguments[inIndex].c_str(), nullptr);
}

TEST(ConfigSources, DynamicReconfigureMatchesTheTable) {
  const auto entries = cfgEngineEntries(readSource("cfg/BroadphaseNode.cfg"));
  for (const auto& [name, arguments] : entries)
    EXPECT_TRUE(findConfigField(name))
        << "the .cfg's engine group has " << name << ", which configFields() does not";
  for (const ConfigField& field : configFields()) {
    SCOPED_TRACE(field.name);
    const auto entry = entries.find(field.name);
    ASSERT_NE(entry, entries.end()) << "missing from the .cfg's engine group";
    const std::vector<std::string>& arguments = entry->second;  // type, level, doc, default, ...
    ASSERT_GE(arguments.size(), 4u);
    EXPECT_EQ(arguments[0], cfgType(field.type));
    EXPECT_EQ(arguments[1], "ENGINE");
    EXPECT_EQ(unquoted(arguments[2]), field.doc);
    EXPECT_TRUE(sameDefault(field, arguments[3]));
    // The .cfg offers the type's whole range: dynamic_reconfigure's server clamps to it
    // before the node sees a value, so any narrower range would clamp instead of refuse.
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    if (field.type == ConfigFieldType::kInteger) {
      EXPECT_EQ(cfgBound(arguments, 4, -kInfinity), double{std::numeric_limits<int32_t>::min()});
      EXPECT_EQ(cfgBound(arguments, 5, kInfinity), double{std::numeric_limits<int32_t>::max()});
    } else if (field.type == ConfigFieldType::kNumber) {
      EXPECT_EQ(cfgBound(arguments, 4, -kInfinity), -kInfinity);
      EXPECT_EQ(cfgBound(arguments, 5, kInfinity), kInfinity);
    } else {
      EXPECT_LE(arguments.size(), 5u) << "a range for a field that has none";
    }
  }
}

TEST(ConfigSources, DynamicReconfigureOffersEveryMethodAndAxis) {
  const std::string cfg = readSource("cfg/BroadphaseNode.cfg");
  std::string offered;
  const std::regex constant(R"(gen\.const\("([a-z]+)\", str_t, \"([a-z]+)\")");
  for (auto it = std::sregex_iterator(cfg.begin(), cfg.end(), constant);
       it != std::sregex_iterator(); ++it) {
    EXPECT_EQ((*it)[1], (*it)[2]);
    offered += (*it)[1].str() + " ";
  }
  std::string expected;
  for (Method method : kMethods) expected += std::string(methodName(method)) + " ";
  for (int axis = 0; axis < 3; ++axis) expected += std::string(axisName(axis)) + " ";
  EXPECT_EQ(offered, expected);
}

// ---- config/default.yaml ----

TEST(ConfigSources, YamlDefaultsMatchTheTable) {
  std::istringstream yaml(readSource("config/default.yaml"));
  std::map<std::string, std::pair<std::string, std::string>> lines;  // name -> value, comment
  const std::regex line(R"(^([a-z_0-9]+): *(.*?) *# (.*)$)");
  std::smatch match;
  for (std::string text; std::getline(yaml, text);)
    if (std::regex_match(text, match, line)) lines[match[1]] = {match[2], match[3]};
  for (const ConfigField& field : configFields()) {
    SCOPED_TRACE(field.name);
    const auto entry = lines.find(field.name);
    ASSERT_NE(entry, lines.end()) << "missing from config/default.yaml";
    const auto& [value, comment] = entry->second;
    if (field.type == ConfigFieldType::kInteger || field.type == ConfigFieldType::kNumber)
      EXPECT_EQ(std::strtod(value.c_str(), nullptr), std::strtod(field.default_text, nullptr));
    else
      EXPECT_EQ(value, field.default_text);
    EXPECT_EQ(comment, field.doc);
  }
}

// ---- The launch files ----

// The doc of every `<arg name="..." default="(yaml)" doc="..."/>` of a launch file ("(yaml)":
// the YAML's value stays; a non-empty default, so that roslaunch's ros-args lists it optional).
std::map<std::string, std::string> launchArguments(const std::string& inLaunch) {
  std::map<std::string, std::string> arguments;
  const std::regex argument(R"re(<arg name="([a-z_0-9]+)" default="\(yaml\)" doc="([^"]*)"/>)re");
  for (auto it = std::sregex_iterator(inLaunch.begin(), inLaunch.end(), argument);
       it != std::sregex_iterator(); ++it)
    arguments[(*it)[1]] = (*it)[2];
  return arguments;
}

TEST(ConfigSources, LaunchArgumentsMatchTheTable) {
  const std::string include = readSource("launch/include/sap_broadphase_params.launch.xml");
  for (const char* path : {"launch/sap_broadphase.launch", "launch/sap_broadphase_nodelet.launch",
                           "launch/include/sap_broadphase_params.launch.xml"}) {
    SCOPED_TRACE(path);
    const auto arguments = launchArguments(readSource(path));
    for (const ConfigField& field : configFields()) {
      const auto argument = arguments.find(field.name);
      ASSERT_NE(argument, arguments.end()) << field.name << " is not an argument";
      EXPECT_EQ(argument->second, std::string(field.doc) + "; " + field.allowed) << field.name;
    }
  }
  for (const ConfigField& field : configFields()) {
    const std::string name = field.name;
    EXPECT_NE(include.find("<param if=\"$(eval " + name + " not in ('', '(yaml)'))\" name=\"" +
                           name + "\" value=\"$(arg " + name + ")\"/>"),
              std::string::npos)
        << name << " is never set from its argument";
  }
}

// ---- docs/NODE.md ----

const char* docType(ConfigFieldType inType) {
  switch (inType) {
    case ConfigFieldType::kBool:
      return "bool";
    case ConfigFieldType::kInteger:
      return "int";
    case ConfigFieldType::kNumber:
      return "double";
    case ConfigFieldType::kMethod:
    case ConfigFieldType::kAxis:
      return "string";
    case ConfigFieldType::kSkin:
      return "string or double";
  }
  return "?";
}

TEST(ConfigSources, NodeDocListsEveryKnobAsTheTable) {
  const std::string doc = readSource("docs/NODE.md");
  // * **`~name`** (type, default: value; allowed)  then a blank line and the description.
  const std::regex entry(R"(\n\* \*\*`~([a-z_0-9]+)`\*\* \(([^\n]*)\)\n\n    ([^\n]*))");
  std::map<std::string, std::pair<std::string, std::string>> entries;
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), entry); it != std::sregex_iterator();
       ++it)
    entries[(*it)[1]] = {(*it)[2], (*it)[3]};
  for (const ConfigField& field : configFields()) {
    SCOPED_TRACE(field.name);
    const auto found = entries.find(field.name);
    ASSERT_NE(found, entries.end()) << "no `~" << field.name << "` entry in docs/NODE.md";
    const bool quoted = field.type == ConfigFieldType::kMethod ||
                        field.type == ConfigFieldType::kAxis ||
                        field.type == ConfigFieldType::kSkin;
    const std::string value =
        quoted ? "\"" + std::string(field.default_text) + "\"" : std::string(field.default_text);
    EXPECT_EQ(found->second.first,
              std::string(docType(field.type)) + ", default: " + value + "; " + field.allowed);
    // The description starts with the table's line; more may follow.
    EXPECT_EQ(found->second.second.substr(0, std::string(field.doc).size()), field.doc);
  }
}

}  // namespace
}  // namespace sap_broadphase
