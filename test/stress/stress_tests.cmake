# The numerical stress suite (issue 5 §2) and the replay of the fuzzers' corpora and crash
# regressions (§3), against the brute-force oracle. Included by test/tests.cmake under
# CATKIN_ENABLE_TESTING. Release run time: about 40 s on 2 cores; no test asserts on timing.

catkin_add_gtest(test_stress
  test/stress/test_stress_magnitudes.cpp
  test/stress/test_stress_infinity.cpp
  test/stress/test_stress_ulp.cpp
  test/stress/test_stress_degenerate.cpp
  test/stress/test_stress_sequence.cpp
  test/stress/stress_scenes.cpp
  test/stress/stress_support.cpp
  test/stress/stress_main.cpp
)
target_include_directories(test_stress PRIVATE test/stress)
target_link_libraries(test_stress ${PROJECT_NAME}_core)
