// A result table: printed aligned on stdout and written as CSV, one per experiment.
#pragma once

#include <string>
#include <vector>

namespace sap_bench {

/// Rows of text cells under named columns.
class Table {
 public:
  Table(std::string inTitle, std::vector<std::string> inColumns);
  /// Appends a row; it must have one cell per column.
  void addRow(std::vector<std::string> inCells);
  /// Prints the title and the aligned table to stdout.
  void print() const;
  /// Writes header and rows as CSV; returns false when the file cannot be written.
  bool writeCsv(const std::string& inPath) const;
  std::size_t rowCount() const { return rows_.size(); }

 private:
  std::string title_;
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> rows_;
};

/// Formats a number with inDigits significant digits ("%.*g").
std::string fmt(double inValue, int inDigits = 4);
/// inNumerator / inDenominator formatted, or "-" when either is not positive.
std::string fmtRatio(double inNumerator, double inDenominator, int inDigits = 3);
/// Formats an integer count.
std::string fmtCount(std::size_t inValue);
/// "2^17" when inValue is a power of two, else the plain count.
std::string fmtSize(std::size_t inValue);

}  // namespace sap_bench
