// libFuzzer target: the CLI's text parser (readBoxText), then the engine vs the oracle.
#include <cstddef>
#include <cstdint>

#include "fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  using namespace sap_broadphase::fuzz;
  return reportProblem("fuzz_text", checkTextInput(inData, inSize));
}
