// sap_scene: writes one frame of a test scene in the sap_pairs box format (see --help).
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

#include "cli_args.h"
#include "sap_broadphase/core/config.h"
#include "sap_broadphase/core/scenes.h"
#include "sap_broadphase/core/text_io.h"

namespace {

using namespace sap_broadphase;

const char* const kProgram = "sap_scene";
const char* const kUsage =
    "usage: sap_scene --scene uniform|ball|plane --n N --density D --frame F --seed S\n"
    "                 [--axis x|y|z] [--frames T]\n"
    "\n"
    "Writes frame F of a deterministic test scene to stdout, one box a line:\n"
    "  id min_x min_y min_z max_x max_y max_z   (ids 0..N-1, shortest round-trip doubles)\n"
    "the format sap_pairs reads.\n"
    "\n"
    "  --scene K     uniform (paper §6), ball (ball cluster, §7) or plane (plane cluster, §7)\n"
    "                (default uniform)\n"
    "  --n N         number of boxes (plane: rounded down to a square) (default 1000)\n"
    "  --density D   uniform: sum of box volumes / world volume, > 0 (default 0.05)\n"
    "  --frame F     frame to write, >= 0 (default 0)\n"
    "  --seed S      random seed, unsigned 64-bit (default 1)\n"
    "  --axis A      plane: the axis u all boxes cross at mid-run, x, y or z (default x)\n"
    "  --frames T    ball and plane: run length the motion is timed for, >= 2 (default 500)\n"
    "  --help        print this help\n"
    "\n"
    "Exit status: 0 success; 2 bad usage; 1 unexpected failure (e.g. output not writable).\n";

/// Fills ioConfig and outFrame from argv; returns an error message, empty on success.
std::string parseOptions(int inArgc, char** inArgv, SceneConfig& ioConfig, int& outFrame,
                         bool& outHelp) {
  cli::ArgCursor cursor(inArgc, inArgv);
  while (cursor.more()) {
    std::string arg;
    std::string value;
    std::string error;
    bool isOption = false;
    cursor.next(arg, isOption);
    if (arg == "--") continue;
    if (!isOption) return "unexpected argument '" + arg + "'";
    if (arg == "--help" || arg == "-h") {
      if (cursor.hasAttachedValue()) return arg + " takes no value";
      outHelp = true;
      continue;
    }
    if (arg != "--scene" && arg != "--n" && arg != "--density" && arg != "--frame" &&
        arg != "--seed" && arg != "--axis" && arg != "--frames")
      return "unknown option '" + arg + "'";
    if (!cursor.takeValue(arg, value, error)) return error;
    int64_t integer = 0;
    uint64_t seed = 0;
    const Limit* limit = findLimit("sap_scene", arg);  // --n, --density, --frame, --frames
    const std::string bad = "bad " + arg + " value '" + value + "'" +
                            (limit ? std::string(" (") + limit->allowed + ")" : std::string());
    // An integer flag within its row of the limits table.
    auto integerOf = [&]() {
      return cli::parseInteger(value, static_cast<int64_t>(limit->min),
                               static_cast<int64_t>(limit->max), integer);
    };
    if (arg == "--scene") {
      if (!parseSceneKind(value, ioConfig.kind)) return bad + " (uniform, ball or plane)";
    } else if (arg == "--n") {
      if (!integerOf()) return bad;
      ioConfig.n = static_cast<std::size_t>(integer);
    } else if (arg == "--density") {
      double density = 0.0;
      if (!cli::parseFiniteDouble(value, density) || limitProblem(*limit, density)) return bad;
      ioConfig.density = density;
    } else if (arg == "--frame") {
      if (!integerOf()) return bad;
      outFrame = static_cast<int>(integer);
    } else if (arg == "--seed") {
      if (!cli::parseUnsigned64(value, seed)) return bad + " (an unsigned 64-bit integer)";
      ioConfig.seed = seed;
    } else if (arg == "--axis") {
      if (!cli::parseAxisName(value, ioConfig.plane_axis)) return bad + " (x, y or z)";
    } else {  // --frames
      if (!integerOf()) return bad;
      ioConfig.frames = static_cast<int>(integer);
    }
  }
  return "";
}

int run(int inArgc, char** inArgv) {
  SceneConfig config;
  int frame = 0;
  bool help = false;
  const std::string usageError = parseOptions(inArgc, inArgv, config, frame, help);
  if (!usageError.empty()) return cli::reportUsageError(kProgram, usageError, kUsage);
  if (help) {
    std::fputs(kUsage, stdout);
    return cli::kExitOk;
  }
  std::ios::sync_with_stdio(false);
  const BoxSet boxes = makeSceneFrame(config, frame);
  writeBoxText(std::cout, boxes);
  return cli::finishOutput(kProgram);
}

}  // namespace

int main(int argc, char** argv) {
  return cli::runMain(kProgram, run, argc, argv);
}
