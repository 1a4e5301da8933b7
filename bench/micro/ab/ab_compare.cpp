// Old and new engine builds side by side in one process: every frame of a scene goes to each
// engine in turn (the order rotating from frame to frame and run to run), so that the load
// of a shared machine falls on all of them alike. Each ENGINE is LABEL=LIBRARY:METHOD:THREADS,
// LIBRARY a build of ab_engine.cpp with the engine (ab_build.sh), METHOD 0 auto, 1 parallel,
// 2 sequential.
//
//   ab_compare [--scene uniform|ball|plane] [--first FRAME] [--n N] [--density D] [--speed S]
//              [--frames F] [--runs R] [--skin auto|off] ENGINE...
//
// --first starts at that frame of the scene (default: 75 for the ball, the start of the
// paper's intense frames; 225 for the plane, its crossing; 0 for the uniform scene).
//
// Prints per engine: a fresh engine's first frame (median over runs), the steady frame
// (median and minimum over the later frames of all runs), the process CPU time of a steady
// frame, the steady phases, the time no phase reports, and whether every engine found the
// same number of pairs on every frame; then the first frame's phases.
#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "sap_broadphase/core/scenes.h"

namespace {

using sap_broadphase::SceneConfig;
using sap_broadphase::SceneKind;
using sap_broadphase::SceneSimulator;

using MakeEngine = void* (*)(int, int, int);
using FreeEngine = void (*)(void*);
using Update = std::size_t (*)(void*, const void*, double*);

// keys, sort, candidates, pairing, output, the other phases (history, static, skin, flow), total
constexpr int kTimes = 7;
const char* const kTimeNames[kTimes] = {"keys",   "sort",  "cand", "pairing",
                                        "output", "other", "total"};

struct Engine {
  std::string label;
  int method = 0;
  int threads = 1;
  MakeEngine make = nullptr;
  FreeEngine free = nullptr;
  Update update = nullptr;
  std::vector<std::vector<double>> first;   // [time][run]
  std::vector<std::vector<double>> steady;  // [time][frame]
  std::vector<double> first_cpu, steady_cpu;
};

double processCpuMs() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

double medianOf(std::vector<double> inValues) {
  if (inValues.empty()) return 0.0;
  std::sort(inValues.begin(), inValues.end());
  return inValues[inValues.size() / 2];
}

double minimumOf(const std::vector<double>& inValues) {
  return inValues.empty() ? 0.0 : *std::min_element(inValues.begin(), inValues.end());
}

bool loadEngine(const std::string& inSpec, Engine& outEngine) {
  const std::size_t equals = inSpec.find('=');
  const std::size_t first_colon = inSpec.find(':', equals);
  const std::size_t second_colon = inSpec.find(':', first_colon + 1);
  if (equals == std::string::npos || first_colon == std::string::npos ||
      second_colon == std::string::npos)
    return false;
  outEngine.label = inSpec.substr(0, equals);
  const std::string library = inSpec.substr(equals + 1, first_colon - equals - 1);
  outEngine.method = std::atoi(inSpec.substr(first_colon + 1).c_str());
  outEngine.threads = std::atoi(inSpec.substr(second_colon + 1).c_str());
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    std::fprintf(stderr, "ab_compare: %s\n", dlerror());
    return false;
  }
  outEngine.make = reinterpret_cast<MakeEngine>(dlsym(handle, "abMakeEngine"));
  outEngine.free = reinterpret_cast<FreeEngine>(dlsym(handle, "abFreeEngine"));
  outEngine.update = reinterpret_cast<Update>(dlsym(handle, "abUpdate"));
  outEngine.first.assign(kTimes, {});
  outEngine.steady.assign(kTimes, {});
  return outEngine.make && outEngine.free && outEngine.update;
}

}  // namespace

