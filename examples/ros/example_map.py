#!/usr/bin/python3
"""The static map of the example system (launch/example_robots.launch): the walls of a room
and two pillars, published once, latched, on `static_boxes` (the node's scenery) in ~frame
(map), and as markers on `map_markers` for rviz.

Parameters: ~frame (map), ~size (the room's side, m).
"""
import rospy
from geometry_msgs.msg import Point, Pose, Quaternion, Vector3
from sap_broadphase.msg import BoxArray
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker, MarkerArray

WALL = 0.2  # thickness, m
HEIGHT = 1.0


def map_boxes(size):
    """(min x, min y, min z, max x, max y, max z) of the walls and pillars; ids 0.."""
    half = size / 2.0
    boxes = [(-half, -half, 0.0, half, -half + WALL, HEIGHT),   # south wall
             (-half, half - WALL, 0.0, half, half, HEIGHT),     # north wall
             (-half, -half, 0.0, -half + WALL, half, HEIGHT),   # west wall
             (half - WALL, -half, 0.0, half, half, HEIGHT)]     # east wall
    for x, y in ((4.0, 0.0), (-3.0, 0.0)):                      # a pillar on each path
        boxes.append((x - 0.3, y - 0.3, 0.0, x + 0.3, y + 0.3, 2.0))
    return boxes


def main():
    rospy.init_node("example_map")
    frame = rospy.get_param("~frame", "map")
    boxes = map_boxes(float(rospy.get_param("~size", 14.0)))
    header = rospy.Header(stamp=rospy.Time.now(), frame_id=frame)
    scenery = rospy.Publisher("static_boxes", BoxArray, queue_size=1, latch=True)
    scenery.publish(BoxArray(header=header, ids=list(range(len(boxes))),
                             bounds=[v for box in boxes for v in box]))
    markers = rospy.Publisher("map_markers", MarkerArray, queue_size=1, latch=True)
    markers.publish(MarkerArray(markers=[
        Marker(header=header, ns="map", id=k, type=Marker.CUBE, action=Marker.ADD,
               pose=Pose(Point((b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2),
                         Quaternion(0, 0, 0, 1)),
               scale=Vector3(b[3] - b[0], b[4] - b[1], b[5] - b[2]),
               color=ColorRGBA(0.6, 0.6, 0.6, 0.6))
        for k, b in enumerate(boxes)]))
    rospy.spin()


if __name__ == "__main__":
    main()
