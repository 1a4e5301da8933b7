// libFuzzer target: the CLI's text parser (readBoxText), then the engine vs the oracle.
#include <cstdio>
#include <cstdlib>

#include "fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  const std::string problem = sap_broadphase::fuzz::checkTextInput(inData, inSize);
  if (!problem.empty()) {
    std::fprintf(stderr, "fuzz_text: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
