# ROS layer: conversions, node, markers, scene_publisher. Owned by the ROS-node work (issue 3).
include_directories(include ${catkin_INCLUDE_DIRS})

add_library(${PROJECT_NAME}_ros
  src/ros/conversions.cpp
  src/ros/markers.cpp
  src/ros/node.cpp
  src/ros/node_params.cpp
)
target_link_libraries(${PROJECT_NAME}_ros ${PROJECT_NAME}_core ${catkin_LIBRARIES})
add_dependencies(${PROJECT_NAME}_ros ${PROJECT_NAME}_generate_messages_cpp)

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
