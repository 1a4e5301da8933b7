// Command-line plumbing shared by the CLI tools.
#include "cli_args.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>

namespace sap_broadphase::cli {

void ArgCursor::next(std::string& outText, bool& outIsOption) {
  outText = argv_[index_++];
  has_attached_ = false;
  attached_.clear();
  outIsOption = !options_ended_ && outText.size() > 1 && outText[0] == '-';
  if (outIsOption && outText == "--") {
    options_ended_ = true;
    outIsOption = true;  // the caller skips "--" itself
    return;
  }
  if (!outIsOption) return;
  const std::size_t equals = outText.find('=');
  if (outText.rfind("--", 0) == 0 && equals != std::string::npos) {
    has_attached_ = true;
    attached_ = outText.substr(equals + 1);
    outText.resize(equals);
  }
}

bool ArgCursor::takeValue(const std::string& inOptionName, std::string& outValue,
                          std::string& outError) {
  if (has_attached_) {
    outValue = attached_;
    has_attached_ = false;
    return true;
  }
  if (index_ >= argc_) {
    outError = inOptionName + " needs a value";
    return false;
  }
  outValue = argv_[index_++];
  return true;
}

bool parseInteger(const std::string& inText, int64_t inMin, int64_t inMax, int64_t& outValue) {
  const char* first = inText.data();
  const char* last = first + inText.size();
  const char* digits = (first != last && *first == '-') ? first + 1 : first;
  if (digits == last || !std::all_of(digits, last, [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  int64_t value = 0;
  const auto result = std::from_chars(first, last, value);
  if (result.ec != std::errc() || result.ptr != last) return false;
  if (value < inMin || value > inMax) return false;
  outValue = value;
  return true;
}

bool parseUnsigned64(const std::string& inText, uint64_t& outValue) {
  const char* first = inText.data();
  const char* last = first + inText.size();
  if (first == last || !std::all_of(first, last, [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  const auto result = std::from_chars(first, last, outValue);
  return result.ec == std::errc() && result.ptr == last;
}

bool parseFiniteDouble(const std::string& inText, double& outValue) {
  if (inText.empty() || std::isspace(static_cast<unsigned char>(inText[0]))) return false;
  char* end = nullptr;
  const double value = std::strtod(inText.c_str(), &end);
  if (end != inText.c_str() + inText.size() || !std::isfinite(value)) return false;
  outValue = value;
  return true;
}

bool parseAxisName(const std::string& inText, int& outAxis) {
  if (inText.size() != 1 || inText[0] < 'x' || inText[0] > 'z') return false;
  outAxis = inText[0] - 'x';
  return true;
}

int reportUsageError(const char* inProgram, const std::string& inMessage, const char* inUsage) {
  std::fprintf(stderr, "%s: %s\n\n%s", inProgram, inMessage.c_str(), inUsage);
  return kExitBadInput;
}

int finishOutput(const char* inProgram) {
  std::cout.flush();
  if (std::cout) return kExitOk;
  std::fprintf(stderr, "%s: cannot write the output\n", inProgram);
  return kExitFailure;
}

int runMain(const char* inProgram, int (*inRun)(int, char**), int inArgc, char** inArgv) {
  try {
    return inRun(inArgc, inArgv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", inProgram, e.what());
    return kExitFailure;
  }
}

}  // namespace sap_broadphase::cli
