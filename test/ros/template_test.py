#!/usr/bin/python3
"""A rostest of the sap_broadphase node: publish a BoxArray, wait for its PairArray.

Waits for conditions, never for a fixed time: for the node to subscribe to `boxes` and to
connect to the test's `pairs` subscriber before publishing (a message published before the
connection is lost), then for the answer. WAIT bounds each wait so that a broken system
fails the test instead of hanging it.
"""
import threading
import time
import unittest

import rospy
import rostest
from sap_broadphase.msg import BoxArray, PairArray

WAIT = 30.0  # seconds


def wait_until(condition, what):
    """Polls condition until it holds; fails naming what was awaited after WAIT seconds."""
    deadline = time.monotonic() + WAIT
    while not condition():
        if time.monotonic() > deadline or rospy.is_shutdown():
            raise AssertionError("waited %.0f s for %s" % (WAIT, what))
        time.sleep(0.05)


class BroadphaseTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_broadphase", anonymous=True)

    def setUp(self):
        self.answers = []
        self.answered = threading.Event()
        self.pairs = rospy.Subscriber("pairs", PairArray, self.on_pairs, queue_size=10)
        self.boxes = rospy.Publisher("boxes", BoxArray, queue_size=10)
        wait_until(lambda: self.boxes.get_num_connections() > 0,
                   "the node to subscribe to %s" % self.boxes.resolved_name)
        wait_until(lambda: self.pairs.get_num_connections() > 0,
                   "the node's %s to connect" % self.pairs.resolved_name)

    def tearDown(self):
        self.pairs.unregister()
        self.boxes.unregister()

    def on_pairs(self, message):
        self.answers.append(message)
        self.answered.set()

    def test_overlapping_boxes_pair(self):
        header = rospy.Header(stamp=rospy.Time(1, 0), frame_id="map")
        # Boxes 7 and 8 overlap, 9 touches 8 (closed intervals: a pair), 10 is alone.
        self.boxes.publish(BoxArray(header=header, ids=[7, 8, 9, 10], bounds=[
            0.0, 0.0, 0.0, 1.0, 1.0, 1.0,
            0.5, 0.5, 0.5, 2.0, 2.0, 2.0,
            2.0, 0.0, 0.0, 3.0, 1.0, 1.0,
            5.0, 5.0, 5.0, 6.0, 6.0, 6.0]))
        self.assertTrue(self.answered.wait(WAIT), "no PairArray within %.0f s" % WAIT)
        answer = self.answers[0]
        self.assertEqual(answer.header.stamp, header.stamp, "the answer to another frame")
        self.assertEqual(list(answer.pairs), [7, 8, 8, 9])


if __name__ == "__main__":
    rostest.rosrun("sap_broadphase", "broadphase", BroadphaseTest)
