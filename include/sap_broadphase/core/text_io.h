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
  std::string source;    ///< the name the caller gave (the CLI: the path, or "<stdin>")
  std::size_t line = 0;  ///< 1-based line number (0 when the file could not be read at all)
  std::string reason;
  /// "FILE:LINE: reason"
  std::string message() const;
};

/// Reads one box a line: `id min_x min_y min_z max_x max_y max_z`.
/// - Fields are separated by a run of blanks (space, tab, CR, VT, FF), or by one comma with
///   optional blanks around it; an empty field (",,", a leading or trailing comma) is refused.
/// - Blank lines, and anything from '#' to the end of a line, are ignored.
/// - Coordinates are read by strtod in the "C" locale and must consume the whole field:
///   decimal, exponents, hex floats, inf/infinity, -0.0; overflow reads as +-inf and underflow
///   as a subnormal or zero, as strtod gives them. NaN is refused.
/// - Ids are decimal digits only (no sign, no prefix) in 0..4294967295, unique in the input.
/// Refuses wrong field counts, non-numbers, ids outside uint32, duplicate ids (on the line that
/// repeats the id), NaN, min > max and more than kMaxBoxes boxes, naming the first problem in
/// file order. outBoxes is replaced (no groups or masks); it is left empty on refusal.
std::optional<ParseError> readBoxText(std::istream& ioInput, const std::string& inSource,
                                      BoxSet& outBoxes);
/// Writes boxes in the same format, space-separated, each number the shortest text that reads
/// back bit-exactly ("-0", "inf" and "-inf" included). Groups and masks are not written.
void writeBoxText(std::ostream& ioOutput, const BoxSet& inBoxes);
/// Writes one pair a line, `a b`.
void writePairText(std::ostream& ioOutput, const PairList& inPairs);

}  // namespace sap_broadphase
