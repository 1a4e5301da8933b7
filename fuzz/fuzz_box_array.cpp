// libFuzzer target: sap_broadphase/BoxArray messages, as serialized bytes (the first input
// byte even) or built from decoded box sets (odd), through the ROS conversions and the engine.
#include <cstddef>
#include <cstdint>

#include "box_array_checks.h"
#include "fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  using namespace sap_broadphase::fuzz;
  return reportProblem("fuzz_box_array", checkBoxArrayInput(inData, inSize));
}
