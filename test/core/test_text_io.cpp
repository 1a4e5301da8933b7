// The box text format: separators, comments, strtod numbers, and every refusal with its line.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sap_broadphase/core/config.h"
#include "sap_broadphase/core/text_io.h"

namespace sap_broadphase {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Parses inText; expects success.
BoxSet parseOk(const std::string& inText) {
  std::istringstream input(inText);
  BoxSet boxes;
  const auto error = readBoxText(input, "t.txt", boxes);
  EXPECT_FALSE(error.has_value()) << (error ? error->message() : "");
  return boxes;
}

/// Parses inText; expects a refusal and returns it.
ParseError parseBad(const std::string& inText) {
  std::istringstream input(inText);
  BoxSet boxes;
  boxes.add(99, std::array<double, 3>{0, 0, 0}.data(), std::array<double, 3>{1, 1, 1}.data());
  const auto error = readBoxText(input, "t.txt", boxes);
  EXPECT_TRUE(error.has_value()) << "accepted: " << inText;
  EXPECT_EQ(boxes.size(), 0u) << "a refused input leaves no boxes";
  return error.value_or(ParseError{});
}

bool sameBits(double inA, double inB) {
  return std::memcmp(&inA, &inB, sizeof inA) == 0;
}

TEST(TextIo, ReadsOneBoxPerLine) {
  const BoxSet boxes = parseOk("7 1 2 3 4 5 6\n8 -1 -2 -3 0 0 0\n");
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes.ids[0], 7u);
  EXPECT_EQ(boxes.ids[1], 8u);
  EXPECT_EQ(boxes.lo(0, 0), 1.0);
  EXPECT_EQ(boxes.lo(1, 0), 2.0);
  EXPECT_EQ(boxes.lo(2, 0), 3.0);
  EXPECT_EQ(boxes.hi(0, 0), 4.0);
  EXPECT_EQ(boxes.hi(1, 0), 5.0);
  EXPECT_EQ(boxes.hi(2, 0), 6.0);
  EXPECT_EQ(boxes.lo(2, 1), -3.0);
  EXPECT_TRUE(boxes.groups.empty());
  EXPECT_TRUE(boxes.masks.empty());
}

TEST(TextIo, EverySeparatorAndMixture) {
  const char* const kLines[] = {
      "1 0 0 0 1 1 1",        "1\t0\t0\t0\t1\t1\t1", "1,0,0,0,1,1,1",
      "1, 0 ,0 , 0,\t1 ,1,1", "  1   0 0 0 1 1 1  ", "\t1 0\t \t0 0 1 1 1\t",
      "1 0 0 0 1 1 1\r",      "1,0,0 0\t1 1,1",      "1 ,0, 0 ,0\t,\t1,1 1"};
  for (const char* line : kLines) {
    const BoxSet boxes = parseOk(std::string(line) + "\n");
    ASSERT_EQ(boxes.size(), 1u) << line;
    EXPECT_EQ(boxes.ids[0], 1u) << line;
    EXPECT_EQ(boxes.hi(2, 0), 1.0) << line;
  }
}

TEST(TextIo, CommentsAndBlankLinesAreIgnored) {
  const BoxSet ok = parseOk(
      "# header comment\n"
      "\n"
      "   \t \n"
      "1 0 0 0 1 1 1 # trailing comment\n"
      "2 0 0 0 1 1 1# glued comment 1 2 3\n"
      "#3 0 0 0 1 1 1\n"
      "  # indented comment\n");
  ASSERT_EQ(ok.size(), 2u);
  EXPECT_EQ(ok.ids[1], 2u);
  EXPECT_EQ(ok.hi(2, 1), 1.0);
}

/// An endless input of one character and no newline (what /dev/zero is), counting what is read.
class EndlessBuffer : public std::streambuf {
 public:
  std::size_t taken = 0;

 protected:
  int_type underflow() override {
    setg(chunk_, chunk_, chunk_ + sizeof(chunk_));
    taken += sizeof(chunk_);
    return traits_type::to_int_type(chunk_[0]);
  }

 private:
  char chunk_[4096] = {};
};

// Issue 29: an endless line was read until memory ran out. It is refused once it is longer
// than kMaxTextLineBytes, having read no more than that (and a chunk).
TEST(TextIo, AnEndlessLineIsRefusedWhileBeingRead) {
  EndlessBuffer endless;
  std::istream input(&endless);
  BoxSet boxes;
  const auto error = readBoxText(input, "zero", boxes);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->message(),
            "zero:1: line longer than " + std::to_string(kMaxTextLineBytes) + " bytes");
  EXPECT_LE(endless.taken, kMaxTextLineBytes + 2 * 4096);
  EXPECT_EQ(boxes.size(), 0u);
}

