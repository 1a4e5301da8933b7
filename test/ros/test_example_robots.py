#!/usr/bin/python3
"""The example system (launch/example_robots.launch, rviz and client off, rviz's topics
subscribed) runs as a user starts it: each robot, robot_a publishing a MarkerArray and robot_b a BoxArray in its own moving tf
frame, meets the map's pillar on its path and the pair shows in `pairs`; id_names names
robot_a's markers; `markers` keeps drawing colliding boxes while the robots meet the map's
scenery, the map's box of each such pair drawn too, no list marker without points, and
writes robot_a's names above its colliding boxes; the Python client example (examples/ros/pairs_client.py) answers with the
pairs of its own boxes and prints frames of the node. Also: every parameter of
config/default.yaml is an argument of both launch files.

No timing is asserted: every wait is for a condition, bounded by WAIT only so that a broken
system fails the test instead of hanging it.
"""
import importlib.util
import os
import re
import subprocess
import threading
import unittest

import rospkg
import rospy
import rostest
import yaml
from sap_broadphase.msg import IdNames, PairArray
from visualization_msgs.msg import Marker, MarkerArray

PACKAGE = "sap_broadphase"
WAIT = 120.0  # seconds; a bound on waiting (robot_b reaches its pillar after half a turn)
MAP_IDS = range(0, 6)
ROBOT_A_IDS = range(1000, 2000)
ROBOT_B_IDS = range(2000, 2004)
LIST_TYPES = (Marker.LINE_LIST, Marker.LINE_STRIP, Marker.TRIANGLE_LIST, Marker.CUBE_LIST,
              Marker.SPHERE_LIST, Marker.POINTS)


def rounded(values):
    return tuple(round(v, 6) for v in values)


def wireframes(points):
    """The boxes of a colliding LINE_LIST (24 points a box), as rounded bounds."""
    boxes = []
    for k in range(0, len(points) - 23, 24):
        corners = points[k:k + 24]
        boxes.append(rounded([min(p.x for p in corners), min(p.y for p in corners),
                              min(p.z for p in corners), max(p.x for p in corners),
                              max(p.y for p in corners), max(p.z for p in corners)]))
    return boxes


