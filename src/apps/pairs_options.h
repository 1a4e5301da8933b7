// What sap_pairs and sap_pairs_mpi share: their options, the CLI's method names and reading
// the box file, so that both tools keep one contract (docs/CLI.md).
#pragma once

#include <cstddef>
#include <string>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/config.h"

namespace sap_broadphase::cli {

/// What the command line asked for.
struct PairsOptions {
  int threads = 0;  // 0 = all cores
  Method method = Method::kAuto;
  std::size_t max_pairs = kDefaultMaxPairs;  // the engine's max_pairs
  bool count_only = false;
  bool stats = false;
  bool help = false;
  std::string path = "-";
};

/// Fills outOptions from argv; returns an error message, empty on success.
std::string parsePairsOptions(int inArgc, char** inArgv, PairsOptions& outOptions);

/// Reads the boxes of inPath ("-" = stdin) with readBoxText; on failure prints
/// 'FILE:LINE: reason' to stderr and returns false.
bool readPairsInput(const std::string& inPath, BoxSet& outBoxes);

}  // namespace sap_broadphase::cli
