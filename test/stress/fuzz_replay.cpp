#include "fuzz_replay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#ifndef SAP_FUZZ_DIR
#error "SAP_FUZZ_DIR must name the fuzz/ directory of the sources"
#endif

namespace sap_broadphase::stress {

std::vector<std::string> fuzzInputs(const std::string& inTarget) {
  namespace fs = std::filesystem;
  std::vector<std::string> paths;
  for (const char* kind : {"corpus", "regressions"}) {
    const fs::path directory = fs::path(SAP_FUZZ_DIR) / kind / inTarget;
    if (!fs::is_directory(directory)) continue;
    for (const auto& entry : fs::directory_iterator(directory))
      if (entry.is_regular_file() && entry.path().filename() != ".gitkeep")
        paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

std::vector<uint8_t> readBytes(const std::string& inPath) {
  std::ifstream file(inPath, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(file),
                              std::istreambuf_iterator<char>());
}

void expectCorpusClean(const std::string& inTarget, FuzzCheck inCheck) {
  const std::vector<std::string> inputs = fuzzInputs(inTarget);
  ASSERT_FALSE(inputs.empty()) << "no " << inTarget << " seed corpus under " << SAP_FUZZ_DIR;
  for (const std::string& path : inputs) {
    const std::vector<uint8_t> bytes = readBytes(path);
    EXPECT_EQ("", inCheck(bytes.data(), bytes.size())) << path;
  }
}

}  // namespace sap_broadphase::stress
