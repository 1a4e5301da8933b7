// Publishing results.
#include "bench_output.h"

#include <filesystem>
#include <iostream>

namespace sap_bench {

void publish(const Options& inOptions, const Table& inTable, const std::string& inStem,
             const std::vector<Figure>& inFigures, bool inPrint) {
  if (inPrint) inTable.print();
  const std::string csv = inOptions.out_dir + "/" + inStem + ".csv";
  if (!inTable.writeCsv(csv)) {
    std::cerr << "sap_bench: cannot write " << csv << "\n";
  } else {
    std::cout << "wrote " << csv << "\n";
  }
  if (!inOptions.plots) return;
  for (const Figure& figure : inFigures) {
    const std::string png = renderFigure(inOptions.out_dir, figure);
    if (!png.empty()) std::cout << "wrote " << png << "\n";
  }
}

bool makeOutputDir(const std::string& inDir) {
  std::error_code error;
  std::filesystem::create_directories(inDir, error);
  return !error;
}

}  // namespace sap_bench
