# sap_ros_latency: end-to-end latency through ROS (BoxArray -> node ->
# PairArray/FrameStats), the node in another process (tcp) and loaded into its own (nodelet).
# Included from bench/bench.cmake after the ROS layer; built only when the ROS library target
# exists. Run it with scripts/bench_ros.sh.
if(TARGET ${PROJECT_NAME}_ros)
  add_executable(sap_ros_latency ${CMAKE_CURRENT_LIST_DIR}/ros_latency_main.cpp)
  # nodelet::Loader for the in-process transport (found in cmake/ros_layer.cmake).
  target_link_libraries(sap_ros_latency ${PROJECT_NAME}_ros ${PROJECT_NAME}_core
    ${nodelet_LIBRARIES} ${catkin_LIBRARIES})
  target_include_directories(sap_ros_latency SYSTEM PRIVATE ${catkin_INCLUDE_DIRS}
    ${nodelet_INCLUDE_DIRS})
  # The nodelet transport loads the plugin at run time.
  add_dependencies(sap_ros_latency ${PROJECT_NAME}_generate_messages_cpp ${PROJECT_NAME}_nodelets)
endif()
