// SAP_ASSERT itself: on in Debug and SAP_ASSERTS builds (a broken invariant aborts with its
// message), off in Release (the condition is not even evaluated).
#include <gtest/gtest.h>

#include "core/assert.h"

namespace sap_broadphase {
namespace {

TEST(Asserts, ABrokenInvariantAbortsWithItsMessageOnlyWhereAssertsAreOn) {
  int evaluated = 0;
  SAP_ASSERT(++evaluated > 0, "holds");
#if SAP_ASSERTS_ON
  EXPECT_EQ(evaluated, 1);
  EXPECT_DEATH(SAP_ASSERT(evaluated == 2, "the count is two"),
               "invariant broken: the count is two \\(evaluated == 2\\)");
#else
  EXPECT_EQ(evaluated, 0) << "a Release build evaluates no assertion";
#endif
}

}  // namespace
}  // namespace sap_broadphase