def map_boxes():
    """The map's boxes by id, as examples/ros/example_map.py publishes them (room of 14 m)."""
    path = os.path.join(rospkg.RosPack().get_path(PACKAGE), "examples", "ros", "example_map.py")
    spec = importlib.util.spec_from_file_location("example_map", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return {k: rounded(box) for k, box in enumerate(module.map_boxes(14.0))}


MAP_BOXES = map_boxes()


class ExampleRobotsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_example_robots", anonymous=True)
        cls.lock = threading.Condition()
        cls.pairs_seen = set()
        cls.names = {}
        rospy.Subscriber("pairs", PairArray, cls.on_pairs, queue_size=100)
        rospy.Subscriber("id_names", IdNames, cls.on_names, queue_size=10)
        # As rviz does: with `markers` subscribed the node draws every frame, robots meeting
        # the map's scenery included.
        cls.colliding_drawn = 0
        cls.names_drawn = set()  # texts of the `names` markers
        cls.empty_lists = []  # "ns/id" of list markers added without points (rviz: Error)
        cls.pairs_by_stamp = {}  # stamp -> pairs of that frame
        cls.drawn_by_stamp = {}  # stamp -> boxes of the `colliding` list, rounded bounds
        rospy.Subscriber("markers", MarkerArray, cls.on_markers, queue_size=10)

    @classmethod
    def on_pairs(cls, msg):
        with cls.lock:
            ids = msg.pairs
            pairs = [(ids[k], ids[k + 1]) for k in range(0, len(ids), 2)]
            cls.pairs_seen.update(pairs)
            cls.pairs_by_stamp[msg.header.stamp.to_nsec()] = pairs
            cls.lock.notify_all()

    @classmethod
    def on_markers(cls, msg):
        with cls.lock:
            if any(m.ns == "colliding" and m.points for m in msg.markers):
                cls.colliding_drawn += 1
            cls.empty_lists += ["%s/%d" % (m.ns, m.id) for m in msg.markers
                                if m.action == Marker.ADD and m.type in LIST_TYPES
                                and not m.points]
            if msg.markers:  # each marker has the frame's header (a MarkerArray has none)
                cls.drawn_by_stamp[msg.markers[0].header.stamp.to_nsec()] = {
                    wireframe for m in msg.markers if m.ns == "colliding"
                    for wireframe in wireframes(m.points)}
            cls.names_drawn.update(m.text for m in msg.markers if m.ns == "names")
            cls.lock.notify_all()

    @classmethod
    def on_names(cls, msg):
        with cls.lock:
            cls.names = dict(zip(msg.ids, msg.names))
            cls.lock.notify_all()

    def wait_for(self, condition):
        deadline = rospy.get_time() + WAIT
        with self.lock:
            while not rospy.is_shutdown() and not condition():
                left = deadline - rospy.get_time()
                if left <= 0:
                    return False
                self.lock.wait(left)
            return condition()

    def robot_meets_map(self, robot_ids):
        return lambda: any(a in MAP_IDS and b in robot_ids for a, b in self.pairs_seen)

    def test_robot_a_markers_meet_the_map(self):
        self.assertTrue(self.wait_for(self.robot_meets_map(ROBOT_A_IDS)),
                        "no pair of robot_a (MarkerArray, ids 1000..) with the map (ids 0..5); "
                        "pairs seen: %s" % sorted(self.pairs_seen)[:20])

    def test_robot_b_boxes_meet_the_map(self):
        self.assertTrue(self.wait_for(self.robot_meets_map(ROBOT_B_IDS)),
                        "no pair of robot_b (BoxArray + id_offset 2000) with the map; pairs "
                        "seen: %s" % sorted(self.pairs_seen)[:20])

    def test_a_robots_own_parts_never_pair(self):
        # Both robots have met the map: each has turned through every angle at which its
        # load cubes' boxes touch each other (every 45 degrees), frames seen all along.
        self.assertTrue(self.wait_for(self.robot_meets_map(ROBOT_A_IDS)))
        self.assertTrue(self.wait_for(self.robot_meets_map(ROBOT_B_IDS)))
        with self.lock:
            own = [(a, b) for a, b in self.pairs_seen
                   if any(a in ids and b in ids for ids in (ROBOT_A_IDS, ROBOT_B_IDS))]
        self.assertEqual(own, [], "pairs of a robot's own parts (their groups and masks in "
                                  "config/example_robots.yaml forbid them)")

    def test_markers_drawn_while_robots_meet_the_map(self):
        self.assertTrue(self.wait_for(self.robot_meets_map(ROBOT_A_IDS)))
        with self.lock:
            drawn = self.colliding_drawn
        # The node lives on, and draws colliding boxes again after the meeting.
        self.assertTrue(self.wait_for(lambda: self.colliding_drawn > drawn),
                        "no markers with colliding boxes after robot_a met the map")

    def test_id_names_name_robot_a_markers(self):
        expected = {1000: "robot_a/boxes: body/0", 1001: "robot_a/boxes: load/0[0]",
                    1002: "robot_a/boxes: load/0[1]", 1003: "robot_a/boxes: load/0[2]"}
        self.wait_for(lambda: len(self.names) >= len(expected))
        with self.lock:
            self.assertEqual(self.names, expected)

    def map_pair_drawn(self):
        """A frame with a robot-map pair whose markers arrived: (pair, map box drawn)."""
        for stamp in set(self.pairs_by_stamp) & set(self.drawn_by_stamp):
            for a, b in self.pairs_by_stamp[stamp]:
                if a in MAP_IDS and b not in MAP_IDS:
                    return (a, b), MAP_BOXES[a] in self.drawn_by_stamp[stamp]
        return None

    def test_markers_draw_both_sides_and_no_empty_list(self):
        # The scenery's box of a pair turns red as the robot's does; a frame without pairs
        # sends no empty list marker (rviz would show the display in Error).
        self.assertTrue(self.wait_for(lambda: self.map_pair_drawn() is not None),
                        "no frame whose pairs and markers both arrived with a map pair")
        with self.lock:
            pair, drawn = self.map_pair_drawn()
            self.assertTrue(drawn, "map box %d of pair %s not in the colliding markers"
                            % (pair[0], pair))
            self.assertEqual(self.empty_lists, [], "list markers added without points")

    def test_markers_name_robot_a_colliding_boxes(self):
        # robot_a's boxes are named (MarkerArray source) and collide with the map on its way;
        # robot_b's and the map's have no name on id_names, so they get no text.
        self.assertTrue(self.wait_for(lambda: any(text.startswith("robot_a/boxes: ")
                                                  for text in self.names_drawn)),
                        "no name of robot_a's boxes drawn; texts seen: %s"
                        % sorted(self.names_drawn))
        with self.lock:
            self.assertTrue(all(text.startswith("robot_a/boxes: ") for text in self.names_drawn),
                            sorted(self.names_drawn))

    def test_the_client_example_answers(self):
        environment = dict(os.environ, PYENV_VERSION="system")
        client = subprocess.run(
            ["rosrun", PACKAGE, "pairs_client.py", "_frames:=2", "__name:=client_under_test"],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=environment, timeout=WAIT,
            universal_newlines=True)
        self.assertEqual(client.returncode, 0, client.stdout)
        self.assertIn("compute_pairs: (10, 11), (11, 12)", client.stdout)
        self.assertEqual(len(re.findall(r"^pairs at ", client.stdout, re.MULTILINE)), 2,
                         client.stdout)

    def test_ros_args_lists_every_argument_as_optional(self):
        for launch in ("sap_broadphase.launch", "sap_broadphase_nodelet.launch", "demo.launch",
                       "demo_nodelet.launch", "example_robots.launch"):
            listing = subprocess.run(["roslaunch", PACKAGE, launch, "--ros-args"],
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     universal_newlines=True, check=False)
            self.assertEqual(listing.returncode, 0, listing.stdout)
            self.assertNotIn("Required Arguments", listing.stdout, launch)
            self.assertIn("Optional Arguments", listing.stdout, launch)

    def test_every_parameter_is_a_launch_argument(self):
        root = rospkg.RosPack().get_path(PACKAGE)
        with open(os.path.join(root, "config", "default.yaml")) as defaults:
            parameters = set(yaml.safe_load(defaults))
        for launch in ("launch/sap_broadphase.launch", "launch/sap_broadphase_nodelet.launch",
                       "launch/include/sap_broadphase_params.launch.xml"):
            with open(os.path.join(root, launch)) as text:
                content = text.read()
            arguments = set(re.findall(r'<arg name="([a-z_]+)" default="\(yaml\)"', content))
            arguments |= set(re.findall(r'<arg name="(params_file)" default="\(none\)"', content))
            self.assertEqual(parameters - arguments, set(),
                             "%s lacks arguments for these parameters" % launch)
            self.assertIn("params_file", arguments, launch)
        with open(os.path.join(root, "launch/include/sap_broadphase_params.launch.xml")) as text:
            content = text.read()
        set_by_argument = set(re.findall(r'<param if="[^"]*" name="([a-z_]+)" value="\$\(arg \1\)"',
                                         content))
        set_by_argument |= set(re.findall(r'<rosparam if="[^"]*" param="([a-z_]+)"', content))
        self.assertEqual(parameters - set_by_argument, set(),
                         "sap_broadphase_params.launch.xml sets no parameter from these arguments")


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "example_robots", ExampleRobotsTest)
