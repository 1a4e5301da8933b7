// The box/pair text format: a line tokenizer, strict number parsing, and buffered writers.
#include "sap_broadphase/core/text_io.h"

#include "sap_broadphase/core/config.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <istream>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace sap_broadphase {

namespace {

constexpr int kFieldCount = 7;  // id min_x min_y min_z max_x max_y max_z
const char* const kCoordinateNames[6] = {"min_x", "min_y", "min_z", "max_x", "max_y", "max_z"};
const char* const kAxisNames[3] = {"x", "y", "z"};

/// Whitespace inside a line; '\r' so that CRLF files read like LF files.
bool isBlank(char inChar) {
  return inChar == ' ' || inChar == '\t' || inChar == '\r' || inChar == '\v' || inChar == '\f';
}

/// A field of the current line: [begin, end) offsets into the line buffer.
struct Field {
  std::size_t begin;
  std::size_t end;
};

/// Splits inLine (up to a '#') into fields. A separator is a run of blanks, or one comma with
/// optional blanks around it; an empty field (",,", a leading or trailing comma) is an error.
/// Returns the number of fields found (it may exceed kFieldCount; only the first ones are
/// stored), or sets outReason.
std::size_t splitFields(const std::string& inLine, Field outFields[kFieldCount],
                        std::string& outReason) {
  std::size_t end = inLine.find('#');
  if (end == std::string::npos) end = inLine.size();
  std::size_t pos = 0;
  std::size_t count = 0;
  auto skipBlanks = [&]() {
    while (pos < end && isBlank(inLine[pos])) ++pos;
  };
  skipBlanks();
  if (pos == end) return 0;  // blank or comment-only line
  while (true) {
    if (inLine[pos] == ',') {
      outReason = "empty field " + std::to_string(count + 1) + " (two commas in a row or a " +
                  "leading comma)";
      return 0;
    }
    const std::size_t begin = pos;
    while (pos < end && !isBlank(inLine[pos]) && inLine[pos] != ',') ++pos;
    if (count < static_cast<std::size_t>(kFieldCount)) outFields[count] = Field{begin, pos};
    ++count;
    skipBlanks();
    if (pos == end) return count;
    if (inLine[pos] == ',') {
      ++pos;
      skipBlanks();
      if (pos == end) {
        outReason = "empty field " + std::to_string(count + 1) + " after a trailing comma";
        return 0;
      }
    }
  }
}

/// The field's text for messages, shortened when long.
std::string quoteField(const std::string& inLine, const Field& inField) {
  constexpr std::size_t kMaxShown = 40;
  const std::size_t length = inField.end - inField.begin;
  std::string text = inLine.substr(inField.begin, std::min(length, kMaxShown));
  if (length > kMaxShown) text += "...";
  return "'" + text + "'";
}

/// Parses a decimal id in [0, 2^32). Digits only: no sign, no base prefix, no spaces.
bool parseId(const std::string& inLine, const Field& inField, uint32_t& outId,
             std::string& outReason) {
  const char* first = inLine.data() + inField.begin;
  const char* last = inLine.data() + inField.end;
  const bool negative = first != last && *first == '-';
  const char* digits = negative ? first + 1 : first;
  const bool allDigits =
      digits != last && std::all_of(digits, last, [](char c) { return c >= '0' && c <= '9'; });
  if (!allDigits) {
    outReason = "id is not a decimal integer: " + quoteField(inLine, inField);
    return false;
  }
  uint64_t value = 0;
  const auto result = std::from_chars(digits, last, value);
  if (negative || result.ec != std::errc() || value > UINT32_MAX) {
    outReason = "id out of range (0..4294967295): " + quoteField(inLine, inField);
    return false;
  }
  outId = static_cast<uint32_t>(value);
  return true;
}

/// Reads a whole field as strtod does. std::from_chars (correctly rounded, like glibc's strtod,
/// and several times faster) takes the common decimal spellings; whatever it does not take
/// completely (a '+' sign, hex floats, out-of-range values) goes to strtod, the reference.
/// ioLine is the line buffer: the character after the field is set to '\0' for strtod.
bool readNumber(std::string& ioLine, const Field& inField, double& outValue) {
  const char* first = ioLine.data() + inField.begin;
  const char* last = ioLine.data() + inField.end;
  const auto fast = std::from_chars(first, last, outValue);
  if (fast.ec == std::errc() && fast.ptr == last) return true;
  const char saved = ioLine[inField.end];  // ioLine.size() is valid: std::string ends in '\0'
  ioLine[inField.end] = '\0';
  char* parsedEnd = nullptr;
  outValue = std::strtod(first, &parsedEnd);  // overflow gives +-inf, underflow 0/subnormal
  ioLine[inField.end] = saved;
  return parsedEnd == last;
}

/// The text format's wording of a NaN in coordinate inIndex (0..5 = min_x..max_z).
std::string nanReason(int inIndex) {
  return std::string("NaN in ") + kCoordinateNames[inIndex];
}

/// Shortest text that reads back as exactly inValue ("inf", "-inf", "-0" included).
std::string formatDouble(double inValue) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), inValue);
  return std::string(buffer, result.ptr);
}

