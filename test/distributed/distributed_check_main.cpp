// distributed_check: run under mpirun by test_distributed. Every rank builds the same scenes
// from fixed seeds, keeps its share of the boxes (by a distribution rule), and the distributed
// broad phase's pairs are compared, frame by frame, with the brute-force oracle on the whole
// scene: each rank's pairs must be exactly the oracle's pairs that involve its boxes, and the
// gathered list exactly the oracle's list. Prints every mismatch; exits 1 on any.
//
// Usage: mpirun -np R distributed_check [--threads T]
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <unordered_set>
#include <vector>

#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/scenes.h"
#include "sap_broadphase/distributed/distributed_broadphase.h"

namespace {

using namespace sap_broadphase;
using distributed::DistributedBroadphase;
using distributed::DistributedConfig;
using distributed::PairDelivery;
using distributed::SlabBalance;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// splitmix64: fixed-seed randomness, the same on every rank and platform.
struct SplitMix {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double range(double inLo, double inHi) { return inLo + (inHi - inLo) * unit(); }
};

/// Which rank holds each box of the whole scene.
enum class Distribution { kRoundRobin, kBlocks, kAllOnFirst, kAllOnLast, kEvenRanksOnly, kSpatial };

const char* distributionName(Distribution inRule) {
  switch (inRule) {
    case Distribution::kRoundRobin:
      return "round-robin";
    case Distribution::kBlocks:
      return "blocks";
    case Distribution::kAllOnFirst:
      return "all-on-rank-0";
    case Distribution::kAllOnLast:
      return "all-on-last-rank";
    case Distribution::kEvenRanksOnly:
      return "even-ranks-only";
    case Distribution::kSpatial:
      return "spatial";
  }
  return "?";
}

int holderOf(Distribution inRule, const BoxSet& inAll, std::size_t i, int inRanks) {
  switch (inRule) {
    case Distribution::kRoundRobin:
      return static_cast<int>(i % inRanks);
    case Distribution::kBlocks:
      return static_cast<int>(i * inRanks / inAll.size());
    case Distribution::kAllOnFirst:
      return 0;
    case Distribution::kAllOnLast:
      return inRanks - 1;
    case Distribution::kEvenRanksOnly:
      return static_cast<int>((i % ((inRanks + 1) / 2)) * 2);
    case Distribution::kSpatial: {
      // By the sign pattern of x: ranks hold x-bands, infinite boxes the end ones.
      const double x = inAll.lo(0, i);
      const int band = x < -2 ? 0 : x < 0 ? 1 : x < 2 ? 2 : 3;
      return band % inRanks;
    }
  }
  return 0;
}

/// This rank's boxes of inAll under inRule, in the order of inAll.
BoxSet myShare(const BoxSet& inAll, Distribution inRule, int inRank, int inRanks) {
  BoxSet mine;
  for (std::size_t i = 0; i < inAll.size(); ++i) {
    if (holderOf(inRule, inAll, i, inRanks) != inRank) continue;
    const double lo[3] = {inAll.lo(0, i), inAll.lo(1, i), inAll.lo(2, i)};
    const double hi[3] = {inAll.hi(0, i), inAll.hi(1, i), inAll.hi(2, i)};
    if (inAll.hasFilters())
      mine.add(inAll.ids[i], lo, hi, inAll.group(i), inAll.mask(i));
    else
      mine.add(inAll.ids[i], lo, hi);
  }
  return mine;
}

void addBox(BoxSet& ioBoxes, uint32_t inId, double x0, double y0, double z0, double x1, double y1,
            double z1) {
  const double lo[3] = {x0, y0, z0};
  const double hi[3] = {x1, y1, z1};
  ioBoxes.add(inId, lo, hi);
}

/// Unit cubes on an integer lattice touching face to face, and zero-width boxes at integer x:
/// the sample puts slab borders on integers, where faces touch and -0.0 meets 0.0.
BoxSet touchingLattice() {
  BoxSet boxes;
  uint32_t id = 0;
  for (int x = -6; x < 6; ++x) {
    for (int y = 0; y < 5; ++y) {
      for (int z = 0; z < 3; ++z) {
        const double x0 = x == 0 ? -0.0 : x;
        const double x1 = x + 1 == 0 ? -0.0 : x + 1;
        addBox(boxes, id++, x0, y, z, x1, y + 1, z + 1);
      }
    }
  }
  for (int x = -6; x <= 6; ++x) {
    for (int k = 0; k < 20; ++k) {
      const double at = x == 0 && k % 2 ? -0.0 : x;
      addBox(boxes, id++, at, 0.25 * (k % 5), 0.5 * (k % 3), at, 0.25 * (k % 5) + 0.5,
             0.5 * (k % 3) + 0.25);
    }
  }
  return boxes;
}

/// Small boxes plus boxes spanning every slab, infinite boxes and boxes with huge bounds.
BoxSet spanningAndInfinite(uint64_t inSeed) {
  SplitMix random{inSeed};
  BoxSet boxes;
  uint32_t id = 100;
  for (int k = 0; k < 600; ++k) {
    const double x = random.range(-8, 8), y = random.range(0, 4), z = random.range(0, 4);
    addBox(boxes, id++, x, y, z, x + random.range(0, 0.6), y + random.range(0, 0.6),
           z + random.range(0, 0.6));
  }
  for (int k = 0; k < 12; ++k) {  // across the whole x range, thin in y and z
    const double y = random.range(0, 4), z = random.range(0, 4);
    addBox(boxes, id++, -9, y, z, 9, y + 0.3, z + 0.3);
  }
  addBox(boxes, id++, -kInf, 1, 1, kInf, 1.5, 1.5);            // the whole x axis
  addBox(boxes, id++, -kInf, -kInf, -kInf, kInf, kInf, kInf);  // everything
  addBox(boxes, id++, -kInf, 2, 2, -3, 2.5, 2.5);              // x from -inf
  addBox(boxes, id++, 3, 0, 0, kInf, 0.5, 0.5);                // x to +inf
  addBox(boxes, id++, kInf, 0, 0, kInf, 4, 4);                 // at +inf only
  addBox(boxes, id++, -kInf, 0, 0, -kInf, 4, 4);               // at -inf only
  addBox(boxes, id++, -1.7976931348623157e308, 0, 0, 1.7976931348623157e308, 0.1, 0.1);
  return boxes;
}

/// Random groups and masks on a uniform scene.
BoxSet withFilters(BoxSet inBoxes, uint64_t inSeed) {
  SplitMix random{inSeed};
  inBoxes.groups.resize(inBoxes.size());
  inBoxes.masks.resize(inBoxes.size());
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    inBoxes.groups[i] = 1u << (random.next() % 4);
    inBoxes.masks[i] = static_cast<uint32_t>(random.next() % 16);  // 0: pairs with nothing
  }
  return inBoxes;
}

