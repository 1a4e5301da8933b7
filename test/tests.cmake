# GoogleTest suites of the core and the CLI, registered with sap_add_gtest
# (cmake/sap_tests.cmake), so they run under catkin (scripts/test.sh) and under plain CMake
# without ROS (scripts/test_no_ros.sh) alike. No test asserts on timing; the whole suite stays
# under about 3 minutes in Release on 2 cores.

# Unit tests of the engine's parts: text format, validation, SuccTree, sort keys, radix sorts,
# candidate generation, the frame history, pair sorting, the third-axis slabs, and the
# configuration's front-end files against its table.
sap_add_gtest(test_core
  test/core/test_text_io.cpp
  test/core/test_config.cpp
  test/core/test_asserts.cpp
  test/core/test_box_set.cpp
  test/core/test_box_transform.cpp
  test/core/test_succ_tree.cpp
  test/core/test_radix_sort.cpp
  test/core/test_sweep.cpp
  test/core/test_small_frame.cpp
  test/core/test_frame_history.cpp
  test/core/test_pair_set.cpp
  test/core/test_slab_grid.cpp
  test/core/test_config_sources.cpp
  test/core/test_events.cpp
  test/core/test_support.cpp
  test/core/test_main.cpp
)
target_include_directories(test_core PRIVATE test/core)
target_link_libraries(test_core ${PROJECT_NAME}_core_internal)
# test_config_sources reads the .cfg, the YAML defaults, the launch files and docs/NODE.md.
target_compile_definitions(test_core PRIVATE SAP_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")

# The whole engine against the brute-force oracle: random boxes, edge cases, scenes, frame
# sequences, determinism across thread counts and axes, axis swapping.
sap_add_gtest(test_engine
  test/core/test_engine_random.cpp
  test/core/test_engine_edge_cases.cpp
  test/core/test_engine_scenes.cpp
  test/core/test_engine_reuse.cpp
  test/core/test_determinism.cpp
  test/core/test_axis_swap.cpp
  test/core/test_engine_skips.cpp
  test/core/test_engine_records.cpp
  test/core/test_engine_pair_bound.cpp
  test/core/test_support.cpp
  test/core/test_main.cpp
)
target_include_directories(test_engine PRIVATE test/core)
target_link_libraries(test_engine ${PROJECT_NAME}_core_internal)

# Skin reuse (SkinReuse) and its kept candidates (SkinList) against the oracle over moving frames.
sap_add_gtest(test_skin_list
  test/core/test_skin_list.cpp test/core/test_skin_reuse.cpp test/core/test_support.cpp
  test/core/test_main.cpp)
target_include_directories(test_skin_list PRIVATE test/core)
target_link_libraries(test_skin_list ${PROJECT_NAME}_core_internal)

# Box queries (Broadphase::query, FrameQuery) against the brute-force query oracle.
sap_add_gtest(test_query test/core/test_query.cpp test/core/test_support.cpp test/core/test_main.cpp)
target_include_directories(test_query PRIVATE test/core)
target_link_libraries(test_query ${PROJECT_NAME}_core_internal)

# The CLI contract, exercised through the real executables.
sap_add_gtest(test_cli test/core/test_cli.cpp test/core/test_main.cpp)
target_include_directories(test_cli PRIVATE test/core)
target_link_libraries(test_cli ${PROJECT_NAME}_core_internal)
add_dependencies(test_cli sap_pairs sap_scene)
target_compile_definitions(test_cli PRIVATE
  SAP_PAIRS_EXE="$<TARGET_FILE:sap_pairs>" SAP_SCENE_EXE="$<TARGET_FILE:sap_scene>")

# The numerical stress suite lives with its own work (test/stress).
if(EXISTS "${CMAKE_CURRENT_SOURCE_DIR}/test/stress/stress_tests.cmake")
  include(test/stress/stress_tests.cmake)
endif()

include(test/core/static_index_tests.cmake)

# The ROS node's tests live with the node; they need the ROS layer (catkin build only).
if(TARGET ${PROJECT_NAME}_ros AND EXISTS "${CMAKE_CURRENT_SOURCE_DIR}/test/ros/ros_tests.cmake")
  include(test/ros/ros_tests.cmake)
endif()

# The per-frame flow: the plan on its own, the work-unit runner, then every path and combination of skips,
# declared scenery, the automatic skin and large-world coordinates against the oracle.
sap_add_gtest(test_frame_flow
  test/core/test_frame_plan.cpp test/core/test_skin_audit.cpp
  test/core/test_work_units.cpp
  test/core/test_frame_flow.cpp
  test/core/test_support.cpp
  test/core/test_main.cpp
)
target_include_directories(test_frame_flow PRIVATE test/core)
target_link_libraries(test_frame_flow ${PROJECT_NAME}_core_internal)

# The distributed broad phase over MPI, run under mpirun (plain CMake build, MPI found).
include(test/distributed/distributed_tests.cmake)
