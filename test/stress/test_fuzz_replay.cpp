// The text, box-set, sequence and settings fuzzers' corpora and crash regressions, replayed.
#include <gtest/gtest.h>

#include "fuzz_checks.h"
#include "fuzz_replay.h"
#include "sequence_checks.h"
#include "settings_checks.h"

namespace sap_broadphase::stress {
namespace {

TEST(FuzzReplay, TextParserCorpusAndRegressions) {
  expectCorpusClean("text", fuzz::checkTextInput);
}

TEST(FuzzReplay, BoxSetValidationCorpusAndRegressions) {
  expectCorpusClean("boxset", fuzz::checkBoxSetBytes);
}

TEST(FuzzReplay, FrameSequenceCorpusAndRegressions) {
  expectCorpusClean("sequence", fuzz::checkSequenceBytes);
}

TEST(FuzzReplay, SettingsCorpusAndRegressions) {
  expectCorpusClean("settings", fuzz::checkSettingsInput);
}

}  // namespace
}  // namespace sap_broadphase::stress
