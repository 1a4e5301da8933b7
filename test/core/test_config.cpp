// The configuration table (config.h): its rows describe the struct they stand for (defaults,
// names, ranges), its checks refuse what the engine cannot run, and the give-back policy.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/runner/memory_policy.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/config.h"

namespace sap_broadphase {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A value of inField other than its default, of the field's own kind.
ConfigValue otherValue(const ConfigField& inField) {
  switch (inField.type) {
    case ConfigFieldType::kBool:
      return std::string(inField.default_text) != "true";
    case ConfigFieldType::kInteger:
      return static_cast<int64_t>(std::stoll(inField.default_text) == 1 ? 2 : 1);
    case ConfigFieldType::kNumber:
      return std::stod(inField.default_text) + 0.5;
    case ConfigFieldType::kMethod:
      return std::string("brute");
    case ConfigFieldType::kAxis:
      return std::string("z");
    case ConfigFieldType::kSkin:
      return std::string("0.75");
  }
  return false;
}

TEST(ConfigTable, OneRowPerFieldWithUniqueNames) {
  std::set<std::string> names;
  for (const ConfigField& field : configFields()) {
    EXPECT_TRUE(names.insert(field.name).second) << field.name << " listed twice";
    EXPECT_NE(std::string(field.doc), "") << field.name;
    EXPECT_NE(std::string(field.allowed), "") << field.name;
    EXPECT_EQ(findConfigField(field.name), &field);
  }
  // Every member of BroadphaseConfig: a field added to the struct and not to the table fails
  // here (sameConfig and the node's parameters would silently ignore it).
  EXPECT_EQ(names, (std::set<std::string>{
                       "threads", "method", "primary_axis", "secondary_axis", "axis_swapping",
                       "axis_swap_threshold", "parallel_min_boxes", "third_axis_slabs",
                       "reuse_unchanged_frames", "skin", "exact_final_test", "max_pairs"}));
  EXPECT_EQ(findConfigField("no_such_field"), nullptr);
}

TEST(ConfigTable, DefaultsAreTheStructsDefaults) {
  const BroadphaseConfig defaults;
  for (const ConfigField& field : configFields())
    EXPECT_EQ(valueText(field.get(defaults)), field.default_text) << field.name;
  EXPECT_EQ(configProblem(defaults), std::nullopt);
}

TEST(ConfigTable, EachFieldIsSetAndReadBackThroughItsRow) {
  for (const ConfigField& field : configFields()) {
    BroadphaseConfig config;
    const ConfigValue value = otherValue(field);
    EXPECT_EQ(field.set(config, value), std::nullopt) << field.name;
    EXPECT_EQ(valueText(field.get(config)), valueText(value)) << field.name;
    EXPECT_FALSE(sameConfig(config, BroadphaseConfig())) << field.name << " not compared";
    EXPECT_TRUE(sameConfig(config, config)) << field.name;
  }
}

TEST(ConfigTable, SetAcceptsTheKindsFrontEndsCarry) {
  BroadphaseConfig config;
  EXPECT_EQ(findConfigField("axis_swap_threshold")->set(config, int64_t{2}), std::nullopt);
  EXPECT_EQ(config.axis_swap_threshold, 2.0);
  EXPECT_EQ(findConfigField("threads")->set(config, 3.0), std::nullopt);
  EXPECT_EQ(config.threads, 3);
  EXPECT_EQ(findConfigField("primary_axis")->set(config, std::string("Z")), std::nullopt);
  EXPECT_EQ(config.primary_axis, 2);
  EXPECT_EQ(findConfigField("primary_axis")->set(config, int64_t{1}), std::nullopt);
  EXPECT_EQ(config.primary_axis, 1);
  EXPECT_EQ(findConfigField("skin")->set(config, std::string("off")), std::nullopt);
  EXPECT_EQ(config.skin, 0.0);
  EXPECT_EQ(findConfigField("skin")->set(config, 0.5), std::nullopt);
  EXPECT_EQ(config.skin, 0.5);
  EXPECT_EQ(findConfigField("skin")->set(config, std::string("auto")), std::nullopt);
  EXPECT_EQ(config.skin, std::nullopt);
  EXPECT_EQ(findConfigField("method")->set(config, std::string("sequential")), std::nullopt);
  EXPECT_EQ(config.method, Method::kSequential);
}

TEST(ConfigTable, SetRefusesWrongKindsAndRangesNamingTheFieldAndLeavesTheConfigAlone) {
  const BroadphaseConfig before;
  BroadphaseConfig config;
  const auto refused = [&](const char* inName, const ConfigValue& inValue) {
    const auto problem = findConfigField(inName)->set(config, inValue);
    EXPECT_TRUE(sameConfig(config, before)) << inName << " changed by a refused value";
    return problem.value_or("accepted");
  };
  const std::string here = " (at most " + std::to_string(maxThreads()) + " on this machine)";
  EXPECT_EQ(refused("threads", int64_t{-1}),
            "threads must be an integer from 0 to 4 a processor (0 = all cores), not -1" + here);
  EXPECT_EQ(refused("threads", 1.5),
            "threads must be an integer from 0 to 4 a processor (0 = all cores), not 1.5" + here);
  EXPECT_EQ(refused("method", std::string("quick")),
            "method must be auto, parallel, sequential or brute, not quick");
  EXPECT_EQ(refused("primary_axis", std::string("w")),
            "primary_axis must be x, y or z (or 0, 1, 2), not w");
  EXPECT_EQ(refused("primary_axis", int64_t{3}),
            "primary_axis must be x, y or z (or 0, 1, 2), not 3");
  EXPECT_EQ(refused("axis_swapping", int64_t{1}), "axis_swapping must be true or false, not 1");
  EXPECT_EQ(refused("axis_swap_threshold", kNaN),
            "axis_swap_threshold must be a number >= 0, not nan");
  EXPECT_EQ(refused("third_axis_slabs", int64_t{65}),
            "third_axis_slabs must be an integer in 0..64 (0 = auto), not 65");
  EXPECT_NE(refused("skin", -1.0), "accepted");
  EXPECT_NE(refused("skin", kInf), "accepted");
  EXPECT_NE(refused("skin", std::string("wide")), "accepted");
}

TEST(ConfigTable, ConfigProblemChecksEveryRowAndTheAxesRule) {
  const auto problem = [](auto inChange) {
    BroadphaseConfig config;
    inChange(config);
    return configProblem(config).value_or("valid");
  };
  EXPECT_EQ(problem([](BroadphaseConfig& c) { c.threads = -2; }),
            "threads must be an integer from 0 to 4 a processor (0 = all cores), not -2 (at most " +
                std::to_string(maxThreads()) + " on this machine)");
  EXPECT_EQ(problem([](BroadphaseConfig& c) { c.primary_axis = 5; }),
            "primary_axis must be x, y or z (or 0, 1, 2), not 5");
  EXPECT_EQ(problem([](BroadphaseConfig& c) { c.secondary_axis = 0; }),
            "primary_axis and secondary_axis must differ, not both x");
  EXPECT_EQ(problem([](BroadphaseConfig& c) { c.third_axis_slabs = -1; }),
            "third_axis_slabs must be an integer in 0..64 (0 = auto), not -1");
  EXPECT_EQ(problem([](BroadphaseConfig& c) { c.axis_swap_threshold = -0.5; }),
            "axis_swap_threshold must be a number >= 0, not -0.5");
  EXPECT_NE(problem([](BroadphaseConfig& c) { c.skin = kNaN; }), "valid");
  EXPECT_NE(problem([](BroadphaseConfig& c) { c.skin = -kInf; }), "valid");
  EXPECT_EQ(problem([](BroadphaseConfig& c) { c.skin = 0.0; }), "valid");
  EXPECT_EQ(problem([](BroadphaseConfig& c) { c.axis_swap_threshold = kInf; }), "valid");
  BroadphaseConfig bad;
  bad.threads = -1;
  EXPECT_THROW(Broadphase{bad}, std::invalid_argument);
}

TEST(ConfigTable, DescribeListsEveryFieldOnce) {
  BroadphaseConfig config;
  config.skin = 0.125;
  config.method = Method::kParallel;
  EXPECT_EQ(describeConfig(config),
            "threads 0, method parallel, primary_axis x, secondary_axis y, axis_swapping true, "
            "axis_swap_threshold 0.25, parallel_min_boxes 32768, third_axis_slabs 0, "
            "reuse_unchanged_frames true, skin 0.125, exact_final_test true, max_pairs 268435456");
}

TEST(MethodNames, OneVocabularyReadBack) {
  for (Method method : kMethods) EXPECT_EQ(parseMethod(methodName(method)), method);
  EXPECT_EQ(parseMethod("sap"), Method::kAuto);
  EXPECT_EQ(parseMethod("fast"), std::nullopt);
  EXPECT_EQ(methodList(), "auto, parallel, sequential or brute");
  EXPECT_EQ(methodList({Method::kSequential}), "sequential");
}

TEST(AxisNames, ReadAsLettersOrDigits) {
  for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(parseAxis(axisName(axis)), axis);
  EXPECT_EQ(parseAxis("Y"), 1);
  EXPECT_EQ(parseAxis("2"), 2);
  EXPECT_EQ(parseAxis("3"), std::nullopt);
  EXPECT_EQ(parseAxis("xy"), std::nullopt);
  EXPECT_STREQ(axisName(7), "?");
}

TEST(SkinText, ReadsBackAsTheSameSkin) {
  for (double skin : {0.1, 1.0 / 3.0, 2.5e-7, 123456.789, 0.0}) {
    std::optional<double> read;
    ASSERT_TRUE(skinFromText(skinToText(skin), read)) << skin;
    EXPECT_EQ(read, skin);
  }
  EXPECT_EQ(skinToText(std::nullopt), "auto");
  EXPECT_EQ(skinToText(0.0), "off");
  std::optional<double> read = 1.0;
  EXPECT_TRUE(skinFromText("", read));
  EXPECT_EQ(read, std::nullopt);
  EXPECT_FALSE(skinFromText("1.5m", read));
}

TEST(GiveBackWatch, GivesBackOnlyAfterManySmallFramesInABigBuffer) {
  GiveBackWatch watch;
  const std::size_t big = std::size_t{1} << 21;
  for (std::size_t frame = 0; frame < 3 * kGiveBackAfterSmallFrames; ++frame) {
    EXPECT_FALSE(watch.shouldGiveBack(100, kGiveBackMinBoxes)) << "small buffers are kept";
    EXPECT_FALSE(watch.shouldGiveBack(big / kGiveBackRatio, big)) << "a quarter or more in use";
  }
  int give_backs = 0;
  std::size_t first = 0;
  for (std::size_t frame = 1; frame <= 3 * kGiveBackAfterSmallFrames; ++frame) {
    if (frame == kGiveBackAfterSmallFrames / 2) watch.shouldGiveBack(big / 2, big);  // restarts
    if (watch.shouldGiveBack(1000, big)) {
      ++give_backs;
      if (first == 0) first = frame;
    }
  }
  EXPECT_EQ(first, kGiveBackAfterSmallFrames / 2 + kGiveBackAfterSmallFrames - 1);
  EXPECT_EQ(give_backs, 2);
}

// ---- The limits table ----

TEST(Limits, ThreadsCappedAtFourAProcessorEverywhere) {
  const int cap = maxThreads();
  EXPECT_EQ(cap, kMaxThreadsPerProcessor * std::max(1, omp_get_num_procs()));
  BroadphaseConfig config;
  config.threads = cap;
  EXPECT_EQ(configProblem(config), std::nullopt);
  // Issue: `threads 999` was taken at start-up and by sap_pairs; Python's threads=100000
  // crashed. Each front end goes through this row.
  for (const int threads : {cap + 1, 999, 100000, std::numeric_limits<int>::max()}) {
    config.threads = threads;
    ASSERT_TRUE(configProblem(config)) << threads;
    EXPECT_NE(configProblem(config)->find("threads must be"), std::string::npos);
    EXPECT_THROW(Broadphase{config}, std::invalid_argument) << threads;
  }
}

TEST(Limits, SettingsOutOfRangeAreRefusedNotClamped) {
  // The values the issue found clamped: each is refused, and the config stays as it was.
  const std::vector<std::pair<const char*, ConfigValue>> cases = {
      {"parallel_min_boxes", int64_t{-1}},
      {"threads", int64_t{-5}},
      {"third_axis_slabs", int64_t{65}},
      {"axis_swap_threshold", -kInf},
      {"skin", 1e300},
      {"skin", std::string("1e300")},
  };
  for (const auto& [name, value] : cases) {
    BroadphaseConfig config;
    const auto problem = findConfigField(name)->set(config, value);
    ASSERT_TRUE(problem) << name << " " << valueText(value) << " accepted";
    EXPECT_EQ(problem->rfind(std::string(name) + " must be", 0), 0u) << *problem;
    EXPECT_TRUE(sameConfig(config, BroadphaseConfig{}));
  }
  BroadphaseConfig config;
  EXPECT_EQ(findConfigField("skin")->set(config, kMaxSkin), std::nullopt);
  const Limit* width = findLimit("dynamic_reconfigure", "marker_line_width");
  ASSERT_TRUE(width);
  EXPECT_EQ(limitProblem(*width, kInf),
            "marker_line_width must be 0 (10 % of the mean edge) or up "
            "to 1e6 m, not inf");
  EXPECT_TRUE(limitProblem(*findLimit("dynamic_reconfigure", "max_marker_boxes"), -1.0));
}

TEST(Limits, RateHoldsInARosDuration) {
  const Limit* rate = findLimit("node parameter", "~rate");
  ASSERT_TRUE(rate);
  EXPECT_EQ(limitProblem(*rate, 0.0), std::nullopt);  // a frame per delivery
  EXPECT_EQ(limitProblem(*rate, 10.0), std::nullopt);
  EXPECT_EQ(limitProblem(*rate, 1e-10),
            "~rate must be 0 (a frame per delivery) or 1e-9..1e6 Hz, "
            "not 1e-10");
  // Every accepted rate's period fits ros::Duration's int32 seconds.
  EXPECT_LE(1.0 / rate->min, 2147483647.0);
  for (const double bad : {-1.0, 4.6e-10, kInf, -kInf, kNaN, 1e7})
    EXPECT_TRUE(limitProblem(*rate, bad)) << bad;
}

// Property over every row's range edges: no crash; inside refused by none, outside refused
// by all (0 only where the row allows it), NaN and infinities refused unless the range holds
// them.
TEST(Limits, EveryRowRefusesOutsideItsRangeAndTakesItsEdges) {
  const double kExtremes[] = {0.0,
                              -0.0,
                              -1.0,
                              1.0,
                              kNaN,
                              kInf,
                              -kInf,
                              std::numeric_limits<double>::max(),
                              std::numeric_limits<double>::lowest(),
                              std::numeric_limits<double>::denorm_min(),
                              double{std::numeric_limits<int32_t>::max()},
                              double{std::numeric_limits<int32_t>::min()},
                              static_cast<double>(std::numeric_limits<int64_t>::max()),
                              18446744073709551615.0};
  for (const Limit& limit : limits()) {
    SCOPED_TRACE(std::string(limit.entry) + " " + limit.name);
    EXPECT_GT(std::string(limit.reason).size(), 0u);
    EXPECT_GT(std::string(limit.violation).size(), 0u);
    if (!(limit.max > limit.min)) continue;  // not a number (method, axes, switches)
    EXPECT_EQ(limitProblem(limit, limit.min), std::nullopt);
    EXPECT_EQ(limitProblem(limit, limit.max), std::nullopt);
    for (const double value : kExtremes) {
      const bool inside =
          (value >= limit.min && value <= limit.max) || (limit.zero_allowed && value == 0.0);
      EXPECT_EQ(!limitProblem(limit, value), inside) << value;
    }
  }
}

// The engine's numeric fields over the same extremes through their rows, as every front end
// sets them (integers and numbers): refused or accepted per the table, the engine built from
// an accepted config.
TEST(Limits, EngineFieldsOverTheirTypesExtremes) {
  const ConfigValue kValues[] = {int64_t{0},
                                 int64_t{-1},
                                 std::numeric_limits<int64_t>::max(),
                                 std::numeric_limits<int64_t>::min(),
                                 int64_t{std::numeric_limits<int32_t>::max()},
                                 0.0,
                                 -0.0,
                                 kNaN,
                                 kInf,
                                 -kInf,
                                 1e300,
                                 std::numeric_limits<double>::max(),
                                 std::numeric_limits<double>::denorm_min(),
                                 std::string(""),
                                 std::string("nan"),
                                 std::string("inf"),
                                 std::string("-1e400"),
                                 true};
  for (const ConfigField& field : configFields()) {
    for (const ConfigValue& value : kValues) {
      SCOPED_TRACE(std::string(field.name) + " " + valueText(value));
      BroadphaseConfig config;
      if (field.set(config, value)) {
        EXPECT_TRUE(sameConfig(config, BroadphaseConfig{}));
        continue;
      }
      if (const double* number = std::get_if<double>(&value)) {
        if (field.type == ConfigFieldType::kInteger || field.type == ConfigFieldType::kNumber) {
          EXPECT_TRUE(*number >= field.min && *number <= field.max);
        }
      }
      // An accepted value breaks no row; only the rule between the axes may (secondary_axis 0).
      const auto problem = configProblem(config);
      if (problem) {
        EXPECT_NE(problem->find("must differ"), std::string::npos) << *problem;
      } else if (config.threads <= 1) {
        EXPECT_NO_THROW(Broadphase{config});
      }
    }
  }
}

TEST(Limits, TheRobustnessDocIsTheTable) {
  const std::string path = std::string(SAP_SOURCE_DIR) + "/docs/ROBUSTNESS.md";
  std::ifstream file(path);
  ASSERT_TRUE(file) << path;
  const std::string doc((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::string begin = "<!-- limits table: limitsMarkdown() -->\n";
  const std::string end = "<!-- end of the limits table -->";
  const std::size_t from = doc.find(begin);
  const std::size_t to = doc.find(end);
  ASSERT_NE(from, std::string::npos) << "no limits table in " << path;
  ASSERT_NE(to, std::string::npos);
  EXPECT_EQ(doc.substr(from + begin.size(), to - from - begin.size()), limitsMarkdown())
      << "docs/ROBUSTNESS.md and the limits table (src/core/frame/config.cpp) differ; the table:\n"
      << limitsMarkdown();
}

}  // namespace
}  // namespace sap_broadphase
