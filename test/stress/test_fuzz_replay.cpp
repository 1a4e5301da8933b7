// The text and box-set fuzzers' corpora and crash regressions, replayed.
#include <gtest/gtest.h>

#include "fuzz_checks.h"
#include "fuzz_replay.h"

namespace sap_broadphase::stress {
namespace {

TEST(FuzzReplay, TextParserCorpusAndRegressions) {
  const auto inputs = fuzzInputs("text");
  ASSERT_FALSE(inputs.empty()) << "no seed corpus under " << SAP_FUZZ_DIR;
  for (const std::string& path : inputs) {
    const std::vector<uint8_t> bytes = readBytes(path);
    EXPECT_EQ("", fuzz::checkTextInput(bytes.data(), bytes.size())) << path;
  }
}

TEST(FuzzReplay, BoxSetValidationCorpusAndRegressions) {
  const auto inputs = fuzzInputs("boxset");
  ASSERT_FALSE(inputs.empty()) << "no seed corpus under " << SAP_FUZZ_DIR;
  for (const std::string& path : inputs) {
    const std::vector<uint8_t> bytes = readBytes(path);
    EXPECT_EQ("", fuzz::checkBoxSetBytes(bytes.data(), bytes.size())) << path;
  }
}

}  // namespace
}  // namespace sap_broadphase::stress
