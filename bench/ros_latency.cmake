# sap_ros_latency (issue 4, item 11): end-to-end latency through ROS (BoxArray -> node ->
# PairArray/FrameStats). Included from bench/bench.cmake after the ROS layer; built only when
# the ROS library target exists. Run it with scripts/bench_ros.sh.
if(TARGET ${PROJECT_NAME}_ros)
  add_executable(sap_ros_latency ${CMAKE_CURRENT_LIST_DIR}/ros_latency_main.cpp)
  target_link_libraries(sap_ros_latency ${PROJECT_NAME}_ros ${PROJECT_NAME}_core
    ${catkin_LIBRARIES})
  target_include_directories(sap_ros_latency SYSTEM PRIVATE ${catkin_INCLUDE_DIRS})
  add_dependencies(sap_ros_latency ${PROJECT_NAME}_generate_messages_cpp)
endif()