/// Every box moved by up to inStep on each axis (infinite bounds stay infinite).
void jitter(BoxSet& ioBoxes, double inStep, SplitMix& ioRandom) {
  for (std::size_t i = 0; i < ioBoxes.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      const double d = ioRandom.range(-inStep, inStep);
      ioBoxes.lo(a, i) += d;
      ioBoxes.hi(a, i) += d;
    }
  }
}

/// A scene: its frames, produced one at a time.
struct Scenario {
  std::string name;
  std::function<BoxSet(int)> frame;  ///< the whole scene at frame f
  int frames;
};

std::vector<Scenario> scenarios() {
  std::vector<Scenario> all;
  const auto sceneFrames = [](SceneKind inKind, std::size_t inN, int inFirst) {
    return [=](int inFrame) {
      SceneConfig config;
      config.kind = inKind;
      config.n = inN;
      config.seed = 7;
      config.frames = 40;
      config.speed = 0.5;
      return makeSceneFrame(config, inFirst + inFrame);
    };
  };
  all.push_back({"uniform", sceneFrames(SceneKind::kUniform, 3000, 0), 4});
  all.push_back({"ball", sceneFrames(SceneKind::kBallCluster, 2000, 6), 3});
  all.push_back({"plane", sceneFrames(SceneKind::kPlaneCluster, 1600, 18), 3});
  all.push_back({"touching-lattice",
                 [](int inFrame) {
                   BoxSet boxes = touchingLattice();
                   if (inFrame == 2) {  // a frame where every box moves by a whole cell in x
                     for (std::size_t i = 0; i < boxes.size(); ++i) {
                       boxes.lo(0, i) += 1;
                       boxes.hi(0, i) += 1;
                     }
                   }
                   return boxes;  // frames 0, 1, 3: unchanged (nothing re-sent)
                 },
                 4});
  all.push_back({"spanning-infinite",
                 [](int inFrame) {
                   BoxSet boxes = spanningAndInfinite(11);
                   SplitMix random{static_cast<uint64_t>(100 + inFrame)};
                   for (int f = 0; f < inFrame; ++f) jitter(boxes, 0.3, random);
                   return boxes;
                 },
                 3});
  all.push_back({"groups-masks",
                 [](int inFrame) {
                   SceneConfig config;
                   config.n = 2500;
                   config.seed = 3;
                   config.speed = 0.5;
                   return withFilters(makeSceneFrame(config, inFrame), 5);
                 },
                 3});
  all.push_back({"changing-ids",
                 [](int inFrame) {
                   // Boxes leave and join between frames (ids kept increasing: matched by a
                   // merge), and on frame 2 the ids come in reverse (matched by a hash).
                   SceneConfig config;
                   config.n = 2000;
                   config.seed = 9;
                   config.speed = 0.5;
                   const BoxSet frame = makeSceneFrame(config, inFrame);
                   BoxSet kept;
                   for (std::size_t k = 0; k < frame.size(); ++k) {
                     const std::size_t i = inFrame == 2 ? frame.size() - 1 - k : k;
                     if ((frame.ids[i] + inFrame) % 7 == 0) continue;
                     const double lo[3] = {frame.lo(0, i), frame.lo(1, i), frame.lo(2, i)};
                     const double hi[3] = {frame.hi(0, i), frame.hi(1, i), frame.hi(2, i)};
                     kept.add(frame.ids[i], lo, hi);
                   }
                   return kept;
                 },
                 5});
  all.push_back({"empty", [](int) { return BoxSet(); }, 2});
  return all;
}

