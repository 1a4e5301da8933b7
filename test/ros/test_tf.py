#!/usr/bin/python3
"""tf2 without stalls, and the scenery placed with the latest transform.

late: a robot publishes in robot_late, a frame with no transform into `map` yet; the node's
~transform_timeout (60 s) is far above WAIT. The test's frames in robot_ok must be answered
while the late robot's frames wait for their transform, and once the test sends that
transform the late robot's box joins the world.

scenery: the scenery is latched in `platform`, stamped at 1 s (long before tf2's cache), while
`platform` moves: the node places it with the latest transform (as docs/NODE.md says), and
the pairs of a moving frame in `map` against it equal the oracle's.

Every wait is for a condition, bounded by WAIT so that a broken node fails instead of hanging.
"""
import random
import threading
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import TransformStamped
from sap_broadphase.msg import BoxArray, FrameStats

from ros_test_support import PairsByStamp, poll_until, sends_to, wait_until

PACKAGE = "sap_broadphase"
WAIT = 20.0  # seconds; a bound on waiting, never a speed check
PLATFORM_X = 5.0


def random_bounds(seed, count, extent=4.0):
    rng = random.Random(seed)
    bounds = []
    for _ in range(count):
        low = [rng.uniform(0.0, extent) for _ in range(3)]
        bounds += low + [v + rng.uniform(0.2, 1.0) for v in low]
    return bounds


def oracle(ids_a, bounds_a, ids_b=(), bounds_b=()):
    """Pairs among boxes a and between a and b (never b x b), as sorted (low, high) ids."""
    boxes_a = [bounds_a[6 * i:6 * i + 6] for i in range(len(ids_a))]
    boxes_b = [bounds_b[6 * i:6 * i + 6] for i in range(len(ids_b))]

    def overlap(x, y):
        return all(x[k] <= y[k + 3] and y[k] <= x[k + 3] for k in range(3))

    pairs = []
    for i, box in enumerate(boxes_a):
        for j in range(i + 1, len(boxes_a)):
            if overlap(box, boxes_a[j]):
                pairs.append(tuple(sorted((ids_a[i], ids_a[j]))))
        for j, other in enumerate(boxes_b):
            if overlap(box, other):
                pairs.append(tuple(sorted((ids_a[i], ids_b[j]))))
    return sorted(pairs)


def transform(parent, child, x, stamp):
    msg = TransformStamped()
    msg.header.frame_id = parent
    msg.header.stamp = stamp
    msg.child_frame_id = child
    msg.transform.translation.x = x
    msg.transform.rotation.w = 1.0
    return msg


class Node:
    """Topics of one node under /<namespace>."""

    def __init__(self, namespace):
        self.condition = threading.Condition()
        self.answers = PairsByStamp("/%s/pairs" % namespace, self.condition, queue_size=None)
        self.stats = []
        self.boxes = rospy.Publisher("/%s/boxes" % namespace, BoxArray, queue_size=10)
        self.static = rospy.Publisher("/%s/static_boxes" % namespace, BoxArray, queue_size=1,
                                      latch=True)
        self.stats_sub = rospy.Subscriber("/%s/stats" % namespace, FrameStats, self.on_stats)

    def on_stats(self, msg):
        with self.condition:
            self.stats.append(msg)
            self.condition.notify_all()

    def connected(self):
        return (self.boxes.get_num_connections() > 0 and self.static.get_num_connections() > 0
                and self.answers.subscriber.get_num_connections() > 0
                and self.stats_sub.get_num_connections() > 0)

    def wait_pairs(self, stamp):
        """The pairs of the frame stamped stamp, or None after WAIT."""
        return self.answers.wait_for(stamp, WAIT)


class TfTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_tf", anonymous=True)
        cls.broadcaster = tf2_ros.TransformBroadcaster()
        cls.static_broadcaster = tf2_ros.StaticTransformBroadcaster()

    def wait_until(self, ready, what):
        wait_until(ready, what, WAIT)

    def send_frame(self, node, ids, bounds, frame_id):
        msg = BoxArray()
        msg.header.frame_id = frame_id
        msg.header.stamp = rospy.Time.now()
        msg.ids = ids
        msg.bounds = bounds
        node.boxes.publish(msg)
        return msg.header.stamp

    def test_late_source_never_blocks_the_others(self):
        node = Node("late")
        self.wait_until(node.connected, "connection to the node in /late")
        # The late robot publishes from the start; its frames wait for robot_late's transform.
        # Once two of them have gone out (the node, connected, has them too), every frame of
        # the test in robot_ok must be answered meanwhile, without the late robot.
        self.wait_until(lambda: sends_to("/late/late_robot", "/late/boxes", "/late/sap_broadphase"),
                        "connection from the late robot to the node")
        late_frames = []
        watch = rospy.Subscriber("/late/boxes", BoxArray,
                                 lambda msg: late_frames.append(msg.header.frame_id))
        self.wait_until(lambda: late_frames.count("robot_late") >= 2, "frames of the late robot")
        watch.unregister()
        ids = list(range(40))
        for i in range(3):
            bounds = random_bounds(100 + i, len(ids))
            stamp = self.send_frame(node, ids, bounds, "robot_ok")
            pairs = node.wait_pairs(stamp)
            self.assertIsNotNone(pairs, "frame %d in robot_ok not answered while robot_late has "
                                 "no transform: the late source holds up the others" % i)
            self.assertEqual(pairs, oracle(ids, bounds))

        # Its transform arrives: the late robot's box (id 5000, the unit cube at the origin of
        # robot_late, moved to x = 1.5 in map) joins the world.
        self.static_broadcaster.sendTransform(
            transform("map", "robot_late", 1.5, rospy.Time.now()))
        ids = ids + [40]
        bounds = random_bounds(200, 40) + [1.8, 0.2, 0.2, 2.2, 0.8, 0.8]  # inside the late box
        late_box = [1.5, 0.0, 0.0, 2.5, 1.0, 1.0]
        expected = oracle(ids + [5000], bounds + late_box)
        self.assertTrue(any(5000 in pair for pair in expected), "no pair with the late box")
        pairs = None

        def joined():
            nonlocal pairs
            pairs = node.wait_pairs(self.send_frame(node, ids, bounds, "robot_ok"))
            return pairs == expected

        # The late robot's next frame (5 Hz) brings its box: polled, not assumed.
        poll_until(joined, WAIT, interval=0.2)
        self.assertEqual(pairs, expected, "the late robot never joined once its transform came")


    def test_non_finite_transform_refuses_the_source(self):
        """map -> r_inf translates by (inf, 0, 0), which tf2 takes: a box published in r_inf
        would span the whole x axis and pair with every box. Its frame is refused, counted and
        named; the frames in robot_ok are answered exactly, without it."""
        node = Node("inf")
        self.wait_until(node.connected, "connection to the node in /inf")
        ids = list(range(30))
        bounds = random_bounds(400, len(ids))
        stamp = self.send_frame(node, ids, bounds, "robot_ok")
        self.assertEqual(node.wait_pairs(stamp), oracle(ids, bounds))

        self.send_frame(node, [500], [0.0, 0.0, 0.0, 1.0, 1.0, 1.0], "r_inf")
        refused = lambda: any("r_inf" in s.last_refusal and "not finite" in s.last_refusal
                              for s in node.stats)
        with node.condition:
            found = node.condition.wait_for(refused, WAIT)
            last = node.stats[-1].last_refusal if node.stats else "(no stats)"
        self.assertTrue(found, "the frame in r_inf was not refused for its infinite transform "
                        "(last refusal: %r)" % last)
        with node.condition:
            refusal = next(s for s in node.stats if "r_inf" in s.last_refusal)
        # tf2 composes the looked-up transform from the infinite one: inf, or inf - inf = NaN.
        self.assertIn("is not finite (translation.x is ", refusal.last_refusal)
        self.assertGreaterEqual(refusal.frames_refused, 1)

        stamp = self.send_frame(node, ids, bounds, "robot_ok")
        pairs = node.wait_pairs(stamp)
        self.assertEqual(pairs, oracle(ids, bounds),
                         "the box in r_inf joined the world: %s"
                         % [p for p in (pairs or []) if 500 in p][:5])

    def test_old_scenery_placed_with_the_latest_transform(self):
        node = Node("scenery")
        self.wait_until(node.connected, "connection to the node in /scenery")
        # `platform` moves: its transform is sent with the current time, 10 times a second,
        # always at x = PLATFORM_X (a moving transform whose latest value is known).
        stop = threading.Event()

        def move_platform():
            while not stop.is_set() and not rospy.is_shutdown():
                self.broadcaster.sendTransform(
                    transform("map", "platform", PLATFORM_X, rospy.Time.now()))
                stop.wait(0.1)

        mover = threading.Thread(target=move_platform)
        mover.start()
        try:
            scenery = BoxArray()
            scenery.header.frame_id = "platform"
            scenery.header.stamp = rospy.Time(1, 0)  # long ago: no transform at that time
            scenery.ids = [100000 + i for i in range(40)]
            scenery.bounds = random_bounds(300, 40)
            node.static.publish(scenery)
            placed = [v + (PLATFORM_X if k % 3 == 0 else 0.0)
                      for k, v in enumerate(scenery.bounds)]

            ids = list(range(60))
            bounds = random_bounds(301, len(ids), extent=10.0)
            expected = oracle(ids, bounds, scenery.ids, placed)
            self.assertTrue(any(pair[1] >= 100000 for pair in expected), "no scenery pair")
            stats = None

            def placed_in_world():
                nonlocal stats
                stamp = self.send_frame(node, ids, bounds, "map")
                node.wait_pairs(stamp)
                with node.condition:
                    stats = next((s for s in node.stats if s.header.stamp == stamp), None)
                return stats is not None and stats.static_world_boxes == len(scenery.ids)

            # The scenery lands between two frames: polled, not assumed.
            poll_until(placed_in_world, WAIT, interval=0.2)
            self.assertIsNotNone(stats, "no stats for the frames in map")
            self.assertEqual(stats.static_world_boxes, len(scenery.ids),
                             "the scenery stamped long ago was never placed (skipped: %d)"
                             % stats.frames_skipped)
            # A frame sent once the scenery is in force: computed once, against it.
            stamp = self.send_frame(node, ids, bounds, "map")
            self.assertEqual(node.wait_pairs(stamp), expected)
        finally:
            stop.set()
            mover.join()


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "tf", TfTest)
