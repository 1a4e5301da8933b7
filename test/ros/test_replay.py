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
import unittest

import rosbag
import rospy
import rostest
from std_msgs.msg import UInt32

from ros_test_support import PairsByStamp, artifact, sends_to, stop, wait_until

PACKAGE = "sap_broadphase"
ROBOTS = ["robot_a", "robot_b"]
FRAMES = 8  # per robot
# The static transforms of replay.test: each robot's frame is its x offset in `map`.
X_OFFSET = {"robot_a": 0.0, "robot_b": 0.5}
WAIT = 60.0  # seconds; a bound on waiting, never a speed check


def world_pairs(frames):
    """The brute-force pairs of a world made of these frames, moved into `map`."""
    boxes = []
    for msg in frames:
        dx = X_OFFSET[msg.header.frame_id]
        b = msg.bounds
        for k, box_id in enumerate(msg.ids):
            low = (b[6 * k] + dx, b[6 * k + 1], b[6 * k + 2])
            high = (b[6 * k + 3] + dx, b[6 * k + 4], b[6 * k + 5])
            boxes.append((box_id, low, high))
    pairs = []
    for p, (id_p, low_p, high_p) in enumerate(boxes):
        for id_q, low_q, high_q in boxes[p + 1:]:
            if all(low_p[a] <= high_q[a] and low_q[a] <= high_p[a] for a in range(3)):
                pairs.append((min(id_p, id_q), max(id_p, id_q)))
    return sorted(pairs)


def worlds_by_stamp(frames):
    """{stamp: [pairs]} of every world a node builds from these frames in this order: after
    each frame, the latest frame of each robot, stamped with the newest of their stamps."""
    latest, worlds = {}, {}
    for msg in frames:
        latest[msg.header.frame_id] = msg
        stamp = max(m.header.stamp for m in latest.values())
        worlds.setdefault(stamp, []).append(world_pairs(latest.values()))
    return worlds


class ReplayTest(unittest.TestCase):
    def setUp(self):
        self.processes = []
        rospy.init_node("test_replay", anonymous=True)
        self.live = PairsByStamp("/live/pairs")
        self.replay = PairsByStamp("/replay/pairs")
        self.steps = {robot: rospy.Publisher("/live/%s/step" % robot, UInt32, queue_size=100)
                      for robot in ROBOTS}

    def tearDown(self):
        for process in reversed(self.processes):
            stop(process)

    def test_two_robots_recorded_and_replayed_give_the_same_pairs(self):
        bag = artifact("replay_test.bag")
        if os.path.exists(bag):
            os.remove(bag)
        log = open(artifact("replay_record.log"), "w")
        # --limit ends the recorder once it has written every frame of both robots.
        record = subprocess.Popen(["rosbag", "record", "--limit=%d" % (FRAMES * len(ROBOTS)),
                                   "-O", bag, "/live/boxes",
                                   "__name:=replay_recorder"], stdout=log, stderr=log)
        self.processes.append(record)
        me = rospy.get_name()
        for robot in ROBOTS:
            for subscriber in ("/replay_recorder", "/live/sap_broadphase"):
                wait_until(lambda: sends_to("/live/" + robot, "/live/boxes", subscriber),
                           "connection from %s to %s" % (robot, subscriber), WAIT)
            wait_until(lambda: self.steps[robot].get_num_connections() > 0,
                       "subscriber of %s's steps" % robot, WAIT)
        for namespace in ("live", "replay"):
            wait_until(lambda: sends_to("/%s/sap_broadphase" % namespace,
                                        "/%s/pairs" % namespace, me),
                       "connection from the %s node's pairs" % namespace, WAIT)

        # Live: the robots take turns, each frame answered before the next goes out.
        stamps = []
        for i in range(FRAMES):
            for robot, stamp_base in zip(ROBOTS, (1000.0, 1000.5)):
                stamp = rospy.Time.from_sec(stamp_base + i)
                self.steps[robot].publish(UInt32(i))
                self.assertIsNotNone(self.live.wait_for(stamp, WAIT),
                                     "no live pairs for %s frame %d" % (robot, i))
                stamps.append(stamp)
        cross = [pair for pair in self.live.pairs[stamps[-1]] if pair[0] < 1000 <= pair[1]]
        self.assertGreater(len(cross), 0, "the robots' boxes should overlap, or nothing is tested")
        self.assertEqual(record.wait(WAIT), 0, "rosbag record did not end after every frame")
        with rosbag.Bag(bag) as reader:
            bag_frames = [msg for _, msg, _ in reader.read_messages()]
        in_bag = [msg.header.stamp for msg in bag_frames]
        self.assertEqual(sorted(in_bag), sorted(stamps), "the bag lacks frames")
        # The oracle agrees with the live node on every live world (frames in stamp order).
        live_worlds = worlds_by_stamp(sorted(bag_frames, key=lambda msg: msg.header.stamp))
        for stamp in stamps:
            self.assertEqual(self.live.pairs[stamp], live_worlds[stamp][-1],
                             "live frame %s: pairs differ from the brute-force oracle" % stamp)

        # Replay at the recorded pace. The bag holds the frames in the order the recorder
        # received them, which under load need not be the order they were published in (the
        # robots are two connections), and the node may take several replayed frames in one
        # computed frame (the latest frame of each source wins). So each answer must be the
        # world of some prefix of the bag's order with the answer's stamp as its newest, and
        # the last frame must be answered. (Stepping the player one message per 's' on its
        # standard input proved unreliable under load: a step could let two messages out and
        # the next none.)
        replay_worlds = worlds_by_stamp(bag_frames)
        log = open(artifact("replay_play.log"), "w")
        play = subprocess.Popen(["rosbag", "play", "-q", "--wait-for-subscribers", bag,
                                 "/live/boxes:=/replay/boxes"], stdout=log, stderr=log)
        self.processes.append(play)
        self.assertIsNotNone(self.replay.wait_for(max(in_bag), WAIT),
                             "the last replayed frame (%s) was not answered; the replay node "
                             "answered %s" % (max(in_bag), sorted(self.replay.pairs)))
        with self.replay.condition:
            answers = dict(self.replay.pairs)
        for stamp, pairs in sorted(answers.items()):
            self.assertIn(stamp, replay_worlds, "an answer stamped %s, which no frame has" % stamp)
            self.assertIn(pairs, replay_worlds[stamp], "replayed frame %s: pairs of no world the "
                          "bag's order builds (live pairs of that stamp: %s)"
                          % (stamp, "equal" if pairs == self.live.pairs.get(stamp) else "differ"))
        self.assertEqual(play.wait(WAIT), 0)


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "replay", ReplayTest)
