#!/usr/bin/python3
"""No message lost at connection: a publisher that waits for get_num_connections() > 0 and
publishes once (what one-shot tools and scripts do) reaches the node's world, in every trial,
for every source type.

Each trial starts a new publisher node (one_shot_publisher.py) on a topic of its own, where it
is the first and only publisher: the node subscribes and its publisher check asks the new
publisher what it publishes. A check counted as a subscriber would let the publisher send its
one message to the check instead of the subscription. The trial's frame is stamped with a time
of its own, newer than every earlier trial's, so the world's frame carrying it is told by its
stamp in `stats` (the newest stamp of the world's sources).

No timing is asserted: each wait is for a condition (the trial's stamp in `stats`), bounded by
WAIT only so that a lost message fails the trial instead of hanging the test.
"""
import os
import subprocess
import sys
import threading
import unittest

import rospy
import rostest
from sap_broadphase.msg import FrameStats

PACKAGE = "sap_broadphase"
WAIT = 20.0  # seconds; a bound on waiting, never a speed check
TRIALS = 20
TYPES = [("boxes", "sap_broadphase/BoxArray"), ("markers", "visualization_msgs/MarkerArray"),
         ("vision", "vision_msgs/BoundingBox3DArray"),
         ("detections", "vision_msgs/Detection3DArray"),
         ("jsk", "jsk_recognition_msgs/BoundingBoxArray")]
PUBLISHER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "one_shot_publisher.py")


class OneShotTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_one_shot", anonymous=True)
        cls.condition = threading.Condition()
        cls.stamps = set()
        cls.stats_sub = rospy.Subscriber("stats", FrameStats, cls.on_stats, queue_size=1000)

    @classmethod
    def on_stats(cls, msg):
        with cls.condition:
            cls.stamps.add(msg.header.stamp.to_sec())
            cls.condition.notify_all()

    def topic(self, short, trial):
        return "one_shot/%s_%d" % (short, trial)

    def test_sources_are_the_trials_topics(self):
        """one_shot_sources.yaml lists exactly the topics the trials publish on."""
        listed = [entry if isinstance(entry, str) else entry["topic"]
                  for entry in rospy.get_param("/sap_broadphase/sources")]
        expected = [self.topic(short, k) for short, _ in TYPES for k in range(TRIALS)]
        self.assertEqual(listed, expected)

    def trial(self, type_name, topic, stamp, box_id):
        """True once the frame the one-shot publisher sent is in the world."""
        publisher = subprocess.Popen(
            [sys.executable, PUBLISHER, type_name, topic, "%.1f" % stamp, str(box_id)],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        try:
            with self.condition:
                return self.condition.wait_for(lambda: stamp in self.stamps, WAIT)
        finally:
            publisher.stdin.close()
            publisher.wait(WAIT)

    def test_one_shot_publishes_reach_the_world(self):
        with self.condition:
            self.condition.wait_for(lambda: self.stats_sub.get_num_connections() > 0, WAIT)
        self.assertGreater(self.stats_sub.get_num_connections(), 0, "no connection to stats")
        lost = []
        for t, (short, type_name) in enumerate(TYPES):
            for k in range(TRIALS):
                stamp = 1000.0 + 100 * t + k  # newer than every earlier trial's
                if not self.trial(type_name, self.topic(short, k), stamp, 1000 * t + k):
                    lost.append("%s trial %d" % (type_name, k))
        self.assertEqual(lost, [], "%d of %d one-shot messages never reached the world"
                         % (len(lost), TRIALS * len(TYPES)))


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "one_shot", OneShotTest)
