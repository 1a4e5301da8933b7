#!/usr/bin/python3
"""Publishes, ten times a second, a vision_msgs/BoundingBox3DArray of the right layout under
another MD5 sum (another version of the definition) on `shared_vision`: a publisher the node
must refuse by name without locking out the right publishers of the topic (hostile.test)."""
import rospy

from test_hostile import raw_class, serialized
from test_adapters import foreign_classes

TYPE = "vision_msgs/BoundingBox3DArray"

if __name__ == "__main__":
    rospy.init_node("wrong_md5_publisher")
    array = foreign_classes(TYPE)[TYPE](boxes=[])
    array.header.frame_id = "map"
    publisher = rospy.Publisher("shared_vision", raw_class(TYPE, "0" * 32), queue_size=1)
    rate = rospy.Rate(10)
    while not rospy.is_shutdown():
        publisher.publish(publisher.data_class(serialized(array)))
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break