TEST(TextIo, TheLongestLineIsRead) {
  std::string line = "7 0 0 0 1 1 1 #";
  line += std::string(kMaxTextLineBytes - line.size(), 'c');
  ASSERT_EQ(line.size(), kMaxTextLineBytes);
  std::istringstream input(line + "\n8 0 0 0 1 1 1");
  BoxSet boxes;
  EXPECT_EQ(readBoxText(input, "t.txt", boxes), std::nullopt);
  EXPECT_EQ(boxes.size(), 2u);
  std::istringstream longer(line + "c\n");
  const auto error = readBoxText(longer, "t.txt", boxes);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->line, 1u);
}

TEST(TextIo, EmptyInputIsNoBoxes) {
  EXPECT_EQ(parseOk("").size(), 0u);
  EXPECT_EQ(parseOk("\n\n# only comments\n").size(), 0u);
}

TEST(TextIo, LastLineWithoutNewline) {
  const BoxSet boxes = parseOk("1 0 0 0 1 1 1\n2 0 0 0 1 1 1");
  EXPECT_EQ(boxes.size(), 2u);
}

TEST(TextIo, NumbersAsStrtodReadsThem) {
  const BoxSet boxes = parseOk(
      "1 -inf -INF -Infinity inf +inf INFINITY\n"
      "2 -0.0 -0 0 0.0 +0 -0e10\n"
      "3 1e-300 -1E+300 .5 1e300 1E+300 5.\n"
      "4 0x1.8p1 -0X10 0x0p0 0x1p+2 0xAp0 0x1.fffffffffffffp1023\n"
      "5 4.9e-324 -4.9e-324 1e-323 1e-310 1e-320 2.2250738585072014e-308\n"
      "6 0.1 0.2 0.3 0.30000000000000004 1.7976931348623157e308 1e308\n"
      "0004294967295 0 0 0 0 0 0\n");
  ASSERT_EQ(boxes.size(), 7u);
  EXPECT_EQ(boxes.lo(0, 0), -kInf);
  EXPECT_EQ(boxes.lo(1, 0), -kInf);
  EXPECT_EQ(boxes.lo(2, 0), -kInf);
  EXPECT_EQ(boxes.hi(0, 0), kInf);
  EXPECT_EQ(boxes.hi(1, 0), kInf);
  EXPECT_EQ(boxes.hi(2, 0), kInf);
  EXPECT_TRUE(sameBits(boxes.lo(0, 1), -0.0));
  EXPECT_TRUE(sameBits(boxes.lo(1, 1), -0.0));
  EXPECT_TRUE(sameBits(boxes.lo(2, 1), 0.0));
  EXPECT_TRUE(sameBits(boxes.hi(2, 1), -0.0));
  EXPECT_EQ(boxes.lo(0, 2), 1e-300);
  EXPECT_EQ(boxes.lo(1, 2), -1e300);
  EXPECT_EQ(boxes.lo(2, 2), 0.5);
  EXPECT_EQ(boxes.hi(2, 2), 5.0);
  EXPECT_EQ(boxes.lo(0, 3), 3.0);
  EXPECT_EQ(boxes.lo(1, 3), -16.0);
  EXPECT_EQ(boxes.hi(0, 3), 4.0);
  EXPECT_EQ(boxes.hi(1, 3), 10.0);
  EXPECT_EQ(boxes.hi(2, 3), std::numeric_limits<double>::max());
  EXPECT_EQ(boxes.lo(0, 4), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(boxes.lo(1, 4), -std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(boxes.lo(2, 4), 1e-323);
  EXPECT_EQ(boxes.hi(2, 4), std::numeric_limits<double>::min());
  EXPECT_EQ(boxes.hi(1, 4), 1e-320);
  EXPECT_EQ(boxes.lo(0, 5), 0.1);
  EXPECT_EQ(boxes.hi(0, 5), 0.30000000000000004);
  EXPECT_EQ(boxes.ids[6], 4294967295u);
}

TEST(TextIo, EveryNumberReadsBitForBitAsStrtodReadsIt) {
  // Long mantissas, near-halfway digit strings, extreme exponents, signs and spellings.
  std::mt19937_64 random(7);
  std::vector<std::string> numbers = {"+1.5",
                                      "-.5e-3",
                                      "0x1p-1074",
                                      "0x1.000001p0",
                                      "1e-400",
                                      "-1e400",
                                      "2.4703282292062328e-324",
                                      "INF",
                                      "-Infinity",
                                      "1E0",
                                      "00012.500",
                                      "9007199254740993"};
  for (int k = 0; k < 20000; ++k) {
    std::string text = (random() % 3 == 0) ? "-" : "";
    const int digits = 1 + static_cast<int>(random() % 40);
    for (int d = 0; d < digits; ++d) text += static_cast<char>('0' + random() % 10);
    if (random() % 2) text.insert(text.size() - static_cast<std::size_t>(random() % digits), ".");
    if (text.back() == '.' || text == "-" || text.find('.') == 0) text += "5";
    if (random() % 4 != 0) text += "e" + std::to_string(static_cast<int>(random() % 700) - 350);
    numbers.push_back(text);
  }
  std::string input;
  for (std::size_t k = 0; k < numbers.size(); ++k)
    input += std::to_string(k) + " " + numbers[k] + " 0 0 inf 0 0\n";
  const BoxSet boxes = parseOk(input);
  ASSERT_EQ(boxes.size(), numbers.size());
  for (std::size_t k = 0; k < numbers.size(); ++k) {
    const double expected = std::strtod(numbers[k].c_str(), nullptr);
    ASSERT_TRUE(sameBits(boxes.lo(0, k), expected)) << numbers[k];
  }
}

TEST(TextIo, OverflowReadsAsInfinityLikeStrtod) {
  const BoxSet boxes = parseOk("1 -1e400 0 0 1e400 1e-400 0\n");
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes.lo(0, 0), -kInf);
  EXPECT_EQ(boxes.hi(0, 0), kInf);
  EXPECT_EQ(boxes.hi(1, 0), 0.0);
}

TEST(TextIo, InfiniteSlabsAndZeroExtentBoxesAreValid) {
  const BoxSet boxes = parseOk("1 -inf -inf -1 inf inf 0\n2 3 3 3 3 3 3\n3 -inf 0 0 -inf 0 0\n");
  EXPECT_EQ(boxes.size(), 3u);
}

TEST(TextIo, ReplacesPreviousContent) {
  std::istringstream input("5 0 0 0 1 1 1\n");
  BoxSet boxes;
  const double zero[3] = {0, 0, 0};
  boxes.add(1, zero, zero, 2u, 3u);
  boxes.add(2, zero, zero, 2u, 3u);
  ASSERT_FALSE(readBoxText(input, "x", boxes).has_value());
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes.ids[0], 5u);
  EXPECT_TRUE(boxes.groups.empty());
  EXPECT_TRUE(boxes.masks.empty());
}

