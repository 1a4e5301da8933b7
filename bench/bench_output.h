// Where an experiment's results go: the table on stdout, CSV and figures in --out.
#pragma once

#include <string>
#include <vector>

#include "bench_options.h"
#include "bench_plot.h"
#include "bench_table.h"

namespace sap_bench {

/// Prints inTable (unless !inPrint), writes OUT/inStem.csv and renders the figures.
void publish(const Options& inOptions, const Table& inTable, const std::string& inStem,
             const std::vector<Figure>& inFigures = {}, bool inPrint = true);

/// Creates the output folder (and parents); false when it cannot.
bool makeOutputDir(const std::string& inDir);

}  // namespace sap_bench
