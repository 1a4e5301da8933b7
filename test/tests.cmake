# Core tests (GoogleTest via catkin) and CLI tests.
catkin_add_gtest(test_core
  test/core/test_succ_tree.cpp
  test/core/test_radix_sort.cpp
  test/core/test_box_set.cpp
  test/core/test_sweep_vs_oracle.cpp
  test/core/test_text_io.cpp
)
target_link_libraries(test_core ${PROJECT_NAME}_core)

# The CLI contract, exercised through the real executables.
catkin_add_gtest(test_cli test/core/test_cli.cpp)
target_link_libraries(test_cli ${PROJECT_NAME}_core)
add_dependencies(test_cli sap_pairs sap_scene)
target_compile_definitions(test_cli PRIVATE
  SAP_PAIRS_EXE="$<TARGET_FILE:sap_pairs>" SAP_SCENE_EXE="$<TARGET_FILE:sap_scene>")
