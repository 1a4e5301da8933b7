// Command-line options of sap_bench.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sap_bench {

/// What the user asked for; zero/empty values mean "the experiment's default".
struct Options {
  std::vector<std::string> experiments;  ///< names to run, in order ("all" expands)
  std::string out_dir = "bench_out";     ///< CSVs, PNGs and machine.txt go here
  bool quick = false;                    ///< small sizes, few frames: smoke tests and CI
  std::size_t max_n = 0;                 ///< cap on box counts (0 = none)
  std::size_t min_n = 0;                 ///< floor on box counts in size sweeps (0 = none)
  std::vector<std::size_t> only_sizes;   ///< --sizes: a size sweep's box counts (empty = its own)
  int runs = 0;                          ///< repetitions per configuration (0 = default)
  int frames = 0;                        ///< frames per run (0 = default)
  int threads = 0;                       ///< threads of the parallel engine (0 = all cores)
  uint64_t seed = 1;                     ///< scene seed
  bool plots = true;                     ///< render PNG plots with gnuplot
  bool list = false;                     ///< print the experiment list and exit

  /// Runs for a configuration: --runs, else inDefault (quick: at most 2).
  int runsOr(int inDefault) const;
  /// Frames per run: --frames, else inFullDefault (or inQuickDefault with --quick).
  int framesOr(int inFullDefault, int inQuickDefault) const;
  /// The sizes to use: --sizes if given, else inQuick with --quick, else inFull; then filtered by
  /// --min-n/--max-n (an empty result keeps the smallest size, capped).
  std::vector<std::size_t> sizes(const std::vector<std::size_t>& inFull,
                                 const std::vector<std::size_t>& inQuick) const;
  /// One size: inQuick with --quick, else inFull; capped by --max-n.
  std::size_t size(std::size_t inFull, std::size_t inQuick) const;
};

/// 2^inFrom, 2^(inFrom+1), ..., 2^inTo.
std::vector<std::size_t> powersOfTwo(int inFrom, int inTo);

/// Parses argv; on error or --help prints to stderr and returns false with outExitCode set.
bool parseOptions(int inArgc, char** inArgv, Options& outOptions, int& outExitCode);

}  // namespace sap_bench
