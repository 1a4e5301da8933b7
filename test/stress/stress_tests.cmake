# The stress suite: hostile numbers (magnitudes, infinities, ulps, degenerate boxes) and
# multi-frame sequences through every path where the engine skips work, against the
# brute-force oracle; then the replay of the fuzzers' corpora and crash regressions
# (docs/ROBUSTNESS.md). Included by test/tests.cmake when tests are built. No test asserts on
# timing.

sap_add_gtest(test_stress
  test/stress/test_stress_magnitudes.cpp
  test/stress/test_stress_infinity.cpp
  test/stress/test_stress_ulp.cpp
  test/stress/test_stress_degenerate.cpp
  test/stress/test_stress_sequence.cpp
  test/stress/test_stress_skips.cpp
  test/stress/stress_scenes.cpp
  test/stress/stress_sequences.cpp
  test/stress/stress_support.cpp
  test/core/test_support.cpp
  test/core/test_main.cpp
)
target_include_directories(test_stress PRIVATE test/stress test/core)
target_link_libraries(test_stress ${PROJECT_NAME}_core_internal)

# The fuzzers' seed corpora and crash regressions (fuzz/corpus, fuzz/regressions), replayed
# through the checks the libFuzzer targets run (scripts/fuzz.sh builds the targets themselves).
sap_add_gtest(test_fuzz_replay
  test/stress/test_fuzz_replay.cpp
  test/stress/fuzz_replay.cpp
  fuzz/fuzz_checks.cpp
  fuzz/sequence_checks.cpp
  fuzz/settings_checks.cpp
  test/stress/stress_sequences.cpp
  test/core/test_main.cpp
)
target_include_directories(test_fuzz_replay PRIVATE test/stress fuzz)
target_link_libraries(test_fuzz_replay ${PROJECT_NAME}_core_internal)
target_compile_definitions(test_fuzz_replay PRIVATE
  SAP_FUZZ_DIR="${CMAKE_CURRENT_SOURCE_DIR}/fuzz")

# The same for the BoxArray, wire, ~sources and reconfigure targets, which need the ROS
# messages, the node's parameter readers and the header generated from cfg/BroadphaseNode.cfg
# (catkin build only).
if(TARGET ${PROJECT_NAME}_ros)
  sap_add_gtest(test_fuzz_replay_ros
    test/stress/test_fuzz_replay_ros.cpp
    test/stress/fuzz_replay.cpp
    fuzz/box_array_checks.cpp
    test/ros/message_read_back.cpp
    fuzz/wire_checks.cpp
    fuzz/sources_checks.cpp
    fuzz/reconfigure_checks.cpp
    fuzz/fuzz_checks.cpp
    test/stress/stress_sequences.cpp
    test/core/test_main.cpp
  )
  target_include_directories(test_fuzz_replay_ros PRIVATE test/stress fuzz test/ros)
  target_link_libraries(test_fuzz_replay_ros ${PROJECT_NAME}_ros ${PROJECT_NAME}_core_internal
    ${catkin_LIBRARIES})
  add_dependencies(test_fuzz_replay_ros ${PROJECT_NAME}_generate_messages_cpp
    ${PROJECT_NAME}_gencfg)
  target_compile_definitions(test_fuzz_replay_ros PRIVATE
    SAP_FUZZ_DIR="${CMAKE_CURRENT_SOURCE_DIR}/fuzz"
    SAP_ADAPTERS_MSGS_DIR="${CMAKE_CURRENT_SOURCE_DIR}/src/ros/adapters_msgs")
endif()
