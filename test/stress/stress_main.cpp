// Entry point of the stress test executables (catkin_add_gtest links no gtest_main).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>

int main(int argc, char** argv) {
  // Thread count 3 oversubscribes a 2-core machine; with libgomp's default spin-waiting every
  // barrier then costs milliseconds. libgomp reads OMP_WAIT_POLICY when it is loaded, before
  // main, so the process re-executes itself once with passive waiting.
  if (std::getenv("OMP_WAIT_POLICY") == nullptr) {
    setenv("OMP_WAIT_POLICY", "passive", 1);
    execv("/proc/self/exe", argv);  // only returns on failure: then carry on as we are
  }
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
