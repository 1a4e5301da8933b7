// The BoxArray fuzzer's corpus and crash regressions, replayed (needs the ROS messages).
#include <gtest/gtest.h>

#include "box_array_checks.h"
#include "fuzz_replay.h"

namespace sap_broadphase::stress {
namespace {

TEST(FuzzReplay, BoxArrayCorpusAndRegressions) {
  expectCorpusClean("box_array", fuzz::checkBoxArrayInput);
}

}  // namespace
}  // namespace sap_broadphase::stress
