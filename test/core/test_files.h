// Files and processes for the tests that run the project's executables (the CLI, the MPI
// programs): a temporary folder per test, whole files read and written, shell quoting, and a
// command run with its output captured. Header-only: each test binary that needs it includes it.
#pragma once

#include <stdlib.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace sap_broadphase::test_files {

/// What one run of a command left behind.
struct RunResult {
  int status = -1;  ///< exit status, or -1 when it did not exit normally
  std::string out;
  std::string err;
};

/// A temporary folder for one test (/tmp/<inPrefix>XXXXXX), removed with what it holds.
class TempDir {
 public:
  explicit TempDir(const std::string& inPrefix = "sap_test_") {
    std::string pattern = "/tmp/" + inPrefix + "XXXXXX";
    const char* made = mkdtemp(pattern.data());
    path_ = made ? made : "";
  }
  ~TempDir() {
    if (!path_.empty()) (void)std::system(("rm -rf '" + path_ + "'").c_str());
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  /// Path of a file inside the folder.
  std::string file(const std::string& inName) const { return path_ + "/" + inName; }

 private:
  std::string path_;
};

inline std::string readFile(const std::string& inPath) {
  std::ifstream file(inPath, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

inline void writeFile(const std::string& inPath, const std::string& inText) {
  std::ofstream file(inPath, std::ios::binary);
  file << inText;
}

/// Single-quotes inText for the shell.
inline std::string shellQuote(const std::string& inText) {
  std::string quoted = "'";
  for (char c : inText) quoted += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// inExe (quoted) followed by inArgs, each quoted: a command line for runCommand.
inline std::string commandLine(const std::string& inExe, const std::vector<std::string>& inArgs) {
  std::string command = shellQuote(inExe);
  for (const std::string& arg : inArgs) command += " " + shellQuote(arg);
  return command;
}

/// Runs inCommand (already quoted) with stdin from inStdinPath (or /dev/null), stdout and
/// stderr captured apart into inDir.
inline RunResult runCommand(const TempDir& inDir, const std::string& inCommand,
                            const std::string& inStdinPath = "") {
  const std::string outPath = inDir.file("stdout.txt");
  const std::string errPath = inDir.file("stderr.txt");
  const std::string command = inCommand + " < " +
                              shellQuote(inStdinPath.empty() ? "/dev/null" : inStdinPath) + " > " +
                              shellQuote(outPath) + " 2> " + shellQuote(errPath);
  const int raw = std::system(command.c_str());
  RunResult result;
  result.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
  result.out = readFile(outPath);
  result.err = readFile(errPath);
  return result;
}

}  // namespace sap_broadphase::test_files
