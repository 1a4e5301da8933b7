# rostests of the node; included by test/tests.cmake under CATKIN_ENABLE_TESTING.
# Each test launches its own roscore on a loopback port chosen by rostest; every <test> has a
# time-limit and no test asserts on wall-clock speed.
find_package(rostest REQUIRED)

# Topic round trips and the service against the oracle, refusals, a burst, markers.
add_rostest_gtest(test_node test/ros/node.test
  test/ros/test_node.cpp test/ros/node_client.cpp test/ros/test_frames.cpp)
target_include_directories(test_node PRIVATE test/ros)
target_link_libraries(test_node ${PROJECT_NAME}_ros ${PROJECT_NAME}_core_internal ${catkin_LIBRARIES})
add_dependencies(test_node ${PROJECT_NAME}_node ${PROJECT_NAME}_generate_messages_cpp)

# `pairs` keeps the rate of scene_publisher (10 Hz, 10^4 boxes), checked by rostest's hztest.
add_rostest(test/ros/hz.test DEPENDENCIES ${PROJECT_NAME}_node ${PROJECT_NAME}_scene_publisher)

# rviz in Xvfb with rviz/demo.rviz: the screenshot shows the colliding-box colour.
add_rostest(test/ros/rviz.test DEPENDENCIES ${PROJECT_NAME}_node ${PROJECT_NAME}_scene_publisher)

# rosbag record of boxes and pairs; rosbag play of the boxes gives the same pairs again.
add_rostest(test/ros/rosbag.test DEPENDENCIES ${PROJECT_NAME}_node)

# Unit tests of the ROS layer's pure functions (conversions, markers, sources): no roscore.
catkin_add_gtest(test_ros_units
  test/ros/test_conversions.cpp test/ros/test_frames.cpp test/ros/test_markers.cpp
  test/ros/test_sources_units.cpp test/ros/test_units_main.cpp)
target_include_directories(test_ros_units PRIVATE test/ros)
target_link_libraries(test_ros_units ${PROJECT_NAME}_ros ${PROJECT_NAME}_core_internal ${catkin_LIBRARIES})
add_dependencies(test_ros_units ${PROJECT_NAME}_generate_messages_cpp)

# ScenePublisherNodelet feeding BroadphaseNodelet in one manager: boxes pass in process, every
# answered frame equals the oracle's pairs.
add_rostest_gtest(test_nodelet test/ros/nodelet.test
  test/ros/test_nodelet.cpp test/ros/test_frames.cpp)
target_include_directories(test_nodelet PRIVATE test/ros)
target_link_libraries(test_nodelet ${PROJECT_NAME}_ros ${PROJECT_NAME}_core_internal ${catkin_LIBRARIES})
add_dependencies(test_nodelet ${PROJECT_NAME}_nodelets ${PROJECT_NAME}_generate_messages_cpp)

# Sources (several publishers and topics), tf2 into a fixed frame, static_boxes, pair_events.
add_rostest_gtest(test_sources test/ros/sources.test
  test/ros/test_sources.cpp test/ros/test_frames.cpp)
target_include_directories(test_sources PRIVATE test/ros)
target_link_libraries(test_sources ${PROJECT_NAME}_ros ${PROJECT_NAME}_core ${catkin_LIBRARIES})
add_dependencies(test_sources ${PROJECT_NAME}_node ${PROJECT_NAME}_generate_messages_cpp)

# dynamic_reconfigure of the node and of BroadphaseNodelet (python client): threads and skin
# changed at run time show in stats, pairs equal the oracle's, invalid values are refused.
add_rostest(test/ros/reconfigure.test DEPENDENCIES ${PROJECT_NAME}_node ${PROJECT_NAME}_nodelets)

# Input adapters without a roscore: embedded definitions against genmsg's MD5, the vision_msgs
# and jsk wire decoders, MarkerArray state (DELETE, DELETEALL, CUBE_LIST), validation, ~sources.
catkin_add_gtest(test_adapters_units test/ros/test_adapters_units.cpp test/ros/test_units_main.cpp)
target_include_directories(test_adapters_units PRIVATE src/ros ${SAP_ADAPTERS_GENERATED})
target_include_directories(test_adapters_units SYSTEM PRIVATE
  ${topic_tools_INCLUDE_DIRS} ${sensor_msgs_INCLUDE_DIRS})
target_compile_definitions(test_adapters_units PRIVATE
  SAP_TEST_ROS_DIR="${CMAKE_CURRENT_SOURCE_DIR}/test/ros")
target_link_libraries(test_adapters_units ${PROJECT_NAME}_ros ${catkin_LIBRARIES}
  ${topic_tools_LIBRARIES})
add_dependencies(test_adapters_units ${PROJECT_NAME}_generate_messages_cpp)

# ~sources of other types sent by publishers of exactly those types (genpy classes built from
# the embedded definitions): pairs equal the oracle's for rotated and axis-aligned boxes,
# MarkerArray DELETE, ~id_names, another definition refused by its MD5 sum.
add_rostest(test/ros/adapters.test DEPENDENCIES ${PROJECT_NAME}_node)

# The example system as installed, rviz off: both robots (MarkerArray and BoxArray, moving tf)
# pair with the map, id_names names robot_a's markers, the Python client example answers; every
# parameter of config/default.yaml is an argument of both launch files.
add_rostest(test/ros/example_robots.test DEPENDENCIES ${PROJECT_NAME}_node)
# roslaunch's own check of every launch file: arguments, included files, packages of nodes.
find_package(roslaunch REQUIRED)
roslaunch_add_file_check(launch)
