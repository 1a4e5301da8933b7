#!/usr/bin/python3
"""dynamic_reconfigure of the node (namespace `node`) and of BroadphaseNodelet (namespace
`nodelet`), through dynamic_reconfigure's python client: every frame published after a change
is computed with the new threads and skin (as `stats` reports them) and its pairs equal the
brute-force oracle's; invalid values are refused, the settings in force stay and the node keeps
answering.

No timing is asserted: every wait is for a condition (a connection, the answer to a frame),
bounded by WAIT only so that a broken node fails the test instead of hanging it. Frames come
from fixed seeds (zlib.crc32 of a name, the same in every run, unlike Python's hash() of a
string). Each case runs once per namespace as a test of its own (no subTest: rosunit's report
drops a failed subTest's message).
"""
import os
import random
import subprocess
import threading
import time
import unittest
import zlib

import rospy
import rostest
from dynamic_reconfigure.client import Client
from sap_broadphase.msg import BoxArray, FrameStats, PairArray

PACKAGE = "sap_broadphase"
NAMESPACES = ["node", "nodelet"]
WAIT = 30.0  # seconds; a bound on waiting, never a speed check
BOXES = 400


def seed_of(*parts):
    """A seed that names what it seeds and is the same in every run."""
    return zlib.crc32("/".join(str(part) for part in parts).encode())


def random_frame(seed):
    """BOXES boxes of edges up to 2 in a cube of 20: a few hundred pairs."""
    rng = random.Random(seed)
    bounds = []
    for _ in range(BOXES):
        low = [rng.uniform(0.0, 20.0) for _ in range(3)]
        bounds += low + [v + rng.uniform(0.0, 2.0) for v in low]
    return bounds


def overlap(box_a, box_b):
    return all(box_a[k] <= box_b[k + 3] and box_b[k] <= box_a[k + 3] for k in range(3))


