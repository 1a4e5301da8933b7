#include "pairs_options.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>

#include "cli_args.h"
#include "sap_broadphase/core/text_io.h"

namespace sap_broadphase::cli {
namespace {

/// The methods the CLI offers, by the engine's names (methodName), except that Method::kAuto
/// is spelled "sap" here, as it was before the engine named it.
const Method kCliMethods[] = {Method::kAuto, Method::kSequential, Method::kBruteForce};

const char* cliMethodName(Method inMethod) {
  return inMethod == Method::kAuto ? "sap" : methodName(inMethod);
}

/// Parses a --method name: one of kCliMethods by its CLI name.
bool parseCliMethod(const std::string& inName, Method& outMethod) {
  for (Method method : kCliMethods) {
    if (inName == cliMethodName(method)) {
      outMethod = method;
      return true;
    }
  }
  return false;
}

}  // namespace

std::string parsePairsOptions(int inArgc, char** inArgv, PairsOptions& outOptions) {
  ArgCursor cursor(inArgc, inArgv);
  bool havePath = false;
  while (cursor.more()) {
    std::string arg;
    std::string value;
    std::string error;
    bool isOption = false;
    cursor.next(arg, isOption);
    if (arg == "--") continue;
    if (!isOption) {
      if (havePath) return "more than one input file given ('" + arg + "')";
      outOptions.path = arg;
      havePath = true;
    } else if (arg == "--threads") {
      int64_t threads = 0;
      if (!cursor.takeValue(arg, value, error)) return error;
      const Limit& limit = *findLimit("sap_pairs, sap_pairs_mpi", "--threads");
      if (!parseInteger(value, 1, static_cast<int64_t>(limit.max), threads))
        return "bad --threads value '" + value + "' (" + limit.allowed + ": at most " +
               std::to_string(maxThreads()) + " on this machine)";
      outOptions.threads = static_cast<int>(threads);
    } else if (arg == "--max-pairs") {
      if (!cursor.takeValue(arg, value, error)) return error;
      const Limit& limit = *findLimit("sap_pairs, sap_pairs_mpi", "--max-pairs");
      uint64_t max_pairs = 0;
      // Compared as integers: 2^53 + 1 would round to 2^53 as a double.
      if (!parseUnsigned64(value, max_pairs) || max_pairs < static_cast<uint64_t>(limit.min) ||
          max_pairs > static_cast<uint64_t>(limit.max))
        return "bad --max-pairs value '" + value + "' (" + limit.allowed + ")";
      outOptions.max_pairs = static_cast<std::size_t>(max_pairs);
    } else if (arg == "--method") {
      if (!cursor.takeValue(arg, value, error)) return error;
      if (!parseCliMethod(value, outOptions.method))
        return "bad --method value '" + value + "' (" +
               methodList({std::begin(kCliMethods), std::end(kCliMethods)}, cliMethodName) + ")";
    } else if (arg == "--count" || arg == "--stats" || arg == "--help" || arg == "-h") {
      if (cursor.hasAttachedValue()) return arg + " takes no value";
      if (arg == "--count")
        outOptions.count_only = true;
      else if (arg == "--stats")
        outOptions.stats = true;
      else
        outOptions.help = true;
    } else {
      return "unknown option '" + arg + "'";
    }
  }
  return "";
}

bool readPairsInput(const std::string& inPath, BoxSet& outBoxes) {
  std::optional<ParseError> error;
  if (inPath == "-") {
    error = readBoxText(std::cin, "<stdin>", outBoxes);
  } else {
    struct stat info;
    if (stat(inPath.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
      error = ParseError{inPath, 0, "cannot read: is a directory"};
    } else {
      std::ifstream file(inPath, std::ios::binary);
      if (!file) {
        error = ParseError{inPath, 0, std::string("cannot open: ") + std::strerror(errno)};
      } else {
        error = readBoxText(file, inPath, outBoxes);
      }
    }
  }
  if (!error) return true;
  std::fprintf(stderr, "%s\n", error->message().c_str());
  return false;
}

}  // namespace sap_broadphase::cli
