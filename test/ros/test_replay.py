#!/usr/bin/python3
"""Two robots on one topic survive `rosbag record` and `rosbag play`.

Live, robot_a and robot_b (two processes, frames in robot_a and robot_b) publish on
/live/boxes in turns, each frame answered before the next goes out, while `rosbag record`
captures the topic. Played back into /replay/boxes, every frame comes from the one caller id of
the player: the node must still keep the two robots apart (by their frame ids) and answer the
replayed frames with the pairs the live node gave for the same stamps, cross-robot pairs
included.

Every wait is for a condition, bounded by WAIT only so that a broken node fails the test
instead of hanging it. Every process this test starts is stopped by its PID.
"""
import os
import subprocess
import threading
import time
import unittest
import xmlrpc.client

import rosbag
import rosgraph
import rospy
import rostest
from sap_broadphase.msg import PairArray
from std_msgs.msg import UInt32

PACKAGE = "sap_broadphase"
REPO = os.path.realpath(os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", ".."))
ARTIFACTS = os.path.join(REPO, "build", "artifacts")
ROBOTS = ["robot_a", "robot_b"]
FRAMES = 8  # per robot
WAIT = 60.0  # seconds; a bound on waiting, never a speed check


def stop(process, timeout=5.0):
    if process.poll() is None:
        process.terminate()
        try:
            process.wait(timeout)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


class Answers:
    """The pairs a node published, by stamp."""

    def __init__(self, topic):
        self.condition = threading.Condition()
        self.pairs = {}
        self.subscriber = rospy.Subscriber(topic, PairArray, self.on_pairs, queue_size=100)

    def on_pairs(self, msg):
        pairs = list(msg.pairs)
        with self.condition:
            self.pairs[msg.header.stamp] = sorted(zip(pairs[0::2], pairs[1::2]))
            self.condition.notify_all()

    def wait_for(self, stamp):
        with self.condition:
            return self.condition.wait_for(lambda: stamp in self.pairs, WAIT)


class ReplayTest(unittest.TestCase):
    def setUp(self):
        self.processes = []
        os.makedirs(ARTIFACTS, exist_ok=True)
        rospy.init_node("test_replay", anonymous=True)
        self.live = Answers("/live/pairs")
        self.replay = Answers("/replay/pairs")
        self.steps = {robot: rospy.Publisher("/live/%s/step" % robot, UInt32, queue_size=100)
                      for robot in ROBOTS}

    def tearDown(self):
        for process in reversed(self.processes):
            stop(process)

    def wait_until(self, ready, what):
        end = time.monotonic() + WAIT
        while not ready():
            if time.monotonic() > end or rospy.is_shutdown():
                self.fail("no %s within %.0f s" % (what, WAIT))
            time.sleep(0.05)

    def sends_to(self, node, topic, subscriber):
        """True once node has an outbound connection on topic to subscriber."""
        master = rosgraph.Master(rospy.get_name())
        try:
            info = xmlrpc.client.ServerProxy(master.lookupNode(node)).getBusInfo(
                rospy.get_name())[2]
        except (rosgraph.MasterError, OSError):
            return False
        return any(len(c) > 4 and c[2] == "o" and c[4] == topic and c[1] == subscriber
                   for c in info)

    def test_two_robots_recorded_and_replayed_give_the_same_pairs(self):
        bag = os.path.join(ARTIFACTS, "replay_test.bag")
        if os.path.exists(bag):
            os.remove(bag)
        log = open(os.path.join(ARTIFACTS, "replay_record.log"), "w")
        # --limit ends the recorder once it has written every frame of both robots.
        record = subprocess.Popen(["rosbag", "record", "--limit=%d" % (FRAMES * len(ROBOTS)),
                                   "-O", bag, "/live/boxes",
                                   "__name:=replay_recorder"], stdout=log, stderr=log)
        self.processes.append(record)
        me = rospy.get_name()
        for robot in ROBOTS:
            for subscriber in ("/replay_recorder", "/live/sap_broadphase"):
                self.wait_until(lambda: self.sends_to("/live/" + robot, "/live/boxes", subscriber),
                                "connection from %s to %s" % (robot, subscriber))
            self.wait_until(lambda: self.steps[robot].get_num_connections() > 0,
                            "subscriber of %s's steps" % robot)
        for namespace in ("live", "replay"):
            self.wait_until(lambda: self.sends_to("/%s/sap_broadphase" % namespace,
                                                  "/%s/pairs" % namespace, me),
                            "connection from the %s node's pairs" % namespace)

        # Live: the robots take turns, each frame answered before the next goes out.
        stamps = []
        for i in range(FRAMES):
            for robot, stamp_base in zip(ROBOTS, (1000.0, 1000.5)):
                stamp = rospy.Time.from_sec(stamp_base + i)
                self.steps[robot].publish(UInt32(i))
                self.assertTrue(self.live.wait_for(stamp), "no live pairs for %s frame %d"
                                % (robot, i))
                stamps.append(stamp)
        cross = [pair for pair in self.live.pairs[stamps[-1]] if pair[0] < 1000 <= pair[1]]
        self.assertGreater(len(cross), 0, "the robots' boxes should overlap, or nothing is tested")
        self.assertEqual(record.wait(WAIT), 0, "rosbag record did not end after every frame")
        with rosbag.Bag(bag) as reader:
            in_bag = [msg.header.stamp for _, msg, _ in reader.read_messages()]
        self.assertEqual(sorted(in_bag), sorted(stamps), "the bag lacks frames")

        # Replay at the recorded pace. The node may take several replayed frames in one
        # computed frame (latest per source wins), so not every stamp gets an answer of its
        # own; but a replayed world whose newest frame is stamped t is the live world at t,
        # so every answer must equal the live node's pairs for its stamp, and the last frame
        # (both robots' last frames) must be answered. (Stepping the player one message per
        # 's' on its standard input proved unreliable under load: a step could let two
        # messages out and the next none.)
        log = open(os.path.join(ARTIFACTS, "replay_play.log"), "w")
        play = subprocess.Popen(["rosbag", "play", "-q", "--wait-for-subscribers", bag,
                                 "/live/boxes:=/replay/boxes"], stdout=log, stderr=log)
        self.processes.append(play)
        self.assertTrue(self.replay.wait_for(max(in_bag)), "the last replayed frame (%s) was not "
                        "answered; the replay node answered %s"
                        % (max(in_bag), sorted(self.replay.pairs)))
        for stamp, pairs in sorted(self.replay.pairs.items()):
            self.assertEqual(pairs, self.live.pairs[stamp],
                             "replayed frame %s: pairs differ from the live node's" % stamp)
        self.assertEqual(play.wait(WAIT), 0)


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "replay", ReplayTest)
