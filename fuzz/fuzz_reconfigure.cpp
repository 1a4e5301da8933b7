// libFuzzer target: dynamic_reconfigure requests through the server's steps and the node's
// check of them, fromReconfigureConfig (fuzz/reconfigure_checks.h).
#include <cstddef>
#include <cstdint>

#include "fuzz_checks.h"
#include "reconfigure_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  using namespace sap_broadphase::fuzz;
  return reportProblem("fuzz_reconfigure", checkReconfigureInput(inData, inSize));
}
