// The BoxArray, wire, ~sources and reconfigure fuzzers' corpora and crash regressions,
// replayed (need the ROS messages and the node's parameter readers).
#include <gtest/gtest.h>

#include "box_array_checks.h"
#include "fuzz_replay.h"
#include "reconfigure_checks.h"
#include "sources_checks.h"
#include "wire_checks.h"

namespace sap_broadphase::stress {
namespace {

TEST(FuzzReplay, BoxArrayCorpusAndRegressions) {
  expectCorpusClean("box_array", fuzz::checkBoxArrayInput);
}

TEST(FuzzReplay, WireCorpusAndRegressions) {
  expectCorpusClean("wire", fuzz::checkWireInput);
}

TEST(FuzzReplay, SourcesCorpusAndRegressions) {
  expectCorpusClean("sources", fuzz::checkSourcesInput);
}

TEST(FuzzReplay, ReconfigureCorpusAndRegressions) {
  expectCorpusClean("reconfigure", fuzz::checkReconfigureInput);
}

}  // namespace
}  // namespace sap_broadphase::stress
