// The CLI contract, through the real executables: round trips against the oracle, every flag,
// standard input, and every bad input (exit 2, empty stdout, FILE:LINE: on stderr).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/config.h"
#include "sap_broadphase/core/frame_report.h"
#include "sap_broadphase/core/scenes.h"
#include "sap_broadphase/core/text_io.h"
#include "test_files.h"

namespace sap_broadphase {
namespace {

using test_files::readFile;
using test_files::RunResult;
using test_files::shellQuote;
using test_files::TempDir;
using test_files::writeFile;

/// Runs inExe with inArgs, stdin from inStdinPath (or /dev/null), capturing stdout and stderr.
RunResult runTool(const TempDir& inDir, const std::string& inExe,
                  const std::vector<std::string>& inArgs, const std::string& inStdinPath = "") {
  return test_files::runCommand(inDir, test_files::commandLine(inExe, inArgs), inStdinPath);
}

RunResult runPairs(const TempDir& inDir, const std::vector<std::string>& inArgs,
                   const std::string& inStdinPath = "") {
  return runTool(inDir, SAP_PAIRS_EXE, inArgs, inStdinPath);
}

RunResult runScene(const TempDir& inDir, const std::vector<std::string>& inArgs) {
  return runTool(inDir, SAP_SCENE_EXE, inArgs);
}

/// The oracle's answer for a box file, as sap_pairs should print it.
std::string oracleText(const std::string& inPath) {
  std::ifstream file(inPath);
  BoxSet boxes;
  const auto error = readBoxText(file, inPath, boxes);
  EXPECT_FALSE(error.has_value()) << (error ? error->message() : "");
  std::ostringstream text;
  writePairText(text, bruteForcePairs(boxes));
  return text.str();
}

std::size_t lineCount(const std::string& inText) {
  return static_cast<std::size_t>(std::count(inText.begin(), inText.end(), '\n'));
}

TEST(Cli, HelpExitsZero) {
  TempDir dir;
  const RunResult pairs = runPairs(dir, {"--help"});
  EXPECT_EQ(pairs.status, 0);
  EXPECT_NE(pairs.out.find("usage: sap_pairs"), std::string::npos);
  const RunResult scene = runScene(dir, {"--help"});
  EXPECT_EQ(scene.status, 0);
  EXPECT_NE(scene.out.find("usage: sap_scene"), std::string::npos);
}

TEST(Cli, SceneRoundTripMatchesTheOracleForEveryMethodAndThreadCount) {
  TempDir dir;
  const std::vector<std::vector<std::string>> scenes = {
      {"--scene", "uniform", "--n", "3000", "--density", "0.3", "--frame", "4", "--seed", "7"},
      {"--scene", "ball", "--n", "2000", "--density", "0.1", "--frame", "100", "--seed", "3"},
      {"--scene", "plane", "--n", "2500", "--density", "0.1", "--frame", "250", "--seed", "5",
       "--axis", "y"}};
  for (const auto& sceneArgs : scenes) {
    const RunResult scene = runScene(dir, sceneArgs);
    ASSERT_EQ(scene.status, 0) << scene.err;
    const std::string boxPath = dir.file("boxes.txt");
    writeFile(boxPath, scene.out);
    const std::string expected = oracleText(boxPath);
    if (sceneArgs[1] != "plane") {
      EXPECT_GT(lineCount(expected), 0u) << sceneArgs[1];
    }
    for (const std::string method : {"sap", "sequential", "brute"}) {
      for (const std::string threads : {"1", "2", "3"}) {
        const RunResult pairs = runPairs(dir, {"--threads", threads, "--method", method, boxPath});
        EXPECT_EQ(pairs.status, 0) << pairs.err;
        EXPECT_TRUE(pairs.out == expected)
            << sceneArgs[1] << " --method " << method << " --threads " << threads << ": "
            << lineCount(pairs.out) << " lines, expected " << lineCount(expected);
        EXPECT_EQ(pairs.err, "");
      }
    }
  }
}

TEST(Cli, SceneOutputIsTheLibraryFrameBitForBit) {
  TempDir dir;
  const RunResult scene = runScene(
      dir, {"--scene", "ball", "--n", "500", "--density", "0.2", "--frame", "60", "--seed", "9"});
  ASSERT_EQ(scene.status, 0);
  SceneConfig config;
  config.kind = SceneKind::kBallCluster;
  config.n = 500;
  config.density = 0.2;
  config.seed = 9;
  std::ostringstream expected;
  writeBoxText(expected, makeSceneFrame(config, 60));
  EXPECT_TRUE(scene.out == expected.str());
  EXPECT_EQ(lineCount(scene.out), 500u);
  // Deterministic: the same arguments give the same bytes.
  const RunResult again = runScene(
      dir, {"--scene", "ball", "--n", "500", "--density", "0.2", "--frame", "60", "--seed", "9"});
  EXPECT_TRUE(again.out == scene.out);
}

TEST(Cli, SceneAcceptsEqualsFormAndDefaults) {
  TempDir dir;
  const RunResult scene = runScene(dir, {"--scene=plane", "--n=100", "--axis=z", "--frame=3"});
  EXPECT_EQ(scene.status, 0) << scene.err;
  EXPECT_EQ(lineCount(scene.out), 100u);
  const RunResult empty = runScene(dir, {"--n", "0"});
  EXPECT_EQ(empty.status, 0);
  EXPECT_EQ(empty.out, "");
}

TEST(Cli, CountPrintsOnlyTheNumber) {
  TempDir dir;
  const std::string path = dir.file("boxes.txt");
  writeFile(path, "1 0 0 0 1 1 1\n2 1 1 1 2 2 2\n3 5 5 5 6 6 6\n4 0.5 0.5 0.5 0.5 0.5 0.5\n");
  const RunResult counted = runPairs(dir, {"--count", path});
  EXPECT_EQ(counted.status, 0);
  EXPECT_EQ(counted.out, "2\n");
  const RunResult listed = runPairs(dir, {path});
  EXPECT_EQ(listed.out, "1 2\n1 4\n");
  writeFile(path, "# nothing\n");
  EXPECT_EQ(runPairs(dir, {"--count", path}).out, "0\n");
  EXPECT_EQ(runPairs(dir, {path}).out, "");
}

TEST(Cli, ReadsStandardInput) {
  TempDir dir;
  const std::string path = dir.file("boxes.txt");
  writeFile(path, "10,0,0,0,1,1,1\n5\t1\t1\t1\t2\t2\t2\n");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"-"}, std::vector<std::string>{},
        std::vector<std::string>{"--threads", "2", "--", "-"}}) {
    const RunResult result = runPairs(dir, args, path);
    EXPECT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.out, "5 10\n");
  }
}

