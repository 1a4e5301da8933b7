// The BoxArray and wire fuzzers' corpora and crash regressions, replayed (need the ROS
// messages).
#include <gtest/gtest.h>

#include "box_array_checks.h"
#include "fuzz_replay.h"
#include "wire_checks.h"

namespace sap_broadphase::stress {
namespace {

TEST(FuzzReplay, BoxArrayCorpusAndRegressions) {
  expectCorpusClean("box_array", fuzz::checkBoxArrayInput);
}

TEST(FuzzReplay, WireCorpusAndRegressions) {
  expectCorpusClean("wire", fuzz::checkWireInput);
}

}  // namespace
}  // namespace sap_broadphase::stress
