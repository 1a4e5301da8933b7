// Peak memory of the engine against the target of 120 bytes per box plus 8 per pair. The
// peak resident set (VmHWM) is reset through /proc/self/clear_refs after the scene exists, so
// the growth during the engine's frames is the engine's own (buffers and pair output).
#include <malloc.h>
#include <algorithm>

#include <fstream>
#include <sstream>

#include "bench_output.h"
#include "bench_scenes.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {

namespace {

/// A "VmRSS"/"VmHWM" line of /proc/self/status in bytes, or 0 when unavailable.
std::size_t procStatusBytes(const std::string& inField) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(inField + ":", 0) != 0) continue;
    std::istringstream fields(line.substr(inField.size() + 1));
    std::size_t kilobytes = 0;
    fields >> kilobytes;
    return kilobytes * 1024;
  }
  return 0;
}

/// Resets VmHWM to the current RSS (Linux >= 4.0); false when not possible.
bool resetPeak() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  return static_cast<bool>(clear);
}

}  // namespace

void runMemory(const Options& inOptions) {
  const auto sizes = inOptions.sizes({1u << 17, 1u << 20}, {1u << 14, 1u << 16});
  const int frames = inOptions.framesOr(5, 3);
  Table table("Peak memory of the engine (bytes; target 120/box + 8/pair)",
              {"n", "d", "pairs", "engine_peak_bytes", "bytes_per_box", "budget_bytes",
               "within_budget", "process_peak_bytes", "peak_reset"});
  for (std::size_t n : sizes) {
    for (double density : {0.05, 0.35}) {
      sap_broadphase::SceneSimulator simulator(uniformScene(n, density, inOptions.seed));
      malloc_trim(0);  // return freed heap so the reset peak starts from live memory
      const bool reset = resetPeak();
      const std::size_t before = procStatusBytes("VmRSS");
      std::size_t pairs = 0;
      {
        sap_broadphase::Broadphase engine(parallelConfig(inOptions.threads));
        for (int f = 0; f < frames; ++f) {
          if (f > 0) simulator.step();
          pairs = std::max(pairs, engine.update(simulator.boxes()).size());
        }
      }
      const std::size_t peak = procStatusBytes("VmHWM");
      const std::size_t used = peak > before ? peak - before : 0;
      const std::size_t budget = 120 * n + 8 * pairs;
      table.addRow({fmtSize(n), fmt(density, 2), fmtCount(pairs), fmtCount(used),
                    fmt(static_cast<double>(used) / n), fmtCount(budget),
                    used <= budget ? "yes" : "NO", fmtCount(peak), reset ? "yes" : "no"});
    }
  }
  publish(inOptions, table, "memory");
}

}  // namespace sap_bench
