# ROS layer: conversions, node, markers, scene_publisher. Owned by the ROS-node work (issue 3).
