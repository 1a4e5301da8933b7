// Replays every file of the fuzzers' seed corpora and crash regressions through the same
// checks the libFuzzer targets run (fuzz/fuzz_checks.h), so a crash found once stays fixed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sap_broadphase::stress {

/// The files of SAP_FUZZ_DIR/corpus/<inTarget> and SAP_FUZZ_DIR/regressions/<inTarget>.
std::vector<std::string> fuzzInputs(const std::string& inTarget);
/// The bytes of a file (empty when it cannot be read).
std::vector<uint8_t> readBytes(const std::string& inPath);

}  // namespace sap_broadphase::stress
