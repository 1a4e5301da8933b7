// libFuzzer target: sap_broadphase/BoxArray messages, as serialized bytes (the first input
// byte even) or built from decoded box sets (odd), through the ROS conversions and the engine.
#include <cstdio>
#include <cstdlib>

#include "box_array_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  if (inSize == 0) return 0;
  const std::string problem =
      (inData[0] & 1) ? sap_broadphase::fuzz::checkBoxArrayFromBoxSetBytes(inData + 1, inSize - 1)
                      : sap_broadphase::fuzz::checkBoxArrayBytes(inData + 1, inSize - 1);
  if (!problem.empty()) {
    std::fprintf(stderr, "fuzz_box_array: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
