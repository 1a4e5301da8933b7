#!/usr/bin/python3
"""The example system (launch/example_robots.launch, rviz and client off, rviz's topics
subscribed) runs as a user starts it: each robot, robot_a publishing a MarkerArray and robot_b a BoxArray in its own moving tf
frame, meets the map's pillar on its path and the pair shows in `pairs`; id_names names
robot_a's markers; `markers` keeps drawing colliding boxes while the robots meet the map's
scenery and writes robot_a's names above its colliding boxes; the Python client example (examples/ros/pairs_client.py) answers with the
pairs of its own boxes and prints frames of the node. Also: every parameter of
config/default.yaml is an argument of both launch files.

No timing is asserted: every wait is for a condition, bounded by WAIT only so that a broken
system fails the test instead of hanging it.
"""
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
from visualization_msgs.msg import MarkerArray

PACKAGE = "sap_broadphase"
WAIT = 120.0  # seconds; a bound on waiting (robot_b reaches its pillar after half a turn)
MAP_IDS = range(0, 6)
ROBOT_A_IDS = range(1000, 2000)
ROBOT_B_IDS = range(2000, 2004)


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
        rospy.Subscriber("markers", MarkerArray, cls.on_markers, queue_size=10)

    @classmethod
    def on_pairs(cls, msg):
        with cls.lock:
            ids = msg.pairs
            cls.pairs_seen.update((ids[k], ids[k + 1]) for k in range(0, len(ids), 2))
            cls.lock.notify_all()

    @classmethod
    def on_markers(cls, msg):
        with cls.lock:
            if any(m.ns == "colliding" and m.points for m in msg.markers):
                cls.colliding_drawn += 1
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
