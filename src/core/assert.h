// SAP_ASSERT: what each part of the engine guarantees, stated where it is established and
// checked in Debug builds and in builds with SAP_ASSERTS defined (cmake -DSAP_ASSERTS=ON, as
// scripts/test_no_ros.sh builds the core tests a second time). Off in Release: the condition
// is then not evaluated, so an assertion may scan a whole frame.
//
// The lowest floor of the engine: it includes nothing of it.
#pragma once

#include <cstdio>
#include <cstdlib>

#if defined(SAP_ASSERTS) || !defined(NDEBUG)
#define SAP_ASSERTS_ON 1
#else
#define SAP_ASSERTS_ON 0
#endif

namespace sap_broadphase::detail {

/// Prints the broken invariant and where it is stated, then aborts: an engine that broke its
/// own guarantee cannot be trusted with the next frame either.
[[noreturn]] inline void assertionFailed(const char* inCondition, const char* inMessage,
                                         const char* inFile, int inLine) {
  std::fprintf(stderr, "%s:%d: sap_broadphase invariant broken: %s (%s)\n", inFile, inLine,
               inMessage, inCondition);
  std::abort();
}

}  // namespace sap_broadphase::detail

#if SAP_ASSERTS_ON
#define SAP_ASSERT(condition, message) \
  ((condition)                         \
       ? static_cast<void>(0)          \
       : ::sap_broadphase::detail::assertionFailed(#condition, message, __FILE__, __LINE__))
#else
#define SAP_ASSERT(condition, message) static_cast<void>(sizeof(static_cast<bool>(condition)))
#endif
