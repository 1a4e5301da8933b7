#!/usr/bin/env python3
"""A robot of the source tests: publishes one BoxArray on ~topic at ~rate Hz, stamped now.

It starts only once the node subscribes, so no frame is lost before the node listens.
Parameters: ~topic (boxes), ~frame_id (world), ~ids (list), ~bounds (6 per box), ~rate (20).
"""
import rospy
from sap_broadphase.msg import BoxArray


def main():
    rospy.init_node("box_source")
    msg = BoxArray()
    msg.header.frame_id = rospy.get_param("~frame_id", "world")
    msg.ids = [int(i) for i in rospy.get_param("~ids")]
    msg.bounds = [float(v) for v in rospy.get_param("~bounds")]
    publisher = rospy.Publisher(rospy.get_param("~topic", "boxes"), BoxArray, queue_size=10)
    rate = rospy.Rate(rospy.get_param("~rate", 20.0))
    while not rospy.is_shutdown() and publisher.get_num_connections() == 0:
        rospy.sleep(0.05)
    while not rospy.is_shutdown():
        msg.header.stamp = rospy.Time.now()
        publisher.publish(msg)
        rate.sleep()


if __name__ == "__main__":
    try:
        main()
    except rospy.ROSInterruptException:
        pass