int main(int argc, char** argv) {
  SceneConfig scene;
  scene.n = 1u << 17;
  scene.seed = 1;
  int first_frame = 0, frames = 8, runs = 3, skin_off = 1;
  int first_frame_override = -1;  // --first: the scene's frame to start from
  std::vector<Engine> engines;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool has_value = a + 1 < argc;
    if (arg == "--scene" && has_value) {
      const std::string kind = argv[++a];
      if (kind == "ball") {
        scene.kind = SceneKind::kBallCluster;
        first_frame = 75;  // the paper's intense frames 75..150 of 500
      } else if (kind == "plane") {
        scene.kind = SceneKind::kPlaneCluster;
        scene.plane_axis = 1;
        first_frame = 225;  // the crossing, frames 225..275 of 500
      }
    } else if (arg == "--first" && has_value) {
      first_frame_override = std::atoi(argv[++a]);
    } else if (arg == "--n" && has_value) {
      scene.n = std::strtoull(argv[++a], nullptr, 10);
    } else if (arg == "--density" && has_value) {
      scene.density = std::atof(argv[++a]);
    } else if (arg == "--speed" && has_value) {
      scene.speed = std::atof(argv[++a]);
    } else if (arg == "--frames" && has_value) {
      frames = std::max(2, std::atoi(argv[++a]));
    } else if (arg == "--runs" && has_value) {
      runs = std::max(1, std::atoi(argv[++a]));
    } else if (arg == "--skin" && has_value) {
      skin_off = std::string(argv[++a]) == "off";
    } else {
      Engine engine;
      if (!loadEngine(arg, engine)) {
        std::fprintf(stderr, "ab_compare: bad engine '%s' (LABEL=LIBRARY:METHOD:THREADS)\n",
                     arg.c_str());
        return 2;
      }
      engines.push_back(std::move(engine));
    }
  }
  if (engines.empty()) {
    std::fprintf(stderr, "usage: ab_compare [options] LABEL=LIBRARY:METHOD:THREADS...\n");
    return 2;
  }
  if (first_frame_override >= 0) first_frame = first_frame_override;
  bool same_pairs = true;
  for (int run = 0; run < runs; ++run) {
    SceneSimulator simulator(scene);
    simulator.advanceTo(first_frame);
    std::vector<void*> handles;
    for (Engine& engine : engines)
      handles.push_back(engine.make(engine.threads, engine.method, skin_off));
    for (int frame = 0; frame < frames; ++frame) {
      if (frame > 0) simulator.step();
      std::vector<std::size_t> pairs(engines.size());
      for (std::size_t turn = 0; turn < engines.size(); ++turn) {
        const std::size_t e = (turn + frame + run) % engines.size();
        double times[kTimes];
        const double cpu_start = processCpuMs();
        pairs[e] = engines[e].update(handles[e], &simulator.boxes(), times);
        const double cpu = processCpuMs() - cpu_start;
        for (int t = 0; t < kTimes; ++t)
          (frame == 0 ? engines[e].first : engines[e].steady)[t].push_back(times[t]);
        (frame == 0 ? engines[e].first_cpu : engines[e].steady_cpu).push_back(cpu);
      }
      same_pairs = same_pairs && std::count(pairs.begin(), pairs.end(), pairs[0]) ==
                                     static_cast<long>(pairs.size());
    }
    for (std::size_t e = 0; e < engines.size(); ++e) engines[e].free(handles[e]);
  }
  std::printf("%-14s %3s %9s %9s %9s %9s %9s %9s", "engine", "t", "first", "steady", "min", "cpu",
              "first/st", "first_cpu");
  for (int t = 0; t < kTimes - 1; ++t) std::printf(" %8s", kTimeNames[t]);
  std::printf(" %8s %11s\n", "unrep", "first_unrep");
  for (Engine& engine : engines) {
    const double steady = medianOf(engine.steady[kTimes - 1]);
    const double first = medianOf(engine.first[kTimes - 1]);
    std::printf("%-14s %3d %9.2f %9.2f %9.2f %9.2f %9.2f %9.2f", engine.label.c_str(),
                engine.threads, first, steady, minimumOf(engine.steady[kTimes - 1]),
                medianOf(engine.steady_cpu), first / steady, medianOf(engine.first_cpu));
    double phases = 0.0, first_phases = 0.0;
    for (int t = 0; t < kTimes - 1; ++t) {
      const double phase = medianOf(engine.steady[t]);
      phases += phase;
      first_phases += medianOf(engine.first[t]);
      std::printf(" %8.2f", phase);
    }
    std::printf(" %8.2f %11.2f\n", steady - phases, first - first_phases);
  }
  std::printf("first frame's phases:\n");
  for (Engine& engine : engines) {
    std::printf("%-14s %3d", engine.label.c_str(), engine.threads);
    for (int t = 0; t < kTimes - 1; ++t)
      std::printf(" %s %.2f", kTimeNames[t], medianOf(engine.first[t]));
    std::printf("\n");
  }
  std::printf("pairs: %s\n", same_pairs ? "every engine the same count on every frame"
                                        : "MISMATCH between engines");
  return same_pairs ? 0 : 1;
}
