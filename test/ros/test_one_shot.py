#!/usr/bin/python3
"""No message lost at connection: a publisher that waits for get_num_connections() > 0 and
publishes once (what one-shot tools and scripts do) reaches the node's world, in every trial,
for every source type.

Each trial starts a new publisher node (one_shot_publisher.py) on a topic of its own, where it
is the first and only publisher: the node subscribes and its publisher check asks the new
publisher what it publishes. A check counted as a subscriber would let the publisher send its
one message to the check instead of the subscription. Each trial's box has a place of its own,
so `query_boxes` tells whether it is in the world; the trials of the five types run side by
side, one round after another.

No timing is asserted: each wait is for a condition (the trial's box in the world), bounded by
WAIT only so that a lost message fails the trial instead of hanging the test.
"""
import os
import selectors
import subprocess
import sys
import unittest

import rospy
import rostest
from sap_broadphase.srv import QueryBoxes, QueryBoxesRequest

from ros_test_support import poll_until

PACKAGE = "sap_broadphase"
WAIT = 20.0  # seconds; a bound on waiting, never a speed check
# A publisher process's start (rospy, the message classes, its node) on a loaded machine can
# take longer than the world's answer: its wait is bounded on its own, from its start to its
# "published", so that a slow start is never counted as a lost message.
START_WAIT = 180.0
TYPES = [("boxes", "sap_broadphase/BoxArray"), ("markers", "visualization_msgs/MarkerArray"),
         ("vision", "vision_msgs/BoundingBox3DArray"),
         ("detections", "vision_msgs/Detection3DArray"),
         ("jsk", "jsk_recognition_msgs/BoundingBoxArray")]
PUBLISHER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "one_shot_publisher.py")


class OneShotTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_one_shot", anonymous=True)
        # Trials per source type: one_shot.test's `trials` argument (20 in the test command,
        # 50 in scripts/one_shot_stress.sh), each on a topic of its own.
        cls.trials = int(rospy.get_param("~trials", 20))
        cls.listed = [entry if isinstance(entry, str) else entry["topic"]
                      for entry in rospy.get_param("/sap_broadphase/sources")]
        rospy.wait_for_service("query_boxes", WAIT)
        cls.query = rospy.ServiceProxy("query_boxes", QueryBoxes, persistent=True)

    def topic(self, short, trial):
        return "one_shot/%s_%d" % (short, trial)

    def test_sources_are_the_trials_topics(self):
        """The sources file lists the same number of topics of each type, the trials' topics,
        at least one per trial."""
        per_type = len(self.listed) // len(TYPES)
        expected = [self.topic(short, k) for short, _ in TYPES for k in range(per_type)]
        self.assertEqual(self.listed, expected)
        self.assertTrue(1 <= self.trials <= per_type,
                        "~trials %d: the sources file has topics for 1 to %d"
                        % (self.trials, per_type))

    def in_world(self, box_id):
        """True when the world holds a box overlapping trial box_id's place."""
        request = QueryBoxesRequest()
        request.boxes.header.frame_id = "map"
        x = 3.0 * box_id
        request.boxes.bounds = [x + 0.25, 0.25, 0.25, x + 0.75, 0.75, 0.75]
        answer = self.query(request)
        self.assertTrue(answer.success, answer.message)
        return len(answer.hits) > 0

    def wait_in_world(self, box_id):
        # Polled: each answer is exact for the frame it was answered on.
        return poll_until(lambda: self.in_world(box_id), WAIT, interval=0.02)

    @staticmethod
    def wait_published(publisher):
        """True once the publisher process says it published (its one line on stdout)."""
        with selectors.DefaultSelector() as selector:
            selector.register(publisher.stdout, selectors.EVENT_READ)
            if not selector.select(START_WAIT):
                return False
        return publisher.stdout.readline().strip() == "published"

    def test_one_shot_publishes_reach_the_world(self):
        lost = []
        for k in range(self.trials):
            publishers = {}
            for t, (short, type_name) in enumerate(TYPES):
                box_id = 1000 * t + k
                publishers[type_name, box_id] = subprocess.Popen(
                    [sys.executable, PUBLISHER, type_name, self.topic(short, k),
                     "%d" % (1000 + k), str(box_id)],
                    stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
            for (type_name, box_id), publisher in publishers.items():
                self.assertTrue(self.wait_published(publisher),
                                "%s trial %d: the publisher never published" % (type_name, k))
                reached = self.wait_in_world(box_id)
                publisher.stdin.close()
                publisher.wait(WAIT)
                if not reached:
                    lost.append("%s trial %d" % (type_name, k))
                rospy.loginfo("%s trial %d: %s", type_name, k, "reached" if reached else "LOST")
        self.assertEqual(lost, [], "%d of %d one-shot messages never reached the world"
                         % (len(lost), self.trials * len(TYPES)))


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "one_shot", OneShotTest)
