// The distributed broad phase under mpirun on this machine (ranks on shared memory, no
// network): the exactness checks of distributed_check for 1 to 4 ranks and 1 or 2 threads a
// rank, and sap_pairs_mpi against sap_pairs byte for byte, exit statuses included.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "test_files.h"

namespace {

using sap_broadphase::test_files::commandLine;
using sap_broadphase::test_files::runCommand;
using sap_broadphase::test_files::RunResult;
using sap_broadphase::test_files::shellQuote;
using sap_broadphase::test_files::TempDir;
using sap_broadphase::test_files::writeFile;

/// The mpirun prefix for inRanks local ranks: more ranks than cores allowed, no binding (the
/// ranks' threads share the cores), shared memory only (no network needed), root allowed
/// (containers), waiting ranks yield the core to working ones, and a time limit so that a hung
/// collective fails the test instead of the run.
std::string mpirunPrefix(int inRanks) {
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout -k 10 300 " +
         shellQuote(SAP_MPIEXEC) +
         " --oversubscribe --bind-to none --mca btl self,vader --mca mpi_yield_when_idle 1 -np " +
         std::to_string(inRanks) + " ";
}

RunResult runPairs(const TempDir& inDir, const std::vector<std::string>& inArgs) {
  return runCommand(inDir, commandLine(SAP_PAIRS_EXE, inArgs));
}

RunResult runPairsMpi(const TempDir& inDir, int inRanks, const std::vector<std::string>& inArgs) {
  return runCommand(inDir, mpirunPrefix(inRanks) + commandLine(SAP_PAIRS_MPI_EXE, inArgs));
}

/// Ranks and threads a rank.
class DistributedExactness : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(DistributedExactness, EveryRankGetsExactlyTheOraclePairs) {
  const auto [ranks, threads] = GetParam();
  TempDir dir;
  const RunResult run = runCommand(dir, mpirunPrefix(ranks) + shellQuote(DISTRIBUTED_CHECK_EXE) +
                                            " --threads " + std::to_string(threads));
  EXPECT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find(": 0 mismatching frames"), std::string::npos) << run.out << run.err;
}

INSTANTIATE_TEST_SUITE_P(RanksAndThreads, DistributedExactness,
                         ::testing::Combine(::testing::Values(1, 2, 3, 4), ::testing::Values(1, 2)),
                         [](const ::testing::TestParamInfo<std::tuple<int, int>>& inInfo) {
                           return std::to_string(std::get<0>(inInfo.param)) + "ranks_" +
                                  std::to_string(std::get<1>(inInfo.param)) + "threads";
                         });

/// A scene and the edge cases of the format: touching faces, -0, infinities, spanning boxes.
std::string edgeCaseBoxes() {
  std::string text = "# touching faces on integer x, -0 against 0, infinities\n";
  int id = 1;
  for (int x = -4; x < 4; ++x) {
    for (int y = 0; y < 3; ++y) {
      text += std::to_string(id++) + " " + (x == 0 ? "-0.0" : std::to_string(x)) + " " +
              std::to_string(y) + " 0 " + std::to_string(x + 1) + " " + std::to_string(y + 1) +
              " 1\n";
    }
  }
  text += "900 -inf 0.5 0.5 inf 0.6 0.6\n";
  text += "901 -inf -inf -inf inf inf inf\n";
  text += "902, 3, 0, 0, inf, 1, 1\n";
  text += "903 -1e308 2 0 1e308 2.5 0.5\n";
  text += "904 0 0 0 0 0 0\n";
  return text;
}

/// A uniform scene as sap_scene writes it (made here, so the test needs no other tool).
std::string uniformBoxes(int inCount) {
  std::string text;
  unsigned state = 12345;
  const auto next = [&state]() {
    state = state * 1103515245u + 12345u;
    return static_cast<double>((state >> 8) & 0xFFFF) / 65536.0;
  };
  for (int id = 0; id < inCount; ++id) {
    const double x = next() * 40, y = next() * 40, z = next() * 40;
    char line[160];
    std::snprintf(line, sizeof line, "%d %.17g %.17g %.17g %.17g %.17g %.17g\n", id * 3 + 7, x, y,
                  z, x + 0.5 + next() * 2, y + 0.5 + next() * 2, z + 0.5 + next() * 2);
    text += line;
  }
  return text;
}

TEST(SapPairsMpi, SameOutputAsSapPairsOnEveryRankCount) {
  TempDir dir;
  writeFile(dir.file("edge.txt"), edgeCaseBoxes());
  writeFile(dir.file("uniform.txt"), uniformBoxes(6000));
  writeFile(dir.file("empty.txt"), "# nothing\n");
  for (const std::string name : {"edge.txt", "uniform.txt", "empty.txt"}) {
    const RunResult expected = runPairs(dir, {dir.file(name)});
    ASSERT_EQ(expected.status, 0) << expected.err;
    for (int ranks = 1; ranks <= 4; ++ranks) {
      const RunResult got = runPairsMpi(dir, ranks, {"--threads", "1", dir.file(name)});
      EXPECT_EQ(got.status, 0) << name << " on " << ranks << " ranks: " << got.err;
      EXPECT_TRUE(got.out == expected.out)
          << name << " on " << ranks << " ranks: " << got.out.size() << " bytes, sap_pairs "
          << expected.out.size();
    }
  }
  // --count once per rank count: the same number as sap_pairs.
  const RunResult expectedCount = runPairs(dir, {"--count", dir.file("uniform.txt")});
  for (int ranks = 1; ranks <= 4; ++ranks) {
    const RunResult count = runPairsMpi(dir, ranks, {"--count", dir.file("uniform.txt")});
    EXPECT_EQ(count.status, 0) << count.err;
    EXPECT_EQ(count.out, expectedCount.out) << ranks << " ranks";
  }
}

TEST(SapPairsMpi, BadInputExitsTwoWithTheSameMessageAndNoOutput) {
  TempDir dir;
  writeFile(dir.file("bad.txt"), "1 0 0 0 1 1 1\n2 0 3 0 1 2 1\n");
  writeFile(dir.file("dup.txt"), "5 0 0 0 1 1 1\n5 0 0 0 1 1 1\n");
  for (const std::string name : {"bad.txt", "dup.txt", "missing.txt"}) {
    const RunResult expected = runPairs(dir, {dir.file(name)});
    ASSERT_EQ(expected.status, 2);
    const RunResult got = runPairsMpi(dir, 3, {dir.file(name)});
    EXPECT_EQ(got.status, 2) << got.err;
    EXPECT_EQ(got.out, "");
    // sap_pairs' message, whole lines, among whatever mpirun and its libraries add to stderr
    // (hwloc warns where /sys is not mounted, as in a chroot).
    const std::string expectedLines = "\n" + expected.err;
    EXPECT_NE(("\n" + got.err).find(expectedLines), std::string::npos)
        << "sap_pairs said: " << expected.err << "sap_pairs_mpi said: " << got.err;
  }
}

TEST(SapPairsMpi, BadUsageExitsTwo) {
  TempDir dir;
  const RunResult got = runPairsMpi(dir, 2, {"--threads", "0", "x"});
  EXPECT_EQ(got.status, 2);
  EXPECT_EQ(got.out, "");
  EXPECT_NE(got.err.find("sap_pairs_mpi: bad --threads value '0'"), std::string::npos) << got.err;
  const RunResult help = runPairsMpi(dir, 2, {"--help"});
  EXPECT_EQ(help.status, 0);
  EXPECT_EQ(help.out.rfind("usage: mpirun -np R sap_pairs_mpi", 0), 0u) << help.out;
}

}  // namespace
