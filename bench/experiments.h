// The experiments, one function each, and the list sap_bench dispatches on.
#pragma once

#include <vector>

#include "bench_options.h"

namespace sap_bench {

void runFig1Sort(const Options& inOptions);
void runFig23Phases(const Options& inOptions);
void runFig4Stacked(const Options& inOptions);
void runDispersion(const Options& inOptions);
void runFig5Ball(const Options& inOptions);
void runFig6Plane(const Options& inOptions);
void runThreads(const Options& inOptions);
void runPareto(const Options& inOptions);
void runPeers(const Options& inOptions);
void runMemory(const Options& inOptions);
void runSkips(const Options& inOptions);
void runCoherence(const Options& inOptions);
void runDistributed(const Options& inOptions);
void runSizes(const Options& inOptions);
void runBusy(const Options& inOptions);
void runQuery(const Options& inOptions);
void runEvents(const Options& inOptions);

/// One experiment: its name on the command line, a line of description, its function.
struct Experiment {
  const char* name;
  const char* summary;
  void (*run)(const Options&);
};

/// Every experiment, in the order "all" runs them.
const std::vector<Experiment>& allExperiments();

}  // namespace sap_bench
