// sap_pairs_mpi: sap_pairs computed by the ranks of an MPI job (mpirun -np R sap_pairs_mpi FILE).
// Rank 0 reads the file and deals the boxes out in blocks of file order, as a simulation's
// ranks would hold them; the distributed broad phase finds the pairs and rank 0 prints them.
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli_args.h"
#include "pairs_options.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/text_io.h"
#include "sap_broadphase/distributed/distributed_broadphase.h"

namespace {

using namespace sap_broadphase;
using cli::PairsOptions;
using distributed::DistributedBroadphase;
using distributed::DistributedConfig;
using distributed::DistributedReport;
using distributed::PairDelivery;

const char* const kProgram = "sap_pairs_mpi";
const char* const kUsage =
    "usage: mpirun -np R sap_pairs_mpi [--threads N] [--method sap|sequential|brute]\n"
    "                                  [--max-pairs N] [--count] [--stats] [FILE|-]\n"
    "\n"
    "sap_pairs over R MPI ranks: the same input, output and exit status as sap_pairs (see\n"
    "sap_pairs --help for the text format). Rank 0 reads the boxes and deals them out in\n"
    "blocks of file order; each rank computes one slab of the x axis; rank 0 prints every\n"
    "overlapping pair as 'a b' (a < b), one a line, sorted by (a, b).\n"
    "\n"
    "  --threads N   worker threads of each rank, 1 to 4 a processor (default: all cores)\n"
    "  --method M    each rank's engine: sap (default), sequential or brute\n"
    "  --max-pairs N each rank's engine refuses more pairs than N (the job fails, exit 1)\n"
    "  --count       print only the number of pairs\n"
    "  --stats       print one line a rank to stderr: its boxes, its slab's boxes, its border\n"
    "                set, pairs among its own boxes and across owners, bytes sent, the own\n"
    "                engine's path and threads, and milliseconds of reading, exchange,\n"
    "                engines, delivery and in all\n"
    "  --help        print this help\n"
    "\n"
    "Exit status: 0 success; 2 bad input (then nothing on stdout and 'FILE:LINE: reason' on\n"
    "stderr) or bad usage; 1 unexpected failure. mpirun may add its own lines to stderr.\n";

/// Scatters one per-box array of rank 0, inPerBox values a box, in blocks (counts and offsets
/// in boxes: one MPI element a box, so the int counts reach kMaxBoxes boxes).
template <typename T>
void scatterBlocks(const std::vector<T>& inAll, std::vector<T>& outMine, std::size_t inPerBox,
                   const std::vector<int>& inCounts, const std::vector<int>& inOffsets,
                   int inRank) {
  MPI_Datatype box;
  MPI_Type_contiguous(static_cast<int>(inPerBox * sizeof(T)), MPI_BYTE, &box);
  MPI_Type_commit(&box);
  outMine.resize(inPerBox * static_cast<std::size_t>(inCounts[inRank]));
  MPI_Scatterv(inAll.data(), inCounts.data(), inOffsets.data(), box, outMine.data(),
               inCounts[inRank], box, 0, MPI_COMM_WORLD);
  MPI_Type_free(&box);
}

/// Rank 0's boxes dealt out in contiguous blocks of file order, one a rank.
BoxSet dealBoxes(const BoxSet& inAll, int inRank, int inRanks) {
  uint64_t total = inAll.size();
  MPI_Bcast(&total, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  std::vector<int> counts(static_cast<std::size_t>(inRanks));
  std::vector<int> offsets(static_cast<std::size_t>(inRanks));
  for (int r = 0; r < inRanks; ++r) {
    const uint64_t begin = total * r / inRanks;
    const uint64_t end = total * (r + 1) / inRanks;
    offsets[r] = static_cast<int>(begin);
    counts[r] = static_cast<int>(end - begin);
  }
  BoxSet mine;
  scatterBlocks(inAll.ids, mine.ids, 1, counts, offsets, inRank);
  scatterBlocks(inAll.bounds, mine.bounds, kBoundsPerBox, counts, offsets, inRank);
  return mine;
}

/// Prints every rank's line of statistics on rank 0's stderr, rank by rank.
void printStats(const DistributedReport& inStats, double inReadMs, int inRank, int inRanks) {
  char line[512];
  std::snprintf(line, sizeof line,
                "rank %d boxes %zu slab_boxes %zu border_boxes %zu own_pairs %zu cross_pairs %zu "
                "bytes_sent %llu path %s "
                "threads %d ms read %.3f exchange %.3f engine %.3f deliver %.3f total %.3f\n",
                inRank, inStats.local_boxes, inStats.slab_boxes, inStats.border_boxes,
                inStats.own_pairs, inStats.cross_pairs,
                static_cast<unsigned long long>(inStats.box_bytes_sent + inStats.pair_bytes_sent +
                                                inStats.control_bytes_sent),
                framePathName(inStats.engine.path), inStats.engine.threads, inReadMs,
                inStats.ms_cut + inStats.ms_exchange, inStats.ms_engine,
                inStats.ms_filter + inStats.ms_deliver, inStats.ms_total);
  std::vector<char> all(inRank == 0 ? sizeof line * static_cast<std::size_t>(inRanks) : 0);
  MPI_Gather(line, sizeof line, MPI_CHAR, all.data(), sizeof line, MPI_CHAR, 0, MPI_COMM_WORLD);
  if (inRank != 0) return;
  for (int r = 0; r < inRanks; ++r) std::fputs(all.data() + sizeof line * r, stderr);
}

/// The collective part: deal, compute, gather. Any failure aborts the whole job, since the
/// other ranks would otherwise wait forever in a collective.
int computeAndPrint(const PairsOptions& inOptions, const BoxSet& inAll, double inReadMs, int inRank,
                    int inRanks) {
  const BoxSet mine = dealBoxes(inAll, inRank, inRanks);
  DistributedConfig config;
  config.engine.threads = inOptions.threads;
  config.engine.method = inOptions.method;
  config.engine.max_pairs = inOptions.max_pairs;
  DistributedBroadphase broadphase(MPI_COMM_WORLD, config);
  const PairList& pairs = broadphase.update(mine, PairDelivery::kGatherAtRoot, 0);
  if (inRank == 0) {
    if (inOptions.count_only) {
      std::cout << pairs.size() << '\n';
    } else {
      writePairText(std::cout, pairs);
    }
    std::cout.flush();
  }
  if (inOptions.stats) printStats(broadphase.stats(), inReadMs, inRank, inRanks);
  return inRank == 0 ? cli::finishOutput(kProgram) : cli::kExitOk;
}

int run(int inArgc, char** inArgv) {
  int rank = 0;
  int ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  PairsOptions options;
  // Every rank parses the same arguments; only rank 0 speaks.
  const std::string usageError = cli::parsePairsOptions(inArgc, inArgv, options);
  if (!usageError.empty())
    return rank == 0 ? cli::reportUsageError(kProgram, usageError, kUsage) : cli::kExitBadInput;
  if (options.help) {
    if (rank == 0) std::fputs(kUsage, stdout);
    return cli::kExitOk;
  }
  std::ios::sync_with_stdio(false);
  const auto readStart = std::chrono::steady_clock::now();
  BoxSet all;
  int readOk = rank == 0 ? cli::readPairsInput(options.path, all) : 1;
  MPI_Bcast(&readOk, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!readOk) return cli::kExitBadInput;
  const double readMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - readStart)
          .count();
  try {
    return computeAndPrint(options, all, readMs, rank, ranks);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: rank %d: %s\n", kProgram, rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, cli::kExitFailure);
    return cli::kExitFailure;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // The engine's OpenMP threads never call MPI: only the main thread does.
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  const int status = sap_broadphase::cli::runMain(kProgram, run, argc, argv);
  MPI_Finalize();
  return status;
}
