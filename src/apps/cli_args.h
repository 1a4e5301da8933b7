// Command-line plumbing shared by the CLI tools: option walking, strict value parsing, exit codes.
#pragma once

#include <cstdint>
#include <string>

namespace sap_broadphase::cli {

/// Exit statuses of every tool: 0 success, 1 unexpected failure (out of memory, output not
/// writable), 2 bad input or bad usage (with a message on stderr and nothing on stdout).
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

/// Walks argv left to right. Options are `--name value` or `--name=value`; `--` ends options;
/// `-` alone and anything not starting with '-' are operands.
class ArgCursor {
 public:
  ArgCursor(int inArgc, char** inArgv) : argc_(inArgc), argv_(inArgv) {}
  /// True while arguments remain.
  bool more() const { return index_ < argc_; }
  /// Takes the next argument. outIsOption is set for options (then outText is the name, e.g.
  /// "--threads", and an attached "=value" is kept for takeValue()); operands come whole.
  void next(std::string& outText, bool& outIsOption);
  /// The value of the option just taken: its "=value" part, or else the next argument.
  /// Returns false (with outError set) when there is none.
  bool takeValue(const std::string& inOptionName, std::string& outValue, std::string& outError);
  /// True when the option just taken carried an "=value" (an error for flags without values).
  bool hasAttachedValue() const { return has_attached_; }

 private:
  int argc_;
  char** argv_;
  int index_ = 1;
  bool options_ended_ = false;
  bool has_attached_ = false;
  std::string attached_;
};

/// Parses a decimal integer in [inMin, inMax] (digits with an optional leading '-', nothing
/// else). Returns false on anything else.
bool parseInteger(const std::string& inText, int64_t inMin, int64_t inMax, int64_t& outValue);
/// Parses a decimal unsigned 64-bit integer (digits only).
bool parseUnsigned64(const std::string& inText, uint64_t& outValue);
/// Parses a finite double as strtod reads it; the whole text must be consumed.
bool parseFiniteDouble(const std::string& inText, double& outValue);
/// Parses "x", "y" or "z" into 0, 1 or 2.
bool parseAxisName(const std::string& inText, int& outAxis);

/// Prints "PROGRAM: MESSAGE" and the usage text to stderr; returns kExitBadInput.
int reportUsageError(const char* inProgram, const std::string& inMessage, const char* inUsage);

/// Exit status once the output is written: kExitOk, or kExitFailure with "PROGRAM: cannot
/// write the output" when standard output failed (full disk, closed pipe).
int finishOutput(const char* inProgram);

/// Runs inRun(argc, argv) and turns an escaping exception into "PROGRAM: what" and
/// kExitFailure: the body of both tools' main().
int runMain(const char* inProgram, int (*inRun)(int, char**), int inArgc, char** inArgv);

}  // namespace sap_broadphase::cli
