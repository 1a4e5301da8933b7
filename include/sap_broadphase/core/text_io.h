// The box/pair text format of the CLI (`sap_pairs`, `sap_scene`).
#pragma once

#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// Where and why a text input was refused.
struct ParseError {
  std::string source;    ///< file name, or "-" for standard input
  std::size_t line = 0;  ///< 1-based line number (0 when the file could not be read at all)
  std::string reason;
  /// "FILE:LINE: reason"
  std::string message() const;
};

/// Reads one box a line: `id min_x min_y min_z max_x max_y max_z`, fields separated by spaces,
/// tabs or commas; blank lines and anything after '#' ignored; numbers as strtod reads them.
/// Refuses wrong field counts, non-numbers, ids outside uint32, duplicate ids, NaN and
/// min > max, naming the line. outBoxes is replaced.
std::optional<ParseError> readBoxText(std::istream& ioInput, const std::string& inSource,
                                      BoxSet& outBoxes);
/// Writes boxes in the same format, with round-trip precision.
void writeBoxText(std::ostream& ioOutput, const BoxSet& inBoxes);
/// Writes one pair a line, `a b`.
void writePairText(std::ostream& ioOutput, const PairList& inPairs);

}  // namespace sap_broadphase
