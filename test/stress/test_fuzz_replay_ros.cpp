// The BoxArray fuzzer's corpus and crash regressions, replayed (needs the ROS messages).
#include <gtest/gtest.h>

#include "box_array_checks.h"
#include "fuzz_replay.h"

namespace sap_broadphase::stress {
namespace {

TEST(FuzzReplay, BoxArrayCorpusAndRegressions) {
  const auto inputs = fuzzInputs("box_array");
  ASSERT_FALSE(inputs.empty()) << "no seed corpus under " << SAP_FUZZ_DIR;
  for (const std::string& path : inputs) {
    const std::vector<uint8_t> bytes = readBytes(path);
    if (bytes.empty()) continue;
    const std::string problem =
        (bytes[0] & 1) ? fuzz::checkBoxArrayFromBoxSetBytes(bytes.data() + 1, bytes.size() - 1)
                       : fuzz::checkBoxArrayBytes(bytes.data() + 1, bytes.size() - 1);
    EXPECT_EQ("", problem) << path;
  }
}

}  // namespace
}  // namespace sap_broadphase::stress