/// The oracle's pairs of the whole scene.
PairList oraclePairs(const BoxSet& inAll) {
  BroadphaseConfig config;
  config.method = Method::kBruteForce;
  config.threads = 1;
  Broadphase oracle(config);
  return oracle.update(inAll);
}

/// The pairs of inPairs with at least one box in inMine.
PairList involving(const PairList& inPairs, const BoxSet& inMine) {
  const std::unordered_set<uint32_t> mine(inMine.ids.begin(), inMine.ids.end());
  PairList out;
  for (const IdPair& pair : inPairs) {
    if (mine.count(pair.a) || mine.count(pair.b)) out.push_back(pair);
  }
  return out;
}

/// "" when equal, else what differs.
std::string compare(const PairList& inExpected, const PairList& inGot) {
  if (inExpected == inGot) return "";
  std::string text = "expected " + std::to_string(inExpected.size()) + " pairs, got " +
                     std::to_string(inGot.size());
  PairList missing, extra;
  std::set_difference(inExpected.begin(), inExpected.end(), inGot.begin(), inGot.end(),
                      std::back_inserter(missing));
  std::set_difference(inGot.begin(), inGot.end(), inExpected.begin(), inExpected.end(),
                      std::back_inserter(extra));
  if (!missing.empty())
    text += "; missing (" + std::to_string(missing[0].a) + ", " + std::to_string(missing[0].b) +
            ") and " + std::to_string(missing.size() - 1) + " more";
  if (!extra.empty())
    text += "; extra (" + std::to_string(extra[0].a) + ", " + std::to_string(extra[0].b) +
            ") and " + std::to_string(extra.size() - 1) + " more";
  if (missing.empty() && extra.empty()) text += "; same pairs, wrong order or duplicates";
  return text;
}