TEST(Cli, StatsGoToStandardError) {
  TempDir dir;
  const RunResult scene = runScene(dir, {"--n", "5000", "--density", "0.1"});
  const std::string path = dir.file("boxes.txt");
  writeFile(path, scene.out);
  for (const std::string method : {"sap", "sequential", "brute"}) {
    const RunResult result = runPairs(dir, {"--stats", "--threads", "2", "--method", method, path});
    EXPECT_EQ(result.status, 0);
    EXPECT_EQ(result.out, oracleText(path));
    EXPECT_NE(result.err.find("\nprimary_axis x\nsecondary_axis y\n"), std::string::npos)
        << result.err;
    EXPECT_EQ(result.err.rfind("ms_read ", 0), 0u) << result.err;
    // One "name value" line a field of the report's table, in its order.
    std::size_t at = 0;
    for (const ReportField& field : kReportFields) {
      const std::size_t line = result.err.find(std::string("\n") + field.name + " ", at);
      EXPECT_NE(line, std::string::npos) << "no " << field.name << " line (after the one before) "
                                         << "in --stats:\n"
                                         << result.err;
      if (line != std::string::npos) at = line + 1;
    }
  }
}

/// Expects a refusal of inText (as a file and on stdin) at inLine with inWords in the reason.
void expectBadInput(const std::string& inText, std::size_t inLine, const std::string& inWords) {
  TempDir dir;
  const std::string path = dir.file("bad.txt");
  writeFile(path, inText);
  const RunResult fromFile = runPairs(dir, {"--threads", "2", path});
  EXPECT_EQ(fromFile.status, 2) << inText;
  EXPECT_EQ(fromFile.out, "") << inText;
  const std::string prefix = path + ":" + std::to_string(inLine) + ": ";
  EXPECT_EQ(fromFile.err.rfind(prefix, 0), 0u) << "stderr: " << fromFile.err;
  EXPECT_NE(fromFile.err.find(inWords), std::string::npos) << "stderr: " << fromFile.err;
  const RunResult fromStdin = runPairs(dir, {"--count", "-"}, path);
  EXPECT_EQ(fromStdin.status, 2);
  EXPECT_EQ(fromStdin.out, "");
  EXPECT_EQ(fromStdin.err.rfind("<stdin>:" + std::to_string(inLine) + ": ", 0), 0u)
      << "stderr: " << fromStdin.err;
}

