// Peak memory of the engine against the target of 120 bytes per box plus 8 per pair. The
// peak resident set (VmHWM) is reset through /proc/self/clear_refs after the scene exists, so
// the growth during the engine's frames is the engine's own (buffers and pair output).
#include <algorithm>

#include "bench_memory.h"
#include "bench_output.h"
#include "bench_scenes.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {

void runMemory(const Options& inOptions) {
  const auto sizes = inOptions.sizes({1u << 17, 1u << 20}, {1u << 14, 1u << 16});
  const int frames = inOptions.framesOr(5, 3);
  Table table("Peak memory of the engine (bytes; target 120/box + 8/pair)",
              {"n", "d", "pairs", "engine_peak_bytes", "bytes_per_box", "budget_bytes",
               "within_budget", "process_peak_bytes", "peak_reset"});
  for (std::size_t n : sizes) {
    for (double density : {0.05, 0.35}) {
      sap_broadphase::SceneSimulator simulator(uniformScene(n, density, inOptions.seed));
      PeakMeter meter;
      meter.start();
      std::size_t pairs = 0;
      {
        sap_broadphase::Broadphase engine(parallelConfig(inOptions.threads));
        for (int f = 0; f < frames; ++f) {
          if (f > 0) simulator.step();
          pairs = std::max(pairs, engine.update(simulator.boxes()).size());
        }
      }
      const std::size_t used = meter.grownBytes();
      const std::size_t budget = 120 * n + 8 * pairs;
      table.addRow({fmtSize(n), fmt(density, 2), fmtCount(pairs), fmtCount(used),
                    fmt(static_cast<double>(used) / n), fmtCount(budget),
                    used <= budget ? "yes" : "NO", fmtCount(meter.processPeakBytes()),
                    meter.peakReset() ? "yes" : "no"});
    }
  }
  publish(inOptions, table, "memory");
}

}  // namespace sap_bench
