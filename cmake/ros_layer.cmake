# ROS layer: conversions, sources (merge, tf2), node, markers, scene_publisher.
include_directories(include ${catkin_INCLUDE_DIRS})

# The node's parts (src/ros/*.h) are private: only conversions.h is installed.
include_directories(src/ros)
add_library(${PROJECT_NAME}_ros
  src/ros/conversions.cpp
  src/ros/frame_outputs.cpp
  src/ros/frame_worker.cpp
  src/ros/markers.cpp
  src/ros/node.cpp
  src/ros/node_params.cpp
  src/ros/node_reconfigure.cpp
  src/ros/node_status.cpp
  src/ros/pairs_service.cpp
  src/ros/source_ingest.cpp
  src/ros/sources.cpp
)
target_link_libraries(${PROJECT_NAME}_ros ${PROJECT_NAME}_core ${catkin_LIBRARIES})
# node_reconfigure.cpp and node_params.cpp include the header generated from cfg/BroadphaseNode.cfg.
add_dependencies(${PROJECT_NAME}_ros ${PROJECT_NAME}_generate_messages_cpp ${PROJECT_NAME}_gencfg)

add_executable(${PROJECT_NAME}_node src/apps/node_main.cpp)
set_target_properties(${PROJECT_NAME}_node PROPERTIES OUTPUT_NAME node PREFIX "")
target_link_libraries(${PROJECT_NAME}_node ${PROJECT_NAME}_ros ${PROJECT_NAME}_core
  ${catkin_LIBRARIES})
add_dependencies(${PROJECT_NAME}_node ${PROJECT_NAME}_generate_messages_cpp)

add_executable(${PROJECT_NAME}_scene_publisher src/apps/scene_publisher_main.cpp)
set_target_properties(${PROJECT_NAME}_scene_publisher PROPERTIES OUTPUT_NAME scene_publisher
  PREFIX "")
target_link_libraries(${PROJECT_NAME}_scene_publisher ${PROJECT_NAME}_ros ${PROJECT_NAME}_core
  ${catkin_LIBRARIES})
add_dependencies(${PROJECT_NAME}_scene_publisher ${PROJECT_NAME}_generate_messages_cpp)

install(TARGETS ${PROJECT_NAME}_node ${PROJECT_NAME}_ros ${PROJECT_NAME}_scene_publisher
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(DIRECTORY config launch rviz DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})

# Nodelets: the node and scene_publisher classes loaded into a nodelet manager (one
# implementation, two wrappers), described to pluginlib by nodelet_plugins.xml.
target_sources(${PROJECT_NAME}_ros PRIVATE src/ros/scene_publisher.cpp)
find_package(nodelet REQUIRED)
find_package(pluginlib REQUIRED)
add_library(${PROJECT_NAME}_nodelets src/ros/nodelets.cpp)
target_include_directories(${PROJECT_NAME}_nodelets SYSTEM PRIVATE
  ${nodelet_INCLUDE_DIRS} ${pluginlib_INCLUDE_DIRS})
target_link_libraries(${PROJECT_NAME}_nodelets ${PROJECT_NAME}_ros ${PROJECT_NAME}_core
  ${nodelet_LIBRARIES} ${pluginlib_LIBRARIES} ${catkin_LIBRARIES})
add_dependencies(${PROJECT_NAME}_nodelets ${PROJECT_NAME}_generate_messages_cpp)
install(TARGETS ${PROJECT_NAME}_nodelets
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
install(FILES nodelet_plugins.xml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
