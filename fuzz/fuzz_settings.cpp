// libFuzzer target: every value a front end can hand the engine's field table or the limits
// table (rosparam, dynamic_reconfigure requests, Python keywords, CLI flags).
#include <cstddef>
#include <cstdint>

#include "fuzz_checks.h"
#include "settings_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  using namespace sap_broadphase::fuzz;
  return reportProblem("fuzz_settings", checkSettingsInput(inData, inSize));
}
