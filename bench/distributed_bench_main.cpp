// sap_bench_distributed: the worker of `sap_bench -e distributed`, run under mpirun (sap_bench
// starts it; it can also be run by hand). A uniform scene as a spatially decomposed simulation
// holds it: each rank owns the bodies whose centre lies in its slab, moves them, and after
// the first frame, and every --migrate-every frames, hands the bodies that left its slab to
// their new rank (the simulation's own migration, timed apart). Prints one RESULT line
// (rank 0) with the averages over the frames after the first three.
//
// usage: mpirun -np R sap_bench_distributed --n N [--frames F] [--threads T]
//                         [--motion EDGES] [--density D] [--seed S] [--migrate-every M]
#include <mpi.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "sap_broadphase/distributed/distributed_broadphase.h"

namespace {

using namespace sap_broadphase;
using distributed::DistributedBroadphase;
using distributed::DistributedConfig;
using distributed::DistributedReport;
using distributed::PairDelivery;

/// Bytes of one box as a BoxSet without groups or masks holds it (id + six float64 bounds):
/// the unit of "bytes exchanged per frame, as a share of the frame's boxes".
constexpr double kBoxBytes = 4 + 6 * 8;

/// Frames before the steady state: the cold start (the cut, every ghost sent), the frame after
/// the bodies first migrated to the slabs the cut chose (new ids on every rank: the own
/// engine sweeps afresh), and the frame where the own engine builds its kept candidates.
constexpr int kWarmupFrames = 3;

struct Options {
  uint64_t n = 1u << 20;
  int frames = 6;  ///< frames in all, kWarmupFrames of them before the steady state
  int threads = 1;
  double motion = 0.01;  ///< distance a frame, in mean box edges (the mean edge is 1)
  double density = 0.05;
  uint64_t seed = 1;
  /// Frames between the simulation's migrations (after the first frame, then every so many),
  /// as LAMMPS-style codes re-neighbour every 10 to 20 steps; between them a body that left
  /// its slab stays with its rank and its box is sent to the slab it is in.
  int migrate_every = 10;
};

/// splitmix64 of (seed, id, stream): the same body on every rank.
double unitHash(uint64_t inSeed, uint64_t inId, uint64_t inStream) {
  uint64_t z = inSeed * 0x9e3779b97f4a7c15ull + inId * 0xbf58476d1ce4e5b9ull + inStream + 1;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

/// The bodies a rank owns: boxes (sorted by id) and their velocities.
struct Bodies {
  BoxSet boxes;
  std::vector<double> velocity[3];
  std::size_t size() const { return boxes.size(); }
};

/// One body's record for migration.
struct BodyRecord {
  uint32_t id;
  uint32_t padding;
  double lo[3], hi[3], velocity[3];
};

/// The scene of the paper's §6 without its simulator's memory: body i's centre, edges (0.5 to
/// 1.5 per axis, mean volume 1) and direction come from hashes of i, in a cube of side
/// (n / density)^(1/3). This rank keeps the bodies whose centre is in x-band inRank of inRanks.
Bodies makeBodies(const Options& inOptions, double inWorld, int inRank, int inRanks) {
  Bodies bodies;
  for (uint64_t i = 0; i < inOptions.n; ++i) {
    const double x = unitHash(inOptions.seed, i, 0) * inWorld;
    const int band = std::min(static_cast<int>(x / inWorld * inRanks), inRanks - 1);
    if (band != inRank) continue;
    double centre[3] = {x, unitHash(inOptions.seed, i, 1) * inWorld,
                        unitHash(inOptions.seed, i, 2) * inWorld};
    double lo[3], hi[3], direction[3], norm = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double half = 0.25 + 0.5 * unitHash(inOptions.seed, i, 3 + a);
      lo[a] = centre[a] - half;
      hi[a] = centre[a] + half;
      direction[a] = unitHash(inOptions.seed, i, 6 + a) - 0.5;
      norm += direction[a] * direction[a];
    }
    bodies.boxes.add(static_cast<uint32_t>(i), lo, hi);
    for (int a = 0; a < 3; ++a)
      bodies.velocity[a].push_back(direction[a] / std::sqrt(norm) * inOptions.motion);
  }
  return bodies;
}

/// Moves every body one frame, bouncing off the walls of [0, inWorld]^3.
void moveBodies(Bodies& ioBodies, double inWorld) {
  const std::size_t n = ioBodies.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      double& v = ioBodies.velocity[a][i];
      if ((ioBodies.boxes.lo(a, i) + v < 0.0) || (ioBodies.boxes.hi(a, i) + v > inWorld)) v = -v;
      ioBodies.boxes.lo(a, i) += v;
      ioBodies.boxes.hi(a, i) += v;
    }
  }
}