/// Expects inText to be refused on inLine with a reason containing inWords.
void expectRefused(const std::string& inText, std::size_t inLine, const std::string& inWords) {
  const ParseError error = parseBad(inText);
  EXPECT_EQ(error.source, "t.txt");
  EXPECT_EQ(error.line, inLine) << inText << " -> " << error.message();
  EXPECT_NE(error.reason.find(inWords), std::string::npos)
      << "reason '" << error.reason << "' lacks '" << inWords << "'";
  EXPECT_EQ(error.message().rfind("t.txt:" + std::to_string(inLine) + ": ", 0), 0u)
      << error.message();
}

const char* const kGood = "1 0 0 0 1 1 1\n";

TEST(TextIo, RefusesWrongFieldCounts) {
  expectRefused("1 0 0 0 1 1\n", 1, "expected 7 fields");
  expectRefused(std::string(kGood) + "2 0 0 0 1 1 1 1\n", 2, "found 8");
  expectRefused("# c\n\n3\n", 3, "found 1");
  expectRefused("1 0 0 0 1 1 # 1\n", 1, "found 6");
  expectRefused("1;0;0;0;1;1;1\n", 1, "found 1");
}

TEST(TextIo, RefusesEmptyFields) {
  expectRefused("1,,0,0,0,1,1,1\n", 1, "empty field 2");
  expectRefused(",1,0,0,0,1,1,1\n", 1, "empty field 1");
  expectRefused("1,0,0,0,1,1,1,\n", 1, "empty field 8");
  expectRefused("1,0,0,0,1,1,1 , # comment\n", 1, "empty field 8");
  expectRefused("1 0 0 0 1 1 , , 1\n", 1, "empty field 7");
}

