#!/usr/bin/env python3
"""A robot of the replay test: publishes frame i of a fixed sequence on `boxes` each time a
number i arrives on ~step, so the test decides when each robot's frame goes out.

Frame i holds ~count boxes (ids from ~id_base) drawn from random.Random of ~seed and i, in
frame ~frame_id, stamped ~stamp_base + i seconds: every frame of every robot has a stamp of
its own, and a frame's pairs are found by the stamp.
"""
import random

import rospy
from sap_broadphase.msg import BoxArray
from std_msgs.msg import UInt32


def frame(seed, index, count, id_base):
    rng = random.Random(seed * 1000003 + index)
    bounds = []
    for _ in range(count):
        low = [rng.uniform(0.0, 6.0) for _ in range(3)]
        bounds += low + [v + rng.uniform(0.2, 1.2) for v in low]
    return bounds, [id_base + k for k in range(count)]


def main():
    rospy.init_node("robot_frames")
    frame_id = rospy.get_param("~frame_id")
    seed = int(rospy.get_param("~seed"))
    count = int(rospy.get_param("~count", 60))
    id_base = int(rospy.get_param("~id_base"))
    stamp_base = float(rospy.get_param("~stamp_base"))
    publisher = rospy.Publisher("boxes", BoxArray, queue_size=100)

    def on_step(msg):
        out = BoxArray()
        out.header.frame_id = frame_id
        out.header.stamp = rospy.Time.from_sec(stamp_base + msg.data)
        out.bounds, out.ids = frame(seed, msg.data, count, id_base)
        publisher.publish(out)

    rospy.Subscriber("~step", UInt32, on_step, queue_size=100)
    rospy.spin()


if __name__ == "__main__":
    main()