void appendBody(Bodies& ioBodies, const BodyRecord& inBody) {
  ioBodies.boxes.add(inBody.id, inBody.lo, inBody.hi);
  for (int a = 0; a < 3; ++a) ioBodies.velocity[a].push_back(inBody.velocity[a]);
}

BodyRecord recordOf(const Bodies& inBodies, std::size_t i) {
  BodyRecord body{inBodies.boxes.ids[i], 0, {}, {}, {}};
  for (int a = 0; a < 3; ++a) {
    body.lo[a] = inBodies.boxes.lo(a, i);
    body.hi[a] = inBodies.boxes.hi(a, i);
    body.velocity[a] = inBodies.velocity[a][i];
  }
  return body;
}

/// The simulation's migration: bodies whose home rank changed go there; ids stay sorted.
void migrate(Bodies& ioBodies, const DistributedBroadphase& inBroadphase, MPI_Comm inComm) {
  const int ranks = inBroadphase.ranks();
  const int rank = inBroadphase.rank();
  std::vector<std::vector<BodyRecord>> leaving(static_cast<std::size_t>(ranks));
  std::vector<char> leaves(ioBodies.size(), 0);
  std::size_t leavingCount = 0;
  for (std::size_t i = 0; i < ioBodies.size(); ++i) {
    const int home = inBroadphase.homeRank(ioBodies.boxes.lo(0, i), ioBodies.boxes.hi(0, i));
    if (home == rank) continue;
    leaving[home].push_back(recordOf(ioBodies, i));
    leaves[i] = 1;
    ++leavingCount;
  }
  std::vector<int> sendCounts(ranks), receiveCounts(ranks), sendOffsets(ranks),
      receiveOffsets(ranks);
  std::vector<BodyRecord> sendBuffer;
  for (int r = 0; r < ranks; ++r) {
    sendOffsets[r] = static_cast<int>(sendBuffer.size() * sizeof(BodyRecord));
    sendCounts[r] = static_cast<int>(leaving[r].size() * sizeof(BodyRecord));
    sendBuffer.insert(sendBuffer.end(), leaving[r].begin(), leaving[r].end());
  }
  MPI_Alltoall(sendCounts.data(), 1, MPI_INT, receiveCounts.data(), 1, MPI_INT, inComm);
  int total = 0;
  for (int r = 0; r < ranks; ++r) {
    receiveOffsets[r] = total;
    total += receiveCounts[r];
  }
  std::vector<BodyRecord> arrived(static_cast<std::size_t>(total) / sizeof(BodyRecord));
  MPI_Alltoallv(sendBuffer.data(), sendCounts.data(), sendOffsets.data(), MPI_BYTE, arrived.data(),
                receiveCounts.data(), receiveOffsets.data(), MPI_BYTE, inComm);
  if (leavingCount == 0 && arrived.empty()) return;  // the usual frame: nobody moves house
  Bodies staying;
  for (std::size_t i = 0; i < ioBodies.size(); ++i) {
    if (!leaves[i]) appendBody(staying, recordOf(ioBodies, i));
  }
  if (arrived.empty()) {
    ioBodies = std::move(staying);
    return;
  }
  std::sort(arrived.begin(), arrived.end(),
            [](const BodyRecord& x, const BodyRecord& y) { return x.id < y.id; });
  Bodies merged;
  std::size_t k = 0;
  for (std::size_t i = 0; i < staying.size(); ++i) {
    while (k < arrived.size() && arrived[k].id < staying.boxes.ids[i])
      appendBody(merged, arrived[k++]);
    appendBody(merged, recordOf(staying, i));
  }
  while (k < arrived.size()) appendBody(merged, arrived[k++]);
  ioBodies = std::move(merged);
}