// Input with more pairs than --max-pairs: exit 2, nothing on stdout, the file and the bound
// on stderr; at the bound the pairs are printed.
TEST(Cli, MorePairsThanMaxPairsExitsTwo) {
  TempDir dir;
  const std::string path = dir.file("pile.txt");
  std::string text;
  for (int id = 0; id < 200; ++id) text += std::to_string(id) + " 0 0 0 1 1 1\n";  // 19900 pairs
  writeFile(path, text);
  for (const std::string method : {"sap", "sequential", "brute"}) {
    const RunResult refused = runPairs(dir, {"--method", method, "--max-pairs", "19899", path});
    EXPECT_EQ(refused.status, 2) << method;
    EXPECT_EQ(refused.out, "") << method;
    EXPECT_EQ(refused.err.rfind(path + ": frame refused: more than 19899 pairs", 0), 0u)
        << refused.err;
    const RunResult fromStdin = runPairs(dir, {"--max-pairs=100", "--count", "-"}, path);
    EXPECT_EQ(fromStdin.status, 2);
    EXPECT_EQ(fromStdin.err.rfind("<stdin>: frame refused: more than 100 pairs", 0), 0u)
        << fromStdin.err;
    const RunResult at_bound =
        runPairs(dir, {"--method", method, "--max-pairs", "19900", "--count", path});
    EXPECT_EQ(at_bound.status, 0) << at_bound.err;
    EXPECT_EQ(at_bound.out, "19900\n");
  }
}

TEST(Cli, EveryBadInputExitsTwoWithTheLine) {
  const std::string good = "1 0 0 0 1 1 1\n# comment\n\n";
  expectBadInput(good + "2 nan 0 0 1 1 1\n", 4, "NaN in min_x");
  expectBadInput(good + "2 0 0 0 1 1 -nan\n", 4, "NaN in max_z");
  expectBadInput(good + "2 0 3 0 1 2 1\n", 4, "min_y (3) > max_y (2)");
  expectBadInput(good + "2 0 0 0 1 1\n", 4, "expected 7 fields");
  expectBadInput(good + "2 0 0 0 1 1 1 1\n", 4, "expected 7 fields");
  expectBadInput(good + "2 0 0 zero 1 1 1\n", 4, "min_z is not a number");
  expectBadInput(good + "2 0 0 0 1.0.0 1 1\n", 4, "max_x is not a number");
  expectBadInput(good + "2,,0,0,1,1,1\n", 4, "empty field");
  expectBadInput(good + "1 0 0 0 1 1 1\n", 4, "duplicate id 1");
  expectBadInput(good + "4294967296 0 0 0 1 1 1\n", 4, "id out of range");
  expectBadInput(good + "-3 0 0 0 1 1 1\n", 4, "id out of range");
  expectBadInput(good + "2.5 0 0 0 1 1 1\n", 4, "id is not a decimal integer");
  expectBadInput("x\n", 1, "expected 7 fields");
  expectBadInput(good + std::string(kMaxTextLineBytes + 1, ' ') + "\n", 4, "line longer than");
}

// Issue 29: `sap_pairs /dev/zero` read one endless line until memory ran out. The line is
// refused once it passes kMaxTextLineBytes, while it is being read.
TEST(Cli, AnEndlessLineIsRefusedWhileBeingRead) {
  TempDir dir;
  const RunResult result = runPairs(dir, {"/dev/zero"});
  EXPECT_EQ(result.status, 2) << result.err;
  EXPECT_EQ(result.out, "");
  EXPECT_NE(result.err.find("/dev/zero:1: line longer than"), std::string::npos) << result.err;
}

TEST(Cli, UnreadableFileExitsTwo) {
  TempDir dir;
  const std::string missing = dir.file("missing.txt");
  const RunResult absent = runPairs(dir, {missing});
  EXPECT_EQ(absent.status, 2);
  EXPECT_EQ(absent.out, "");
  EXPECT_EQ(absent.err.rfind(missing + ":0: cannot open", 0), 0u) << absent.err;
  const RunResult directory = runPairs(dir, {dir.path()});
  EXPECT_EQ(directory.status, 2);
  EXPECT_EQ(directory.out, "");
  EXPECT_EQ(directory.err.rfind(dir.path() + ":0: ", 0), 0u) << directory.err;
  if (geteuid() != 0) {  // root reads files whatever their mode
    const std::string locked = dir.file("locked.txt");
    writeFile(locked, "1 0 0 0 1 1 1\n");
    chmod(locked.c_str(), 0);
    const RunResult denied = runPairs(dir, {locked});
    EXPECT_EQ(denied.status, 2);
    EXPECT_EQ(denied.out, "");
    EXPECT_EQ(denied.err.rfind(locked + ":0: cannot open", 0), 0u) << denied.err;
  }
}

