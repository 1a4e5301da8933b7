#!/usr/bin/python3
"""A robot of the example system (launch/example_robots.launch): drives round a circle in
~parent_frame, broadcasts its pose as the tf transform ~parent_frame -> ~frame and publishes
its boxes in ~frame at ~rate Hz, either as a visualization_msgs/MarkerArray (~kind: markers;
a CUBE body and a CUBE_LIST load) or as a sap_broadphase/BoxArray (~kind: boxes; body and
load as axis-aligned boxes of its own frame).

Parameters: ~kind (markers | boxes), ~frame, ~parent_frame (odom), ~centre ([x, y]), ~radius
(m), ~period (s per turn, negative: clockwise), ~rate (Hz). Topic: `boxes` (remap it).
"""
import math

import rospy
import tf2_ros
from geometry_msgs.msg import Point, Pose, Quaternion, TransformStamped, Vector3
from sap_broadphase.msg import BoxArray
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker, MarkerArray

BODY = (1.2, 0.8, 0.6)  # metres, centred on the robot's frame
# Cubes of LOAD_EDGE on its back, far enough apart that their axis-aligned boxes in `map` (a
# turned cube's is up to sqrt(2) x wider) do not touch.
LOAD = [(-0.45, 0.0, 0.5), (0.0, 0.0, 0.5), (0.45, 0.0, 0.5)]
LOAD_EDGE = 0.3


def yaw_quaternion(yaw):
    return Quaternion(0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))


def marker_array(header):
    """Body and load as markers; the first message clears whatever an earlier run left."""
    body = Marker(header=header, ns="body", id=0, type=Marker.CUBE, action=Marker.ADD,
                  pose=Pose(orientation=Quaternion(0, 0, 0, 1)), scale=Vector3(*BODY),
                  color=ColorRGBA(0.2, 0.6, 1.0, 0.8))
    load = Marker(header=header, ns="load", id=0, type=Marker.CUBE_LIST, action=Marker.ADD,
                  pose=Pose(orientation=Quaternion(0, 0, 0, 1)),
                  scale=Vector3(LOAD_EDGE, LOAD_EDGE, LOAD_EDGE),
                  points=[Point(*p) for p in LOAD], color=ColorRGBA(1.0, 0.8, 0.2, 0.8))
    return MarkerArray(markers=[body, load])


def box_array(header):
    """Body and load as axis-aligned boxes of the robot's frame, ids 0..3."""
    bounds = [-BODY[0] / 2, -BODY[1] / 2, -BODY[2] / 2, BODY[0] / 2, BODY[1] / 2, BODY[2] / 2]
    for x, y, z in LOAD:
        half = LOAD_EDGE / 2
        bounds += [x - half, y - half, z - half, x + half, y + half, z + half]
    return BoxArray(header=header, ids=list(range(len(bounds) // 6)), bounds=bounds)


def main():
    rospy.init_node("example_robot")
    kind = rospy.get_param("~kind", "markers")
    if kind not in ("markers", "boxes"):
        rospy.logfatal("~kind must be markers or boxes, not %r", kind)
        return
    frame = rospy.get_param("~frame", rospy.get_name().strip("/"))
    parent = rospy.get_param("~parent_frame", "odom")
    centre = rospy.get_param("~centre", [0.0, 0.0])
    radius = float(rospy.get_param("~radius", 4.0))
    period = float(rospy.get_param("~period", 20.0))
    rate = rospy.Rate(float(rospy.get_param("~rate", 10.0)))
    publisher = rospy.Publisher("boxes", MarkerArray if kind == "markers" else BoxArray,
                                queue_size=1)
    broadcaster = tf2_ros.TransformBroadcaster()
    start = rospy.Time.now()
    while not rospy.is_shutdown():
        now = rospy.Time.now()
        angle = 2.0 * math.pi * (now - start).to_sec() / period
        transform = TransformStamped()
        transform.header.stamp = now
        transform.header.frame_id = parent
        transform.child_frame_id = frame
        transform.transform.translation = Vector3(centre[0] + radius * math.cos(angle),
                                                  centre[1] + radius * math.sin(angle), 0.3)
        # Facing along the circle: the boxes turn with the robot (rotated boxes for the node).
        transform.transform.rotation = yaw_quaternion(
            angle + math.copysign(math.pi / 2.0, period))
        broadcaster.sendTransform(transform)
        header = rospy.Header(stamp=now, frame_id=frame)
        publisher.publish(marker_array(header) if kind == "markers" else box_array(header))
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
