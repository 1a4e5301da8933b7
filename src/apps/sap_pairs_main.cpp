// sap_pairs: reads boxes as text, prints every overlapping pair (see --help for the contract).

#include <chrono>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

#include "cli_args.h"
#include "pairs_options.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/text_io.h"

namespace {

using namespace sap_broadphase;
using cli::PairsOptions;

const char* const kProgram = "sap_pairs";
const char* const kUsage =
    "usage: sap_pairs [--threads N] [--method sap|sequential|brute] [--max-pairs N]\n"
    "                 [--count] [--stats] [FILE|-]\n"
    "\n"
    "Reads axis-aligned boxes from FILE (or standard input when FILE is '-' or absent), one\n"
    "box a line:  id min_x min_y min_z max_x max_y max_z\n"
    "Fields are separated by blanks (spaces, tabs) and/or one comma; blank lines and anything\n"
    "after '#' are ignored. Coordinates are read as C strtod reads them (inf, -inf, -0.0,\n"
    "exponents, hex floats); ids are decimal unsigned 32-bit integers, unique. Boxes are\n"
    "closed: touching boxes overlap.\n"
    "\n"
    "Prints every overlapping pair as 'a b' (a < b), one a line, sorted by (a, b).\n"
    "\n"
    "  --threads N   worker threads, 1 to 4 a processor (default: all cores)\n"
    "  --method M    sap (default): below 32768 boxes or on one thread the small-frame\n"
    "                kernel on one thread, else the parallel sweep-and-prune\n"
    "                sequential: the sequential sweep;  brute: test every pair (oracle)\n"
    "  --max-pairs N input with more than N pairs is refused (exit 2), 1 to 2^53\n"
    "                (default 268435456 = 2^28, 2 GiB of pairs)\n"
    "  --count       print only the number of pairs\n"
    "  --stats       print the frame's report to stderr, one 'name value' line a field\n"
    "                (ms_read, then path, counts, sweep axes, dispersion D, ms per phase)\n"
    "  --help        print this help\n"
    "\n"
    "Exit status: 0 success; 2 bad input (then nothing on stdout and 'FILE:LINE: reason' on\n"
    "stderr; FILE is '<stdin>' for standard input, LINE 0 when the file cannot be read) or bad\n"
    "usage, or more pairs than --max-pairs ('FILE: frame refused: more than N pairs ...');\n"
    "1 unexpected failure (e.g. output not writable).\n";

// The engine's report, one "name value" line a field of its table, after the reading's time.
void printStats(const FrameReport& inStats, double inReadMs) {
  const std::string lines = "ms_read " + reportValueText(ReportUnit::kMilliseconds, inReadMs) +
                            "\n" + reportLines(inStats);
  std::fputs(lines.c_str(), stderr);
}

int run(int inArgc, char** inArgv) {
  PairsOptions options;
  const std::string usageError = cli::parsePairsOptions(inArgc, inArgv, options);
  if (!usageError.empty()) return cli::reportUsageError(kProgram, usageError, kUsage);
  if (options.help) {
    std::fputs(kUsage, stdout);
    return cli::kExitOk;
  }
  std::ios::sync_with_stdio(false);
  const auto readStart = std::chrono::steady_clock::now();
  BoxSet boxes;
  if (!cli::readPairsInput(options.path, boxes)) return cli::kExitBadInput;
  const double readMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - readStart)
          .count();

  BroadphaseConfig config;
  config.threads = options.threads;
  config.method = options.method;
  config.max_pairs = options.max_pairs;
  Broadphase broadphase(config);
  const PairList* found = nullptr;
  try {
    found = &broadphase.update(boxes);
  } catch (const TooManyPairs& refusal) {  // nothing written yet
    const std::string name = options.path == "-" ? "<stdin>" : options.path;
    std::fprintf(stderr, "%s: %s (--max-pairs)\n", name.c_str(), refusal.what());
    return cli::kExitBadInput;
  }
  const PairList& pairs = *found;
  if (options.count_only) {
    std::cout << pairs.size() << '\n';
  } else {
    writePairText(std::cout, pairs);
  }
  std::cout.flush();
  if (options.stats) printStats(broadphase.stats(), readMs);
  return cli::finishOutput(kProgram);
}

}  // namespace

int main(int argc, char** argv) {
  return cli::runMain(kProgram, run, argc, argv);
}
