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

/// A fuzzer's property: empty when it holds for the input, else what went wrong.
using FuzzCheck = std::string (*)(const uint8_t* inData, std::size_t inSize);
/// Runs inCheck on every file of inTarget's corpus and regressions; fails when there is no
/// corpus (a wrong SAP_FUZZ_DIR must not pass as "nothing to replay") or a check fails.
void expectCorpusClean(const std::string& inTarget, FuzzCheck inCheck);

}  // namespace sap_broadphase::stress
