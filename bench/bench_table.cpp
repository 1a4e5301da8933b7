// Printing and saving result tables.
#include "bench_table.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <utility>

namespace sap_bench {
namespace {

/// Quotes a CSV cell when it holds a separator, a quote or a line break.
std::string csvCell(const std::string& inCell) {
  if (inCell.find_first_of(",\"\n") == std::string::npos) return inCell;
  std::string quoted = "\"";
  for (char c : inCell) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace

Table::Table(std::string inTitle, std::vector<std::string> inColumns)
    : title_(std::move(inTitle)), columns_(std::move(inColumns)) {}

void Table::addRow(std::vector<std::string> inCells) {
  inCells.resize(columns_.size());
  rows_.push_back(std::move(inCells));
}

void Table::print() const {
  std::vector<std::size_t> widths(columns_.size());
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    widths[c] = columns_[c].size();
    for (const auto& row : rows_) widths[c] = std::max(widths[c], row[c].size());
  }
  auto printRow = [&](const std::vector<std::string>& inCells) {
    std::string line;
    for (std::size_t c = 0; c < inCells.size(); ++c) {
      if (c > 0) line += "  ";
      line += std::string(widths[c] - inCells[c].size(), ' ') + inCells[c];
    }
    std::cout << line << '\n';
  };
  std::cout << "\n== " << title_ << " ==\n";
  printRow(columns_);
  for (const auto& row : rows_) printRow(row);
  std::cout.flush();
}

bool Table::writeCsv(const std::string& inPath) const {
  std::ofstream file(inPath);
  if (!file) return false;
  auto writeRow = [&](const std::vector<std::string>& inCells) {
    for (std::size_t c = 0; c < inCells.size(); ++c) {
      file << (c > 0 ? "," : "") << csvCell(inCells[c]);
    }
    file << '\n';
  };
  writeRow(columns_);
  for (const auto& row : rows_) writeRow(row);
  return static_cast<bool>(file);
}

std::string fmt(double inValue, int inDigits) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*g", inDigits, inValue);
  return buffer;
}

std::string fmtRatio(double inNumerator, double inDenominator, int inDigits) {
  if (!(inNumerator > 0.0) || !(inDenominator > 0.0)) return "-";
  return fmt(inNumerator / inDenominator, inDigits);
}

std::string fmtCount(std::size_t inValue) {
  return std::to_string(inValue);
}

std::string fmtSize(std::size_t inValue) {
  if (inValue != 0 && (inValue & (inValue - 1)) == 0) {
    int exponent = 0;
    while ((std::size_t{1} << exponent) < inValue) ++exponent;
    return "2^" + std::to_string(exponent);
  }
  return std::to_string(inValue);
}

}  // namespace sap_bench
