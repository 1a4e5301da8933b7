// Parsing sap_bench's command line.
#include "bench_options.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace sap_bench {
namespace {

const char* const kUsage =
    "usage: sap_bench [--experiment NAME[,NAME...]]... [options]\n"
    "  --experiment, -e NAME  experiment(s) to run; 'all' (default) runs every one\n"
    "  --list                 list the experiments and exit\n"
    "  --out DIR              folder for CSV and .png files (default bench_out)\n"
    "  --quick                small sizes and few frames (smoke tests, CI)\n"
    "  --max-n N              cap every box count at N (accepts 2^K)\n"
    "  --min-n N              drop sweep sizes below N (accepts 2^K)\n"
    "  --sizes N[,N...]       the box counts of a size sweep instead of its own (accept 2^K)\n"
    "  --runs R               repetitions per configuration (medians are quoted)\n"
    "  --frames F             frames per run\n"
    "  --threads T            threads of the parallel engine (0 = all cores)\n"
    "  --seed S               scene seed (default 1)\n"
    "  --no-plots             write CSV only\n";

/// Parses "123", "1e6" or "2^K".
bool parseCount(const std::string& inText, std::size_t& outValue) {
  if (inText.rfind("2^", 0) == 0) {
    char* end = nullptr;
    const long exponent = std::strtol(inText.c_str() + 2, &end, 10);
    if (*end != '\0' || exponent < 0 || exponent > 40) return false;
    outValue = std::size_t{1} << exponent;
    return true;
  }
  char* end = nullptr;
  const double value = std::strtod(inText.c_str(), &end);
  if (*end != '\0' || !(value >= 0.0) || value > 1e12) return false;
  outValue = static_cast<std::size_t>(value);
  return true;
}

bool parseInt(const std::string& inText, int& outValue) {
  char* end = nullptr;
  const long value = std::strtol(inText.c_str(), &end, 10);
  if (inText.empty() || *end != '\0' || value < 0 || value > 1000000) return false;
  outValue = static_cast<int>(value);
  return true;
}

void splitNames(const std::string& inText, std::vector<std::string>& ioNames) {
  std::stringstream stream(inText);
  std::string name;
  while (std::getline(stream, name, ',')) {
    if (!name.empty()) ioNames.push_back(name);
  }
}

bool parseCounts(const std::string& inText, std::vector<std::size_t>& outValues) {
  std::vector<std::string> parts;
  splitNames(inText, parts);
  outValues.clear();
  for (const std::string& part : parts) {
    std::size_t value = 0;
    if (!parseCount(part, value) || value == 0) return false;
    outValues.push_back(value);
  }
  return !outValues.empty();
}

}  // namespace

int Options::runsOr(int inDefault) const {
  if (runs > 0) return runs;
  return quick ? std::min(inDefault, 2) : inDefault;
}

int Options::framesOr(int inFullDefault, int inQuickDefault) const {
  if (frames > 0) return frames;
  return quick ? inQuickDefault : inFullDefault;
}

std::vector<std::size_t> Options::sizes(const std::vector<std::size_t>& inFull,
                                        const std::vector<std::size_t>& inQuick) const {
  const std::vector<std::size_t>& base = !only_sizes.empty() ? only_sizes
                                         : quick             ? inQuick
                                                             : inFull;
  std::vector<std::size_t> kept;
  for (std::size_t n : base) {
    if ((max_n == 0 || n <= max_n) && n >= min_n) kept.push_back(n);
  }
  if (kept.empty() && !base.empty()) {
    const std::size_t smallest = *std::min_element(base.begin(), base.end());
    kept.push_back(max_n == 0 ? smallest : std::min(smallest, max_n));
  }
  return kept;
}

std::size_t Options::size(std::size_t inFull, std::size_t inQuick) const {
  const std::size_t n = quick ? inQuick : inFull;
  return max_n == 0 ? n : std::min(n, max_n);
}

std::vector<std::size_t> powersOfTwo(int inFrom, int inTo) {
  std::vector<std::size_t> sizes;
  for (int k = inFrom; k <= inTo; ++k) sizes.push_back(std::size_t{1} << k);
  return sizes;
}

bool parseOptions(int inArgc, char** inArgv, Options& outOptions, int& outExitCode) {
  outExitCode = 0;
  for (int i = 1; i < inArgc; ++i) {
    const std::string arg = inArgv[i];
    const bool hasValue = i + 1 < inArgc;
    const std::string value = hasValue ? inArgv[i + 1] : "";
    bool ok = true;
    bool usedValue = true;
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return false;
    } else if (arg == "--quick") {
      outOptions.quick = true;
      usedValue = false;
    } else if (arg == "--list") {
      outOptions.list = true;
      usedValue = false;
    } else if (arg == "--no-plots") {
      outOptions.plots = false;
      usedValue = false;
    } else if (!hasValue) {
      ok = false;
    } else if (arg == "--experiment" || arg == "-e") {
      splitNames(value, outOptions.experiments);
    } else if (arg == "--out") {
      outOptions.out_dir = value;
    } else if (arg == "--max-n") {
      ok = parseCount(value, outOptions.max_n);
    } else if (arg == "--min-n") {
      ok = parseCount(value, outOptions.min_n);
    } else if (arg == "--sizes") {
      ok = parseCounts(value, outOptions.only_sizes);
    } else if (arg == "--runs") {
      ok = parseInt(value, outOptions.runs);
    } else if (arg == "--frames") {
      ok = parseInt(value, outOptions.frames);
    } else if (arg == "--threads") {
      ok = parseInt(value, outOptions.threads);
    } else if (arg == "--seed") {
      std::size_t seed = 0;
      ok = parseCount(value, seed);
      outOptions.seed = seed;
    } else {
      ok = false;
    }
    if (!ok) {
      std::cerr << "sap_bench: bad or incomplete option '" << arg << "'\n" << kUsage;
      outExitCode = 2;
      return false;
    }
    if (usedValue) ++i;
  }
  if (outOptions.experiments.empty()) outOptions.experiments.push_back("all");
  return true;
}

}  // namespace sap_bench
