// Box queries (Broadphase::query): batches of 1, 100 and 10 000 query boxes against a 2^20-box
// world (uniform, d = 0.05), on the engine's default configuration, beside FCL's dynamic AABB
// tree answering the same batch (a manager of the batch collided against the world's manager,
// the world's tree built beforehand). Ours is timed twice: the first query after an update()
// (a few boxes scan the frame; a large batch builds the frame's index first), and with the
// frame's index already built, batches asked back to back as FCL's are. Every answer is
// checked against ours.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "bench_output.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "experiments.h"
#include "peers/peer.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/scenes.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;
using sap_broadphase::QueryHitList;

// The first inCount boxes of another scene of the same kind: query boxes the size of the
// world's, spread over the same volume.
BoxSet queryBatch(const BoxSet& inOther, std::size_t inCount) {
  BoxSet batch;
  for (std::size_t q = 0; q < inCount; ++q) {
    const double lo[3] = {inOther.lo(0, q), inOther.lo(1, q), inOther.lo(2, q)};
    const double hi[3] = {inOther.hi(0, q), inOther.hi(1, q), inOther.hi(2, q)};
    batch.add(static_cast<uint32_t>(q), lo, hi);
  }
  return batch;
}

struct Timings {
  std::vector<double> first, indexed;
  QueryHitList hits;
};

// ms of inBatch's query right after an update() of inWorld (the frame's first query), and with
// the frame's index built (a 10 000-box batch asked first builds it), asked inRuns times in a
// row as FCL's batches are.
Timings timeOurs(Broadphase& ioEngine, const BoxSet& inWorld, const BoxSet& inBatch,
                 const BoxSet& inIndexBuilder, int inRuns) {
  Timings timings;
  for (int run = 0; run < inRuns; ++run) {
    ioEngine.update(inWorld);  // the same frame again: its pairs are reused, the index forgotten
    Stopwatch first;
    timings.hits = ioEngine.query(inBatch);
    timings.first.push_back(first.ms());
  }
  ioEngine.query(inIndexBuilder);
  for (int run = 0; run < inRuns; ++run) {
    Stopwatch indexed;
    ioEngine.query(inBatch);
    timings.indexed.push_back(indexed.ms());
  }
  return timings;
}

}  // namespace

void runQuery(const Options& inOptions) {
  const std::size_t world_boxes = inOptions.size(std::size_t{1} << 20, std::size_t{1} << 14);
  const double density = 0.05;
  const BoxSet world =
      sap_broadphase::makeSceneFrame(uniformScene(world_boxes, density, inOptions.seed), 0);
  const BoxSet other =
      sap_broadphase::makeSceneFrame(uniformScene(world_boxes, density, inOptions.seed + 1), 0);
  const std::vector<std::size_t> batch_sizes = {1, 100, std::min<std::size_t>(10000, world_boxes)};
  const BoxSet index_builder = queryBatch(other, batch_sizes.back());
  const int runs = inOptions.runsOr(5);

  BroadphaseConfig config;
  config.threads = inOptions.threads;
  Broadphase engine(config);
  engine.update(world);
  std::string fcl_build_ms = "-";
#ifdef SAP_BENCH_WITH_FCL
  FclTreeQuery fcl(world);
  fcl_build_ms = fmt(fcl.worldBuildMs());
#endif

  Table table(
      "Box queries against a " + fmtSize(world_boxes) +
          "-box world (uniform, d = 0.05): ms per batch, median of " + std::to_string(runs) +
          " runs",
      {"queries", "hits", "ours_first_ms", "ours_indexed_ms", "fcl_tree_ms", "fcl_collide_ms",
       "fcl_over_first", "fcl_over_indexed", "fcl_hits", "fcl_world_build_ms"});
  for (std::size_t count : batch_sizes) {
    const BoxSet batch = queryBatch(other, count);
    const Timings ours = timeOurs(engine, world, batch, index_builder, runs);
    std::string fcl_ms = "-", fcl_collide_ms = "-", over_first = "-", over_indexed = "-";
    std::string fcl_hits = "not built";
#ifdef SAP_BENCH_WITH_FCL
    std::vector<double> fcl_total, fcl_collide;
    QueryHitList fcl_answer;
    for (int run = 0; run < runs; ++run) {
      FclTreeQuery::Answer answer = fcl.query(batch);
      fcl_total.push_back(answer.ms);
      fcl_collide.push_back(answer.ms_collide);
      fcl_answer = std::move(answer.hits);
    }
    std::sort(fcl_answer.begin(), fcl_answer.end());
    fcl_ms = fmt(median(fcl_total));
    fcl_collide_ms = fmt(median(fcl_collide));
    over_first = fmtRatio(median(fcl_total), median(ours.first));
    over_indexed = fmtRatio(median(fcl_total), median(ours.indexed));
    fcl_hits = fcl_answer == ours.hits ? "same"
                                       : "differ (" + std::to_string(fcl_answer.size()) +
                                             " against " + std::to_string(ours.hits.size()) + ")";
#endif
    table.addRow({fmtCount(count), fmtCount(ours.hits.size()), fmt(median(ours.first)),
                  fmt(median(ours.indexed)), fcl_ms, fcl_collide_ms, over_first, over_indexed,
                  fcl_hits, fcl_build_ms});
  }
  publish(inOptions, table, "query");
}

}  // namespace sap_bench
