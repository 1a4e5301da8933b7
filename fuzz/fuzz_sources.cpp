// libFuzzer target: the node's ~sources list, as YAML text (the first input byte even) or as
// XML-RPC values built from the bytes (odd), through parseSourceSpecs and the resolved-name
// check (fuzz/sources_checks.h).
#include <cstddef>
#include <cstdint>

#include "fuzz_checks.h"
#include "sources_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* inData, size_t inSize) {
  using namespace sap_broadphase::fuzz;
  return reportProblem("fuzz_sources", checkSourcesInput(inData, inSize));
}
