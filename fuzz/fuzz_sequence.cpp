// libFuzzer target: multi-frame sequences (the input picks the configuration, the first frame
// and the edits between frames) through one engine, every frame against the oracle.
#include <cstddef>
#include <cstdint>

#include "fuzz_checks.h"
#include "sequence_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  using namespace sap_broadphase::fuzz;
  return reportProblem("fuzz_sequence", checkSequenceBytes(inData, inSize));
}
