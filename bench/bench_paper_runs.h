// The runs of the paper's uniform sweeps (Figs. 1-4), shared by the experiments that read them.
#pragma once

#include <cstddef>

#include "bench_options.h"
#include "bench_progress.h"
#include "engine_runner.h"

namespace sap_bench {

/// Runs of each configuration: the runs replay the same seeded frames, so more of them measure
/// only the machine's noise, which the median of a run's nine steady frames absorbs as well;
/// three runs made Figs. 1-4 take nine of the full run's minutes.
constexpr int kPaperRuns = 1;

/// Frames of each run (--frames; 10, quick 4): frame 0 builds, the median is of the rest.
int paperFrames(const Options& inOptions);

/// The sequential Algorithm 1 (engine 0) and the parallel algorithm on --threads (engine 1)
/// over the same frames of uniformScene(inCount, inDensity, seed): kPaperRuns runs (--runs) of
/// paperFrames() frames. Figs. 1, 2-3 and 4 read different phases of the same runs
/// (Fig. 1 the sort of Figs. 2-3's d = 0.35 sizes, Fig. 4 four of its seven densities at
/// Figs. 2-3's three largest sizes), so a configuration runs once a process and is kept for
/// the next experiment that asks for it; ioProgress counts its frames either way.
const SceneRun& paperUniformRun(const Options& inOptions, std::size_t inCount, double inDensity,
                                Progress& ioProgress);

}  // namespace sap_bench