/// A scenario's frames and the oracle's pairs of each, made once for all its runs.
struct ScenarioFrames {
  std::vector<BoxSet> frames;
  std::vector<PairList> expected;
};

ScenarioFrames makeFrames(const Scenario& inScenario) {
  ScenarioFrames made;
  for (int frame = 0; frame < inScenario.frames; ++frame) {
    made.frames.push_back(inScenario.frame(frame));
    made.expected.push_back(oraclePairs(made.frames.back()));
  }
  return made;
}

/// Runs one scenario under one distribution and configuration; returns this rank's failures.
int checkScenario(const Scenario& inScenario, const ScenarioFrames& inFrames, Distribution inRule,
                  const DistributedConfig& inConfig, const std::string& inConfigName, int inRank,
                  int inRanks) {
  DistributedBroadphase broadphase(MPI_COMM_WORLD, inConfig);
  int failures = 0;
  for (int frame = 0; frame < inScenario.frames; ++frame) {
    const BoxSet& all = inFrames.frames[frame];
    const BoxSet mine = myShare(all, inRule, inRank, inRanks);
    const PairList& expected = inFrames.expected[frame];
    // Alternate the deliveries, so that both see moving frames.
    const bool gather = frame % 2 == 1;
    const PairList got = broadphase.update(
        mine, gather ? PairDelivery::kGatherAtRoot : PairDelivery::kToOwners, inRanks - 1);
    std::string problem;
    if (!gather)
      problem = compare(involving(expected, mine), got);
    else
      problem = compare(inRank == inRanks - 1 ? expected : PairList(), got);
    if (problem.empty()) continue;
    ++failures;
    std::printf("FAIL %s / %s / %s frame %d rank %d of %d (%s): %s\n", inScenario.name.c_str(),
                distributionName(inRule), inConfigName.c_str(), frame, inRank, inRanks,
                gather ? "gathered" : "to owners", problem.c_str());
  }
  return failures;
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  int rank = 0;
  int ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int threads = 1;
  for (int k = 1; k + 1 < argc; ++k) {
    if (std::string(argv[k]) == "--threads") threads = std::atoi(argv[k + 1]);
  }

  struct NamedConfig {
    std::string name;
    DistributedConfig config;
  };
  std::vector<NamedConfig> configs;
  DistributedConfig plain;
  plain.engine.threads = threads;
  configs.push_back({"count-balanced", plain});
  DistributedConfig everyFrame = plain;  // cost-balanced, re-cut every frame, few samples
  everyFrame.balance = SlabBalance::kCost;
  everyFrame.recut_imbalance = 0.0;
  everyFrame.samples_per_rank = 3;
  configs.push_back({"cost-recut-each-frame", everyFrame});
  DistributedConfig parallelY = plain;  // slabs on y, the parallel path forced
  parallelY.slab_axis = 1;
  parallelY.engine.method = Method::kParallel;
  configs.push_back({"y-slabs-parallel", parallelY});

  const Distribution rules[] = {Distribution::kRoundRobin,    Distribution::kBlocks,
                                Distribution::kAllOnFirst,    Distribution::kAllOnLast,
                                Distribution::kEvenRanksOnly, Distribution::kSpatial};
  int failures = 0;
  int runs = 0;
  for (const Scenario& scenario : scenarios()) {
    const ScenarioFrames frames = makeFrames(scenario);
    for (const NamedConfig& named : configs) {
      for (Distribution rule : rules) {
        // Every distribution on the plain configuration; the others on two of them.
        if (named.name != "count-balanced" && rule != Distribution::kRoundRobin &&
            rule != Distribution::kSpatial)
          continue;
        failures += checkScenario(scenario, frames, rule, named.config, named.name, rank, ranks);
        ++runs;
      }
    }
  }
  int total = 0;
  MPI_Allreduce(&failures, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0)
    std::printf("%d scenario runs on %d ranks x %d threads: %d mismatching frames\n", runs, ranks,
                threads, total);
  MPI_Finalize();
  return total == 0 ? 0 : 1;
}