/// Parses one non-blank line into a box, its values as written (NaN and min > max included:
/// validate() judges them once the file is read); the reason is set on a syntax error. A NaN
/// read before a field that is not a number on the same line is the line's first problem.
bool parseBoxLine(std::string& ioLine, const Field inFields[kFieldCount], uint32_t& outId,
                  double outMin[3], double outMax[3], std::string& outReason) {
  if (!parseId(ioLine, inFields[0], outId, outReason)) return false;
  int first_nan = -1;
  for (int k = 0; k < 6; ++k) {
    double& value = k < 3 ? outMin[k] : outMax[k - 3];
    if (!readNumber(ioLine, inFields[k + 1], value)) {
      outReason = first_nan >= 0 ? nanReason(first_nan)
                                 : std::string(kCoordinateNames[k]) +
                                       " is not a number: " + quoteField(ioLine, inFields[k + 1]);
      return false;
    }
    if (first_nan < 0 && std::isnan(value)) first_nan = k;
  }
  return true;
}

/// The first problem validate() finds among the boxes read so far, worded for the line it is
/// on (inLines[i] is the line of box i); nothing when they are valid.
std::optional<ParseError> problemOfBoxes(const BoxSet& inBoxes,
                                         const std::vector<std::size_t>& inLines,
                                         const std::string& inSource) {
  const std::optional<ValidationError> error = validate(inBoxes);
  if (!error) return std::nullopt;
  const std::size_t i = error->index;
  std::string reason = error->reason;
  switch (error->problem) {
    case BoxProblem::kNaN:
      reason = nanReason(error->coordinate);
      break;
    case BoxProblem::kMinAboveMax: {
      const int axis = error->coordinate;
      reason = std::string("min_") + kAxisNames[axis] + " (" + formatDouble(inBoxes.lo(axis, i)) +
               ") > max_" + kAxisNames[axis] + " (" + formatDouble(inBoxes.hi(axis, i)) + ")";
      break;
    }
    case BoxProblem::kDuplicateId:
      reason = "duplicate id " + std::to_string(error->id) + " (first on line " +
               std::to_string(inLines[error->earlier]) + ")";
      break;
    case BoxProblem::kShape:
    case BoxProblem::kIdOverflow:
      break;
  }
  return ParseError{inSource, i < inLines.size() ? inLines[i] : 0, reason};
}

/// Collects output text and hands it to the stream in large blocks.
class BlockWriter {
 public:
  explicit BlockWriter(std::ostream& ioOutput) : output_(ioOutput) {}
  ~BlockWriter() { flush(); }
  /// Room for at least inBytes more characters; returns where to write them.
  char* reserve(std::size_t inBytes) {
    if (used_ + inBytes > sizeof(buffer_)) flush();
    return buffer_ + used_;
  }
  /// Marks the characters up to inEnd as written.
  void commit(char* inEnd) { used_ = static_cast<std::size_t>(inEnd - buffer_); }
  void flush() {
    if (used_ > 0) output_.write(buffer_, static_cast<std::streamsize>(used_));
    used_ = 0;
  }

 private:
  std::ostream& output_;
  char buffer_[1 << 16];
  std::size_t used_ = 0;
};

