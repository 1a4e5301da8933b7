// libFuzzer target: validate() on raw box sets decoded from bytes, then the engine vs the
// oracle on the accepted ones.
#include <cstddef>
#include <cstdint>

#include "fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  using namespace sap_broadphase::fuzz;
  return reportProblem("fuzz_boxset", checkBoxSetBytes(inData, inSize));
}
