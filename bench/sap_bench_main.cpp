// sap_bench: the paper's experiments, the accuracy/speed trade-off and the peers.
#include <cstdio>
#include <iostream>

#include "bench_machine.h"
#include "bench_options.h"
#include "bench_output.h"
#include "bench_stats.h"
#include "bench_table.h"
#include "experiments.h"
#include "sap_broadphase/core/broadphase.h"

namespace sap_bench {

const std::vector<Experiment>& allExperiments() {
  static const std::vector<Experiment> kExperiments = {
      {"fig1_sort", "Fig. 1: sort time, sequential vs parallel, vs n (d = 0.35)", runFig1Sort},
      {"fig23_phases", "Figs. 2-3: candidates and pairing time and speedup vs n and d",
       runFig23Phases},
      {"fig4_stacked", "Fig. 4: parallel phase times stacked over density, three sizes",
       runFig4Stacked},
      {"dispersion", "Sort dispersion D per frame in steady state (uniform scene)", runDispersion},
      {"fig5_ball", "Fig. 5: ball cluster, per-frame time, parallel and sequential", runFig5Ball},
      {"fig6_plane", "Fig. 6: plane cluster, u = x / u = y, with and without axis swapping",
       runFig6Plane},
      {"threads", "Speedup per phase, 1 thread vs all cores", runThreads},
      {"pareto", "Run time against error (missed/extra pairs) per engine mode", runPareto},
      {"peers", "CGAL (cutoffs, TBB), Bullet, FCL managers, a uniform grid on the same boxes",
       runPeers},
      {"memory", "Peak memory of the engine per box and per pair", runMemory},
      {"skips", "What each skip saves: filters, static boxes, unchanged frames, small frames, skin",
       runSkips},
      {"coherence",
       "Motion speed against time: automatic skin, no skin, best fixed skin, FCL dynamic tree",
       runCoherence},
      {"distributed",
       "MPI ranks of this machine: exchange and engine per frame, bytes, the cluster model",
       runDistributed},
      {"sizes", "Frame time against n (2^8..2^20), default, one thread, no skin and peers",
       runSizes},
      {"busy", "Busy loops beside the engine: default against one thread, OMP_WAIT_POLICY",
       runBusy},
      {"query", "Box queries: 1, 100, 10 000 boxes against 2^20, beside FCL's dynamic tree",
       runQuery},
      {"events",
       "Contact events in a steady frame, 2^17 and 2^20: the merge against set_difference",
       runEvents},
  };
  return kExperiments;
}

namespace {

const Experiment* findExperiment(const std::string& inName) {
  for (const Experiment& experiment : allExperiments()) {
    if (inName == experiment.name) return &experiment;
  }
  return nullptr;
}

void printList() {
  for (const Experiment& experiment : allExperiments()) {
    std::printf("%-14s %s\n", experiment.name, experiment.summary);
  }
}

}  // namespace
}  // namespace sap_bench

int main(int argc, char** argv) {
  using namespace sap_bench;
  Options options;
  int exitCode = 0;
  if (!parseOptions(argc, argv, options, exitCode)) return exitCode;
  if (options.list) {
    printList();
    return 0;
  }
  std::vector<const Experiment*> chosen;
  for (const std::string& name : options.experiments) {
    if (name == "all") {
      for (const Experiment& experiment : allExperiments()) chosen.push_back(&experiment);
    } else if (const Experiment* experiment = findExperiment(name)) {
      chosen.push_back(experiment);
    } else {
      std::cerr << "sap_bench: unknown experiment '" << name << "'; known:\n";
      printList();
      return 2;
    }
  }
  if (!makeOutputDir(options.out_dir)) {
    std::cerr << "sap_bench: cannot create " << options.out_dir << "\n";
    return 1;
  }
  const std::string setting = machineSummary() + ", threads: " +
                              std::to_string(sap_broadphase::resolveThreadCount(options.threads)) +
                              (options.quick ? ", quick" : "");
  std::cout << "sap_bench: " << setting << ", load: " << loadAverage() << "\n";
  for (const Experiment* experiment : chosen) {
    std::cerr << "== " << experiment->name << ": " << experiment->summary << "\n";
    const std::string start = utcNow() + ", " + setting + ", load at start: " + loadAverage();
    Stopwatch clock;
    experiment->run(options);
    std::cerr << "== " << experiment->name << " done in " << clock.ms() / 1000.0 << " s\n";
    recordExperimentRun(
        options.out_dir, experiment->name,
        start + ", " + fmt(clock.ms() / 1000.0) + " s, load after: " + loadAverage());
  }
  return 0;
}
