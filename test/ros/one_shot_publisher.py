#!/usr/bin/python3
"""A one-shot publisher, as scripts and one-shot tools are written: it waits until its topic
has a subscriber (get_num_connections() > 0), publishes one message and stays until its
standard input closes (so that the message is not cut off by the end of the process).

    one_shot_publisher.py TYPE TOPIC STAMP_SECONDS ID

TYPE is a ~sources type; the message holds one unit box at x = 3 ID (id ID for a BoxArray),
stamped STAMP_SECONDS, in frame `map`. Used by test_one_shot.py, one process per trial: a new
node for the node's publisher check to ask.
"""
import sys
import time

import rospy
from geometry_msgs.msg import Point, Pose, Quaternion, Vector3
from sap_broadphase.msg import BoxArray
from visualization_msgs.msg import Marker, MarkerArray

from test_adapters import foreign_classes


def one_box_message(type_name, stamp, box_id):
    header = rospy.Header(frame_id="map", stamp=stamp)
    x = 3.0 * box_id  # its own place: no two trials' boxes touch
    pose = Pose(Point(x + 0.5, 0.5, 0.5), Quaternion(0.0, 0.0, 0.0, 1.0))
    size = Vector3(1.0, 1.0, 1.0)
    if type_name == "sap_broadphase/BoxArray":
        return BoxArray(header=header, ids=[box_id], bounds=[x, 0, 0, x + 1, 1, 1])
    if type_name == "visualization_msgs/MarkerArray":
        return MarkerArray(markers=[Marker(header=header, ns="one_shot", id=0, type=Marker.CUBE,
                                           action=Marker.ADD, pose=pose, scale=size)])
    classes = foreign_classes(type_name)
    if type_name == "vision_msgs/BoundingBox3DArray":
        box = classes["vision_msgs/BoundingBox3D"](center=pose, size=size)
        return classes[type_name](header=header, boxes=[box])
    if type_name == "vision_msgs/Detection3DArray":
        box = classes["vision_msgs/BoundingBox3D"](center=pose, size=size)
        detection = classes["vision_msgs/Detection3D"](header=header, bbox=box)
        return classes[type_name](header=header, detections=[detection])
    if type_name == "jsk_recognition_msgs/BoundingBoxArray":
        box = classes["jsk_recognition_msgs/BoundingBox"](header=header, pose=pose,
                                                          dimensions=size, label=1)
        return classes[type_name](header=header, boxes=[box])
    raise ValueError("no such source type: " + type_name)


def main():
    type_name, topic, stamp, box_id = sys.argv[1], sys.argv[2], float(sys.argv[3]), int(sys.argv[4])
    rospy.init_node("one_shot", anonymous=True, disable_signals=True)
    msg = one_box_message(type_name, rospy.Time.from_sec(stamp), box_id)
    pub = rospy.Publisher(topic, type(msg), queue_size=1)
    while pub.get_num_connections() == 0 and not rospy.is_shutdown():
        time.sleep(0.01)
    pub.publish(msg)
    print("published", flush=True)
    sys.stdin.read()  # until the test closes it


if __name__ == "__main__":
    main()