/// Sums and maxima over the steady frames.
struct Totals {
  int frames = 0;
  double ms_frame = 0, ms_exchange = 0, ms_engine = 0, ms_own = 0, ms_border = 0, ms_other = 0;
  double ms_migrate = 0;
  double box_bytes = 0, pair_bytes = 0, control_bytes = 0, boxes_sent = 0, imbalance = 0;
  double slab_boxes_max = 0, slab_boxes_sum = 0, border_boxes_max = 0, pairs = 0, recuts = 0;
};

double maxOver(double inValue, MPI_Comm inComm) {
  double out = 0;
  MPI_Allreduce(&inValue, &out, 1, MPI_DOUBLE, MPI_MAX, inComm);
  return out;
}

double sumOver(double inValue, MPI_Comm inComm) {
  double out = 0;
  MPI_Allreduce(&inValue, &out, 1, MPI_DOUBLE, MPI_SUM, inComm);
  return out;
}

bool parse(int argc, char** argv, Options& outOptions) {
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string name = argv[k];
    const char* value = argv[k + 1];
    if (name == "--n")
      outOptions.n = std::strtoull(value, nullptr, 10);
    else if (name == "--frames")
      outOptions.frames = std::atoi(value);
    else if (name == "--threads")
      outOptions.threads = std::atoi(value);
    else if (name == "--motion")
      outOptions.motion = std::atof(value);
    else if (name == "--density")
      outOptions.density = std::atof(value);
    else if (name == "--seed")
      outOptions.seed = std::strtoull(value, nullptr, 10);
    else if (name == "--migrate-every")
      outOptions.migrate_every = std::atoi(value);
    else
      return false;
  }
  return (argc % 2) == 1 && outOptions.n >= 2 && outOptions.n < (1ull << 31) &&
         outOptions.frames > kWarmupFrames && outOptions.threads >= 1;
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  Options options;
  if (!parse(argc, argv, options)) {
    if (rank == 0)
      std::fprintf(stderr,
                   "usage: mpirun -np R sap_bench_distributed --n N [--frames F>=4] "
                   "[--threads T] [--motion EDGES] [--density D] [--seed S] [--migrate-every M]\n");
    MPI_Finalize();
    return 2;
  }
  omp_set_num_threads(options.threads);
  const double world = std::cbrt(static_cast<double>(options.n) / options.density);
  Bodies bodies = makeBodies(options, world, rank, ranks);

  DistributedConfig config;
  config.engine.threads = options.threads;
  DistributedBroadphase broadphase(MPI_COMM_WORLD, config);
  Totals steady;
  double firstFrameBoxBytes = 0, firstFrameMs = 0, firstEngineMs = 0, afterMigrationMs = 0;
  for (int frame = 0; frame < options.frames; ++frame) {
    MPI_Barrier(MPI_COMM_WORLD);
    broadphase.update(bodies.boxes, PairDelivery::kToOwners);
    const DistributedReport& report = broadphase.stats();
    const double msFrame = maxOver(report.ms_total, MPI_COMM_WORLD);
    const double boxBytes = sumOver(static_cast<double>(report.box_bytes_sent), MPI_COMM_WORLD);
    if (frame == 0) {
      firstFrameBoxBytes = boxBytes;
      firstFrameMs = msFrame;
      firstEngineMs = maxOver(report.ms_engine, MPI_COMM_WORLD);
    }
    if (frame == 1) afterMigrationMs = msFrame;
    if (frame >= kWarmupFrames) {
      ++steady.frames;
      steady.ms_frame += msFrame;
      steady.ms_exchange += maxOver(report.ms_cut + report.ms_exchange, MPI_COMM_WORLD);
      steady.ms_engine += maxOver(report.ms_engine, MPI_COMM_WORLD);
      steady.ms_own += maxOver(report.ms_own_engine, MPI_COMM_WORLD);
      steady.ms_border += maxOver(report.ms_border_engine, MPI_COMM_WORLD);
      steady.ms_other +=
          maxOver(report.ms_assemble + report.ms_filter + report.ms_deliver, MPI_COMM_WORLD);
      steady.box_bytes += boxBytes;
      steady.pair_bytes += sumOver(static_cast<double>(report.pair_bytes_sent), MPI_COMM_WORLD);
      steady.control_bytes +=
          sumOver(static_cast<double>(report.control_bytes_sent), MPI_COMM_WORLD);
      steady.boxes_sent += sumOver(static_cast<double>(report.boxes_sent), MPI_COMM_WORLD);
      steady.imbalance += report.imbalance;
      steady.slab_boxes_max += maxOver(static_cast<double>(report.slab_boxes), MPI_COMM_WORLD);
      steady.slab_boxes_sum += sumOver(static_cast<double>(report.slab_boxes), MPI_COMM_WORLD);
      steady.border_boxes_max += maxOver(static_cast<double>(report.border_boxes), MPI_COMM_WORLD);
      steady.recuts += report.recut ? 1 : 0;
    }
    // Pairs returned, summed over ranks: a pair whose boxes have two owners counts twice.
    if (frame >= kWarmupFrames)
      steady.pairs += sumOver(static_cast<double>(report.pairs_returned), MPI_COMM_WORLD);
    const auto migrateStart = std::chrono::steady_clock::now();
    if (frame % std::max(options.migrate_every, 1) == 0)
      migrate(bodies, broadphase, MPI_COMM_WORLD);
    moveBodies(bodies, world);
    if (frame >= kWarmupFrames)
      steady.ms_migrate += maxOver(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - migrateStart)
              .count(),
          MPI_COMM_WORLD);
  }
  if (rank == 0) {
    const double f = steady.frames;
    const double frameBytes = static_cast<double>(options.n) * kBoxBytes;
    const double allBytes = steady.box_bytes + steady.pair_bytes + steady.control_bytes;
    std::string line = "RESULT";
    const auto field = [&line](const char* inName, double inValue) {
      char text[96];
      std::snprintf(text, sizeof text, " %s=%.6g", inName, inValue);
      line += text;
    };
    field("n", static_cast<double>(options.n));
    field("ranks", ranks);
    field("threads", options.threads);
    field("frames", f);
    field("motion", options.motion);
    field("world", world);
    field("ms_frame", steady.ms_frame / f);
    field("ms_exchange", steady.ms_exchange / f);
    field("ms_engine", steady.ms_engine / f);
    field("ms_own", steady.ms_own / f);
    field("ms_border", steady.ms_border / f);
    field("ms_other", steady.ms_other / f);
    field("ms_migrate", steady.ms_migrate / f);
    field("box_bytes", steady.box_bytes / f);
    field("pair_bytes", steady.pair_bytes / f);
    field("control_bytes", steady.control_bytes / f);
    field("boxes_sent", steady.boxes_sent / f);
    field("bytes_per_box", allBytes / f / options.n);
    field("box_bytes_share", steady.box_bytes / f / frameBytes);
    field("all_bytes_share", allBytes / f / frameBytes);
    field("imbalance", steady.imbalance / f);
    field("slab_boxes_max", steady.slab_boxes_max / f);
    field("slab_boxes_mean", steady.slab_boxes_sum / f / ranks);
    field("border_boxes_max", steady.border_boxes_max / f);
    field("pairs_returned", steady.pairs / f);
    field("recuts", steady.recuts);
    field("first_ms", firstFrameMs);
    field("first_engine_ms", firstEngineMs);
    field("first_box_bytes", firstFrameBoxBytes);
    field("after_migration_ms", afterMigrationMs);
    const FrameReport& engine = broadphase.stats().engine;
    std::printf("%s own_path=%s own_skin=%s\n", line.c_str(), framePathName(engine.path),
                skinChoiceName(engine.skin_choice));
  }
  MPI_Finalize();
  return 0;
}