def oracle_pairs(bounds, scenery_ids=(), scenery_bounds=()):
    """Every pair of closed boxes overlapping on all three axes, as sorted (a, b) with a < b:
    among the moving boxes (ids 0..n-1) and between them and the scenery, never scenery x
    scenery."""
    boxes = [bounds[6 * i:6 * i + 6] for i in range(len(bounds) // 6)]
    scenery = [scenery_bounds[6 * i:6 * i + 6] for i in range(len(scenery_ids))]
    pairs = []
    for a, box_a in enumerate(boxes):
        for b in range(a + 1, len(boxes)):
            if overlap(box_a, boxes[b]):
                pairs.append((a, b))
        for scenery_id, box_b in zip(scenery_ids, scenery):
            if overlap(box_a, box_b):
                pairs.append((min(a, scenery_id), max(a, scenery_id)))
    return sorted(pairs)


class Endpoint:
    """Topics and reconfigure client of one broad phase under /<namespace>."""

    def __init__(self, namespace):
        self.namespace = namespace
        self.condition = threading.Condition()
        self.pairs = {}  # stamp -> PairArray
        self.stats = {}  # stamp -> FrameStats of a computed frame
        self.publisher = rospy.Publisher("/%s/boxes" % namespace, BoxArray, queue_size=10)
        self.static_publisher = rospy.Publisher("/%s/static_boxes" % namespace, BoxArray,
                                                queue_size=1, latch=True)
        self.scenery = BoxArray()
        self.pairs_sub = rospy.Subscriber("/%s/pairs" % namespace, PairArray, self.on_pairs)
        self.stats_sub = rospy.Subscriber("/%s/stats" % namespace, FrameStats, self.on_stats)
        self.client = Client("/%s/sap_broadphase" % namespace, timeout=WAIT)
        self.frames = 0

    def on_pairs(self, msg):
        with self.condition:
            self.pairs[msg.header.stamp] = msg
            self.condition.notify_all()

    def on_stats(self, msg):
        if msg.path == "refused":
            return
        with self.condition:
            self.stats[msg.header.stamp] = msg
            self.condition.notify_all()

    def wait_for(self, predicate, what):
        """Until predicate holds: woken by every answer, and polled for connection counts,
        which notify nobody."""
        deadline = time.monotonic() + WAIT
        with self.condition:
            while not self.condition.wait_for(predicate, 0.05):
                if time.monotonic() > deadline or rospy.is_shutdown():
                    raise AssertionError("%s: no %s within %.0f s" % (self.namespace, what, WAIT))

    def connect(self):
        self.wait_for(lambda: self.publisher.get_num_connections() > 0, "subscriber of boxes")
        self.wait_for(lambda: self.pairs_sub.get_num_connections() > 0, "publisher of pairs")
        self.wait_for(lambda: self.stats_sub.get_num_connections() > 0, "publisher of stats")
        self.wait_for(lambda: self.static_publisher.get_num_connections() > 0,
                      "subscriber of static_boxes")

    def declare_scenery(self, count):
        """Publishes count boxes with ids from 100000 as the (latched) scenery."""
        self.scenery.header.frame_id = "world"
        self.scenery.ids = [100000 + i for i in range(count)]
        self.scenery.bounds = random_frame(seed_of(self.namespace, "scenery"))[:6 * count]
        self.static_publisher.publish(self.scenery)

    def frame(self):
        """Publishes a new random frame; returns its pairs (as tuples), the oracle's and stats."""
        self.frames += 1
        msg = BoxArray()
        msg.header.frame_id = "world"
        msg.header.stamp = rospy.Time(1000 + self.frames, 0)  # the frame's key in the answers
        msg.bounds = random_frame(seed_of(self.namespace, "frame", self.frames))
        self.publisher.publish(msg)
        stamp = msg.header.stamp
        self.wait_for(lambda: stamp in self.pairs and stamp in self.stats,
                      "pairs and stats of frame %d" % self.frames)
        flat = list(self.pairs[stamp].pairs)
        pairs = [(flat[i], flat[i + 1]) for i in range(0, len(flat), 2)]
        expected = oracle_pairs(msg.bounds, self.scenery.ids, self.scenery.bounds)
        return pairs, expected, self.stats[stamp]


class ReconfigureTest(unittest.TestCase):
    """Each case below runs as test_<n>_<case>_<namespace>, in that order (unittest sorts the
    names): the first checks the launch values, the last declares a scenery that stays."""

    endpoints = {}

    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_reconfigure", anonymous=True)
        for namespace in NAMESPACES:
            cls.endpoints[namespace] = Endpoint(namespace)
            cls.endpoints[namespace].connect()

    def check_exact(self, endpoint, pairs, expected, stats):
        self.assertEqual(pairs, expected, "%s: pairs differ from the oracle" % endpoint.namespace)
        self.assertEqual(stats.pairs, len(expected))
        self.assertGreater(len(expected), 0, "the frames should have pairs to check")

    def start_with(self, parameter, value):
        """Runs a node with one private parameter; its exit status and output."""
        node = subprocess.run(["rosrun", PACKAGE, "node", "__name:=limits_%s" % parameter,
                               "_%s:=%s" % (parameter, value)],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=WAIT * 2)
        return node.returncode, node.stdout

    def test_0_out_of_range_parameters_stop_the_node_naming_them(self):
        """Parameters out of the limits table stop the node at start-up with a FATAL naming
        the parameter and exit status 1: never an abort, never a clamp (`_rate:=1e-10` ended
        with SIGABRT from ros::Duration; `_threads:=999` was put in force)."""
        for parameter, value in (("rate", "1e-10"), ("rate", "-1"), ("threads", "999"),
                                 ("boxes_queue_size", "0"), ("max_marker_boxes", "-1"),
                                 ("transform_timeout", "1e300"), ("skin", "1e300"),
                                 ("parallel_min_boxes", "-1"), ("third_axis_slabs", "65")):
            status, output = self.start_with(parameter, value)
            self.assertEqual(status, 1, "_%s:=%s: exit %s\n%s" % (parameter, value, status, output))
            self.assertIn("FATAL", output, "_%s:=%s\n%s" % (parameter, value, output))
            self.assertIn("%s must be" % parameter, output)

    def threads_and_skin_at_run_time(self, endpoint):
        start = endpoint.client.get_configuration(timeout=WAIT)
        self.assertEqual(start["threads"], 1)  # the launch file's value
        self.assertEqual(start["skin"], "auto")

        # A fixed skin makes every sweep run on all configured threads.
        config = endpoint.client.update_configuration({"threads": 2, "skin": "0.5"})
        self.assertEqual((config["threads"], config["skin"]), (2, "0.5"))
        pairs, expected, stats = endpoint.frame()
        self.check_exact(endpoint, pairs, expected, stats)
        self.assertEqual(stats.threads, 2)
        self.assertEqual(stats.skin_choice, "fixed")
        self.assertEqual(stats.skin, 0.5)

        config = endpoint.client.update_configuration({"threads": 1, "skin": "0"})
        self.assertEqual((config["threads"], config["skin"]), (1, "off"))
        pairs, expected, stats = endpoint.frame()
        self.check_exact(endpoint, pairs, expected, stats)
        self.assertEqual(stats.threads, 1)
        self.assertEqual(stats.skin_choice, "off")
        self.assertEqual(stats.skin, 0.0)

        config = endpoint.client.update_configuration({"threads": 3, "skin": "0.25"})
        pairs, expected, stats = endpoint.frame()
        self.check_exact(endpoint, pairs, expected, stats)
        self.assertEqual(stats.threads, 3)
        self.assertEqual((stats.skin_choice, stats.skin), ("fixed", 0.25))

        config = endpoint.client.update_configuration({"skin": "auto"})
        self.assertEqual((config["threads"], config["skin"]), (3, "auto"))
        pairs, expected, stats = endpoint.frame()
        self.check_exact(endpoint, pairs, expected, stats)
        self.assertNotIn(stats.skin_choice, ("off", "fixed"))
        self.assertEqual(rospy.get_param("/%s/sap_broadphase/skin" % endpoint.namespace), "auto")

    def invalid_values_refused(self, endpoint):
        before = endpoint.client.update_configuration({"threads": 2, "skin": "off"})
        for change in ({"skin": "-1"}, {"skin": "banana"}, {"skin": "nan"},
                       {"primary_axis": "y", "secondary_axis": "y"},
                       {"method": "quantum"}, {"threads": 2, "skin": "-0.5"},
                       {"threads": 999}, {"threads": 4 * os.cpu_count() + 1},
                       # Issue 29: these were clamped by dynamic_reconfigure's server (to the
                       # .cfg's range) and applied; the table refuses each.
                       {"parallel_min_boxes": -1}, {"threads": -5}, {"third_axis_slabs": 65},
                       {"axis_swap_threshold": -float("inf")},
                       {"axis_swap_threshold": float("nan")},
                       {"marker_line_width": float("inf")}, {"max_marker_boxes": -1},
                       {"skin": "1e300"}):
            config = endpoint.client.update_configuration(change)
            for name in change:
                # The client sees a refusal as the settings in force coming back.
                self.assertEqual(config[name], before[name],
                                 "%s: %s was not refused" % (endpoint.namespace, change))
            for name in before:
                if name in ("groups", "group"):
                    continue
                self.assertEqual(config[name], before[name],
                                 "%s: %s changed %s" % (endpoint.namespace, change, name))
        # Still up, still exact, still with the settings in force before.
        pairs, expected, stats = endpoint.frame()
        self.check_exact(endpoint, pairs, expected, stats)
        self.assertEqual(stats.skin_choice, "off")
        after = endpoint.client.get_configuration(timeout=WAIT)
        self.assertEqual((after["primary_axis"], after["secondary_axis"]), ("x", "y"))
        self.assertEqual((after["threads"], after["skin"]), (2, "off"))

    def scenery_kept_by_a_new_engine(self, endpoint):
        endpoint.declare_scenery(300)
        # The scenery takes effect between two frames: frames until one reports it. The node
        # also computes the last frame's world again when the scenery lands, under the same
        # stamp, and `pairs` and `stats` are two topics: the frame that reports the scenery may
        # pair stats of the second computation with pairs of the first. Only a frame sent
        # after the scenery is in force is checked.
        for _ in range(100):
            _, _, stats = endpoint.frame()
            if stats.static_world_boxes == 300:
                break
        self.assertEqual(stats.static_world_boxes, 300)
        pairs, expected, stats = endpoint.frame()
        self.assertEqual(stats.static_world_boxes, 300)
        self.check_exact(endpoint, pairs, expected, stats)
        with_scenery = [pair for pair in expected if pair[1] >= 100000]
        self.assertGreater(len(with_scenery), 0, "no pair with the scenery to check")

        endpoint.client.update_configuration({"threads": 1, "skin": "0.5"})
        pairs, expected, stats = endpoint.frame()
        self.assertEqual((stats.threads, stats.skin_choice), (1, "fixed"))
        self.assertEqual(stats.static_world_boxes, 300)
        self.check_exact(endpoint, pairs, expected, stats)


def add_cases():
    """One test per case and namespace, so that a failure names both and keeps its message."""
    cases = ["threads_and_skin_at_run_time", "invalid_values_refused",
             "scenery_kept_by_a_new_engine"]
    for number, case in enumerate(cases, start=1):
        for namespace in NAMESPACES:
            def test(self, case=case, namespace=namespace):
                getattr(self, case)(self.endpoints[namespace])
            setattr(ReconfigureTest, "test_%d_%s_%s" % (number, case, namespace), test)


add_cases()


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "reconfigure", ReconfigureTest)
