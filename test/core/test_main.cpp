// Entry point of the core and CLI test executables (catkin_add_gtest links no gtest_main).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>

int main(int argc, char** argv) {
  // The tests run up to 7 OpenMP threads on small machines. With libgomp's default spin-waiting,
  // oversubscribed barriers cost milliseconds each; passive waiting keeps the suite fast.
  // libgomp reads its environment when it is loaded, before main: re-execute once with it set.
  if (std::getenv("OMP_WAIT_POLICY") == nullptr) {
    setenv("OMP_WAIT_POLICY", "passive", 1);
    execv("/proc/self/exe", argv);  // only returns on failure: then carry on as we are
  }
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