/// Reads one line of ioInput into outLine (without its '\n'); false at the end of the input.
/// A line longer than kMaxTextLineBytes sets outTooLong and is not read further: an endless
/// line costs kMaxTextLineBytes, not the machine's memory.
bool readBoundedLine(std::istream& ioInput, std::string& outLine, bool& outTooLong) {
  outLine.clear();
  outTooLong = false;
  std::streambuf* buffer = ioInput.rdbuf();
  if (!buffer) {
    ioInput.setstate(std::ios::badbit);
    return false;
  }
  bool any = false;
  while (true) {
    const int next = buffer->sbumpc();
    if (next == std::char_traits<char>::eof()) {
      if (!any) ioInput.setstate(std::ios::eofbit | std::ios::failbit);
      return any;
    }
    any = true;
    if (next == '\n') return true;
    if (outLine.size() == kMaxTextLineBytes) {
      outTooLong = true;
      return true;
    }
    outLine.push_back(static_cast<char>(next));
  }
}

}  // namespace

std::string ParseError::message() const {
  return source + ":" + std::to_string(line) + ": " + reason;
}

std::optional<ParseError> readBoxText(std::istream& ioInput, const std::string& inSource,
                                      BoxSet& outBoxes) {
  outBoxes.clear();
  std::vector<std::size_t> boxLines;  // line of each box, for messages
  std::string line;
  std::size_t lineNumber = 0;
  // The first problem in file order: one among the boxes read so far (validate()), which lie
  // on earlier lines, else the one found on line inLine.
  auto fail = [&](std::size_t inLine, std::string inReason) {
    std::optional<ParseError> earlier = problemOfBoxes(outBoxes, boxLines, inSource);
    outBoxes.clear();
    return earlier ? *earlier : ParseError{inSource, inLine, std::move(inReason)};
  };
  bool too_long = false;
  while (readBoundedLine(ioInput, line, too_long)) {
    ++lineNumber;
    if (too_long)
      return fail(lineNumber, "line longer than " + std::to_string(kMaxTextLineBytes) + " bytes");
    Field fields[kFieldCount];
    std::string reason;
    const std::size_t count = splitFields(line, fields, reason);
    if (!reason.empty()) return fail(lineNumber, reason);
    if (count == 0) continue;
    if (count != static_cast<std::size_t>(kFieldCount)) {
      return fail(lineNumber, "expected 7 fields (id min_x min_y min_z max_x max_y max_z), found " +
                                  std::to_string(count));
    }
    if (outBoxes.size() == kMaxBoxes)
      return fail(lineNumber, "more than " + std::to_string(kMaxBoxes) + " boxes");
    uint32_t id = 0;
    double lo[3];
    double hi[3];
    if (!parseBoxLine(line, fields, id, lo, hi, reason)) return fail(lineNumber, reason);
    outBoxes.add(id, lo, hi);
    boxLines.push_back(lineNumber);
  }
  if (ioInput.bad()) return fail(lineNumber + 1, "read error");
  if (std::optional<ParseError> problem = problemOfBoxes(outBoxes, boxLines, inSource)) {
    outBoxes.clear();
    return problem;
  }
  return std::nullopt;
}

void writeBoxText(std::ostream& ioOutput, const BoxSet& inBoxes) {
  BlockWriter writer(ioOutput);
  constexpr std::size_t kMaxLineBytes = 16 + 6 * 32;  // id + six shortest doubles (<= 24 each)
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    char* out = writer.reserve(kMaxLineBytes);
    out = std::to_chars(out, out + 16, inBoxes.ids[i]).ptr;
    for (int k = 0; k < 6; ++k) {
      const double value = k < 3 ? inBoxes.lo(k, i) : inBoxes.hi(k - 3, i);
      *out++ = ' ';
      out = std::to_chars(out, out + 31, value).ptr;
    }
    *out++ = '\n';
    writer.commit(out);
  }
}

void writePairText(std::ostream& ioOutput, const PairList& inPairs) {
  BlockWriter writer(ioOutput);
  constexpr std::size_t kMaxLineBytes = 2 * 11 + 2;
  for (const IdPair& pair : inPairs) {
    char* out = writer.reserve(kMaxLineBytes);
    out = std::to_chars(out, out + 11, pair.a).ptr;
    *out++ = ' ';
    out = std::to_chars(out, out + 11, pair.b).ptr;
    *out++ = '\n';
    writer.commit(out);
  }
}

}  // namespace sap_broadphase
