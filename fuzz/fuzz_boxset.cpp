// libFuzzer target: validate() on raw box sets decoded from bytes, then the engine vs the
// oracle on the accepted ones.
#include <cstdio>
#include <cstdlib>

#include "fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  const std::string problem = sap_broadphase::fuzz::checkBoxSetBytes(inData, inSize);
  if (!problem.empty()) {
    std::fprintf(stderr, "fuzz_boxset: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