TEST(TextIo, RefusesNonNumbers) {
  expectRefused("1 abc 0 0 1 1 1\n", 1, "min_x is not a number: 'abc'");
  expectRefused(std::string(kGood) + "2 0 1.0x 0 1 1 1\n", 2, "min_y is not a number");
  expectRefused("1 0 0 1..2 1 1 3\n", 1, "min_z is not a number");
  expectRefused("1 0 0 0 0x 1 1\n", 1, "max_x is not a number");
  expectRefused("1 0 0 0 1 infx 1\n", 1, "max_y is not a number");
  expectRefused("1 0 0 0 1 1 -\n", 1, "max_z is not a number");
  expectRefused("1 0 0 0 1 1 1e\n", 1, "max_z is not a number");
  expectRefused(std::string("1 0 0 0 1 1 1") + '\0' + "5\n", 1, "max_z is not a number");
}

TEST(TextIo, RefusesBadIds) {
  expectRefused("1.5 0 0 0 1 1 1\n", 1, "id is not a decimal integer");
  expectRefused("x 0 0 0 1 1 1\n", 1, "id is not a decimal integer");
  expectRefused("0x10 0 0 0 1 1 1\n", 1, "id is not a decimal integer");
  expectRefused("+5 0 0 0 1 1 1\n", 1, "id is not a decimal integer");
  expectRefused("1e3 0 0 0 1 1 1\n", 1, "id is not a decimal integer");
  expectRefused("-1 0 0 0 1 1 1\n", 1, "id out of range");
  expectRefused(std::string(kGood) + "4294967296 0 0 0 1 1 1\n", 2, "id out of range");
  expectRefused("99999999999999999999999 0 0 0 1 1 1\n", 1, "id out of range");
}

TEST(TextIo, RefusesNaN) {
  expectRefused("1 nan 0 0 1 1 1\n", 1, "NaN in min_x");
  expectRefused("1 0 0 0 1 -nan 1\n", 1, "NaN in max_y");
  expectRefused("1 0 0 NAN(123) 1 1 1\n", 1, "NaN in min_z");
  expectRefused(std::string(kGood) + "\n2 0 0 0 1 1 NaN\n", 3, "NaN in max_z");
}

TEST(TextIo, RefusesMinAboveMax) {
  expectRefused("1 2 0 0 1 1 1\n", 1, "min_x (2) > max_x (1)");
  expectRefused("1 0 0.5 0 1 0.25 1\n", 1, "min_y (0.5) > max_y (0.25)");
  expectRefused("# x\n1 0 0 inf 1 1 1e308\n", 2, "min_z (inf) > max_z (1e+308)");
  expectRefused("1 0 0 0 -inf 1 1\n", 1, "min_x (0) > max_x (-inf)");
  expectRefused("1 0 0 1e-320 1 1 -0.0\n", 1, "min_z");
}

TEST(TextIo, MinusZeroEqualsZeroInsideOneBox) {
  const BoxSet boxes = parseOk("1 0 -0.0 0 -0.0 0 -0.0\n");
  EXPECT_EQ(boxes.size(), 1u);
}

TEST(TextIo, RefusesDuplicateIdsOnTheRepeatLine) {
  expectRefused("5 0 0 0 1 1 1\n6 0 0 0 1 1 1\n\n5 0 0 0 2 2 2\n", 4, "duplicate id 5");
  expectRefused("5 0 0 0 1 1 1\n6 0 0 0 1 1 1\n\n5 0 0 0 2 2 2\n", 4, "first on line 1");
  // Two repeated ids: the earliest repeat in the file is reported.
  expectRefused("9 0 0 0 1 1 1\n8 0 0 0 1 1 1\n8 0 0 0 1 1 1\n9 0 0 0 1 1 1\n", 3,
                "duplicate id 8 (first on line 2)");
  expectRefused("7 0 0 0 1 1 1\n7 0 0 0 1 1 1\n7 0 0 0 1 1 1\n", 2, "first on line 1");
}

