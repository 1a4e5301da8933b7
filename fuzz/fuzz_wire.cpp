// libFuzzer target: the node's message decoders (WireLayout before roscpp) fed arbitrary,
// truncated and lying bytes of every type the node reads from the wire.
#include <cstddef>
#include <cstdint>

#include "fuzz_checks.h"
#include "wire_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  using namespace sap_broadphase::fuzz;
  return reportProblem("fuzz_wire", checkWireInput(inData, inSize));
}