/// Expects inArgs to be refused as bad usage: exit 2, empty stdout, a usage text on stderr.
void expectBadUsage(const std::string& inExe, const std::vector<std::string>& inArgs,
                    const std::string& inWords) {
  TempDir dir;
  const std::string path = dir.file("boxes.txt");
  writeFile(path, "1 0 0 0 1 1 1\n");
  const RunResult result = runTool(dir, inExe, inArgs, path);
  std::string joined;
  for (const std::string& arg : inArgs) joined += arg + " ";
  EXPECT_EQ(result.status, 2) << joined;
  EXPECT_EQ(result.out, "") << joined;
  EXPECT_NE(result.err.find("usage:"), std::string::npos) << joined << ": " << result.err;
  EXPECT_NE(result.err.find(inWords), std::string::npos) << joined << ": " << result.err;
}

TEST(Cli, BadUsageOfSapPairsExitsTwo) {
  const std::string exe = SAP_PAIRS_EXE;
  expectBadUsage(exe, {"--frobnicate"}, "unknown option '--frobnicate'");
  expectBadUsage(exe, {"-x"}, "unknown option");
  expectBadUsage(exe, {"--threads", "0"}, "bad --threads value '0'");
  expectBadUsage(exe, {"--threads", "-2"}, "bad --threads");
  expectBadUsage(exe, {"--threads", "two"}, "bad --threads");
  expectBadUsage(exe, {"--threads", "1.5"}, "bad --threads");
  expectBadUsage(exe, {"--threads=99999"}, "bad --threads");
  expectBadUsage(exe, {"--max-pairs", "0"},
                 "bad --max-pairs value '0' (an integer from 1 to 2^53)");
  expectBadUsage(exe, {"--max-pairs", "-1"}, "bad --max-pairs");
  expectBadUsage(exe, {"--max-pairs=9007199254740993"}, "bad --max-pairs");
  // Issue 29: 999 threads took 110 s instead of 0.25 s on 2 cores. At most 4 a processor.
  expectBadUsage(exe, {"--threads", std::to_string(maxThreads() + 1)}, "bad --threads");
  expectBadUsage(exe, {"--threads", "999999"}, "at most " + std::to_string(maxThreads()));
  expectBadUsage(exe, {"--threads"}, "--threads needs a value");
  expectBadUsage(exe, {"--method", "quick"}, "bad --method value 'quick'");
  expectBadUsage(exe, {"--method"}, "needs a value");
  expectBadUsage(exe, {"--count=yes"}, "--count takes no value");
  expectBadUsage(exe, {"a.txt", "b.txt"}, "more than one input file");
}

TEST(Cli, BadUsageOfSapSceneExitsTwo) {
  const std::string exe = SAP_SCENE_EXE;
  expectBadUsage(exe, {"--scene", "cube"}, "bad --scene value 'cube'");
  expectBadUsage(exe, {"--n", "-1"}, "bad --n");
  expectBadUsage(exe, {"--n", "ten"}, "bad --n");
  expectBadUsage(exe, {"--density", "0"}, "bad --density");
  expectBadUsage(exe, {"--density", "inf"}, "bad --density");
  expectBadUsage(exe, {"--density", "nan"}, "bad --density");
  expectBadUsage(exe, {"--frame", "-1"}, "bad --frame");
  expectBadUsage(exe, {"--seed", "-5"}, "bad --seed");
  expectBadUsage(exe, {"--axis", "w"}, "bad --axis");
  expectBadUsage(exe, {"--frames", "1"}, "bad --frames");
  expectBadUsage(exe, {"--bogus"}, "unknown option");
  expectBadUsage(exe, {"extra"}, "unexpected argument");
  expectBadUsage(exe, {"--n"}, "needs a value");
}

TEST(Cli, EqualsFormAndOptionOrderDoNotMatter) {
  TempDir dir;
  const std::string path = dir.file("boxes.txt");
  writeFile(path, "3 0 0 0 1 1 1\n1 1 1 1 2 2 2\n2 1 0 0 3 0 0\n");
  const RunResult a = runPairs(dir, {"--threads=3", "--method=sequential", path});
  const RunResult b = runPairs(dir, {path, "--method", "brute", "--threads", "1"});
  EXPECT_EQ(a.status, 0);
  EXPECT_EQ(a.out, "1 3\n2 3\n");
  EXPECT_EQ(b.out, a.out);
}

}  // namespace
}  // namespace sap_broadphase
