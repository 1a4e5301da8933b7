#!/usr/bin/python3
"""rosbag with the node: `rosbag record boxes pairs` captures frames and their pairs, and
`rosbag play` of the boxes alone makes the node answer with the same pairs and stamps, frame
by frame.

Every process this test starts (rosbag record, rosbag play) is stopped by its PID.
"""
import os
import random
import subprocess
import threading
import unittest

import rosbag
import rospy
import rostest
from sap_broadphase.msg import BoxArray, PairArray

from ros_test_support import artifact, poll_until, sends_to, stop, subscribed

PACKAGE = "sap_broadphase"
FRAMES = 10
WAIT = 60.0  # seconds; a bound on waiting, never a speed check


def random_frame(seed, count=300):
    rng = random.Random(seed)
    msg = BoxArray()
    msg.header.frame_id = "bag_frame"
    for _ in range(count):
        low = [rng.uniform(0.0, 10.0) for _ in range(3)]
        msg.bounds.extend(low + [v + rng.uniform(0.0, 1.2) for v in low])
    return msg


class RosbagTest(unittest.TestCase):
    def setUp(self):
        self.processes = []
        self.lock = threading.Lock()
        self.pairs = {}
        rospy.init_node("test_rosbag", anonymous=True)
        self.publisher = rospy.Publisher("boxes", BoxArray, queue_size=100)
        rospy.Subscriber("pairs", PairArray, self.on_pairs, queue_size=100)

    def tearDown(self):
        for process in reversed(self.processes):
            stop(process)

    def on_pairs(self, msg):
        with self.lock:
            self.pairs[msg.header.stamp] = list(msg.pairs)

    def wait_until(self, ready):
        return poll_until(ready, WAIT)

    def test_record_then_play_boxes(self):
        bag = artifact("rosbag_test.bag")
        if os.path.exists(bag):
            os.remove(bag)
        log = open(artifact("rosbag_record.log"), "w")
        record = subprocess.Popen(
            ["rosbag", "record", "--limit=%d" % FRAMES, "-O", bag, "boxes", "pairs",
             "__name:=bag_recorder"], stdout=log, stderr=log)
        self.processes.append(record)
        self.assertTrue(self.wait_until(lambda: subscribed(rospy.resolve_name("boxes"),
                                                           "/bag_recorder")
                                        and subscribed(rospy.resolve_name("pairs"),
                                                       "/bag_recorder")),
                        "rosbag record never subscribed")
        self.assertTrue(self.wait_until(lambda: self.publisher.get_num_connections() >= 2),
                        "the node and the recorder did not connect to boxes")
        self.assertTrue(self.wait_until(lambda: sends_to(
            rospy.resolve_name("sap_broadphase"), rospy.resolve_name("pairs"), "/bag_recorder")),
            "the node never connected to the recorder's pairs subscriber")

        stamps = []
        for i in range(FRAMES):
            msg = random_frame(i)
            msg.header.stamp = rospy.Time(1000 + i, 0)
            stamps.append(msg.header.stamp)
            self.publisher.publish(msg)
            self.assertTrue(self.wait_until(lambda: msg.header.stamp in self.pairs),
                            "no pairs for frame %d" % i)
        recorded = dict(self.pairs)
        record.wait(WAIT)  # --limit ends it after FRAMES messages on each topic
        self.assertEqual(record.returncode, 0)

        boxes_in_bag, pairs_in_bag = [], {}
        with rosbag.Bag(bag) as reader:
            for topic, msg, _ in reader.read_messages():
                if topic.endswith("boxes"):
                    boxes_in_bag.append(msg.header.stamp)
                else:
                    pairs_in_bag[msg.header.stamp] = list(msg.pairs)
        self.assertEqual(boxes_in_bag, stamps)
        self.assertEqual(pairs_in_bag, recorded)

        with self.lock:
            self.pairs.clear()
        # Played at the recorded pace, after the node has subscribed (--wait-for-subscribers).
        # A frame that arrives while the node is busy is coalesced with the next (the latest
        # pending frame wins), so not every stamp is answered on its own; but each answer is
        # the answer to the frame of its stamp, so it must equal the recorded pairs of that
        # stamp, and the last frame must be answered. (Stepping the player one message per 's'
        # on its standard input is not reliable under load: a step can let two messages out
        # and the next none.)
        log = open(artifact("rosbag_play.log"), "w")
        play = subprocess.Popen(["rosbag", "play", "-q", "--wait-for-subscribers", bag,
                                 "--topics", "boxes"], stdout=log, stderr=log)
        self.processes.append(play)
        self.assertTrue(self.wait_until(lambda: stamps[-1] in self.pairs),
                        "the last replayed frame (%s) did not come back as pairs; answered: %s"
                        % (stamps[-1], sorted(self.pairs)))
        self.assertEqual(play.wait(WAIT), 0)
        with self.lock:
            replayed = dict(self.pairs)
        for stamp, pairs in sorted(replayed.items()):
            self.assertIn(stamp, recorded, "an answer for a stamp that was never recorded")
            self.assertEqual(pairs, recorded[stamp],
                             "replayed frame %s: pairs differ from the recorded ones" % stamp)


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "rosbag", RosbagTest)