TEST(TextIo, ReportsTheFirstProblemInFileOrder) {
  // The duplicate on line 2 comes before the NaN on line 3.
  expectRefused("1 0 0 0 1 1 1\n1 0 0 0 1 1 1\n2 nan 0 0 1 1 1\n", 2, "duplicate id 1");
  // The bad field count on line 2 comes before the duplicate on line 3.
  expectRefused("1 0 0 0 1 1 1\n2 0 0\n1 0 0 0 1 1 1\n", 2, "expected 7 fields");
  // The NaN on line 2 comes before the duplicate on line 3 and the non-number on line 4.
  expectRefused("1 0 0 0 1 1 1\n2 0 nan 0 1 1 1\n1 0 0 0 1 1 1\n3 x 0 0 1 1 1\n", 2,
                "NaN in min_y");
  // Within a line fields are read left to right: a NaN before a non-number is the problem,
  // and a NaN comes before min > max.
  expectRefused("1 nan 0 0 one 1 1\n", 1, "NaN in min_x");
  expectRefused("1 0 0 0 one 1 nan\n", 1, "max_x is not a number: 'one'");
  expectRefused("1 0 5 0 1 1 nan\n", 1, "NaN in max_z");
}

TEST(TextIo, LineNumbersCountEveryLine) {
  std::string text;
  for (int i = 0; i < 1000; ++i) {
    text += (i % 3 == 0) ? "# comment\n" : (i % 3 == 1 ? "\n" : "");
    text += std::to_string(i) + " 0 0 0 1 1 1\n";
  }
  // 1000 boxes + 334 comment lines + 333 blank lines = 1667 lines.
  text += "1000 0 0 0 1 1\n";
  expectRefused(text, 1668, "expected 7 fields");
}

TEST(TextIo, ErrorMessageFormat) {
  const ParseError error{"-", 12, "NaN in max_x"};
  EXPECT_EQ(error.message(), "-:12: NaN in max_x");
}

TEST(TextIo, WriteReadRoundTripIsBitExact) {
  std::mt19937_64 random(42);
  BoxSet boxes;
  const double specials[] = {0.0,
                             -0.0,
                             kInf,
                             -kInf,
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::min(),
                             std::numeric_limits<double>::max(),
                             -std::numeric_limits<double>::max(),
                             0.1,
                             1.0 / 3.0,
                             1e-300,
                             -1e300};
  for (uint32_t i = 0; i < 2000; ++i) {
    double lo[3];
    double hi[3];
    for (int axis = 0; axis < 3; ++axis) {
      double a;
      double b;
      if (i < 13 * 13) {
        a = specials[i % 13];
        b = specials[(i / 13 + axis) % 13];
      } else {
        uint64_t bitsA = random();
        uint64_t bitsB = random();
        std::memcpy(&a, &bitsA, sizeof a);
        std::memcpy(&b, &bitsB, sizeof b);
        if (std::isnan(a)) a = 1.5;
        if (std::isnan(b)) b = -2.5;
      }
      lo[axis] = a < b ? a : b;
      hi[axis] = a < b ? b : a;
    }
    boxes.add(i * 2654435761u, lo, hi);
  }
  std::ostringstream output;
  writeBoxText(output, boxes);
  const BoxSet back = parseOk(output.str());
  ASSERT_EQ(back.size(), boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    ASSERT_EQ(back.ids[i], boxes.ids[i]);
    for (int axis = 0; axis < 3; ++axis) {
      ASSERT_TRUE(sameBits(back.lo(axis, i), boxes.lo(axis, i))) << i;
      ASSERT_TRUE(sameBits(back.hi(axis, i), boxes.hi(axis, i))) << i;
    }
  }
}

TEST(TextIo, WritesOneBoxALineWithSevenFields) {
  BoxSet boxes;
  const double lo[3] = {-0.0, 0.5, -kInf};
  const double hi[3] = {1.0, 1e300, kInf};
  boxes.add(42, lo, hi);
  std::ostringstream output;
  writeBoxText(output, boxes);
  EXPECT_EQ(output.str(), "42 -0 0.5 -inf 1 1e+300 inf\n");
}

TEST(TextIo, WritesPairsOneALine) {
  std::ostringstream output;
  writePairText(output, PairList{{0, 1}, {3, 4294967295u}});
  EXPECT_EQ(output.str(), "0 1\n3 4294967295\n");
  std::ostringstream empty;
  writePairText(empty, PairList{});
  EXPECT_EQ(empty.str(), "");
}

TEST(TextIo, WritesLargeOutputsCompletely) {
  PairList pairs;
  for (uint32_t i = 0; i < 100000; ++i) pairs.push_back({i, i + 1});
  std::ostringstream output;
  writePairText(output, pairs);
  const std::string text = output.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 100000);
  EXPECT_EQ(text.substr(text.size() - 13), "99999 100000\n");
}

}  // namespace
}  // namespace sap_broadphase
