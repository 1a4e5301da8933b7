# StaticIndex (the index of declared and resting boxes) against brute force over query x
# index pairs: random and adversarial boxes, filters, remove(), empty sides, thread counts
# 1/2/3, and a 10^5-static x 10^3-moving uniform scene.
sap_add_gtest(test_static_index
  test/core/test_static_index.cpp
  test/core/test_main.cpp
)
target_link_libraries(test_static_index ${PROJECT_NAME}_core_internal)
