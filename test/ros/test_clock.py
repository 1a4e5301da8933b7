#!/usr/bin/python3
"""The node under use_sim_time, driven by a /clock that this test publishes.

With ~rate 10 Hz the node computes its world once per 0.1 s of ROS time: while the clock stands
still it computes nothing, however long the wall clock runs, and each step of the clock by one
period computes exactly one frame. A source silent for ~source_timeout of ROS time drops out (`extra`, a second source,
keeps frames coming meanwhile), also after the clock jumped back.

Every wait is for a condition, bounded by WAIT so that a broken node fails instead of hanging.
The one wall-clock pause (HOLD) only gives a wrong node time to show itself: the node under
test computes nothing during it whatever the machine's speed.
"""
import random
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rosgraph_msgs.msg import Clock
from sap_broadphase.msg import BoxArray, FrameStats

from ros_test_support import wait_until

PACKAGE = "sap_broadphase"
WAIT = 30.0  # seconds; a bound on waiting, never a speed check
HOLD = 1.5  # wall seconds with the clock standing still: ten ~rate periods of wall time
PERIOD_NS = 100000000  # 1 / ~rate
START_NS = 100 * 10**9


class ClockTest(unittest.TestCase):
    def setUp(self):
        rospy.init_node("test_clock", anonymous=True)
        self.condition = threading.Condition()
        self.stats = []
        self.now_ns = START_NS
        self.clock = rospy.Publisher("/clock", Clock, queue_size=10, latch=True)
        self.boxes = rospy.Publisher("boxes", BoxArray, queue_size=10)
        self.stats_sub = rospy.Subscriber("stats", FrameStats, self.on_stats)
        self.extra = rospy.Publisher("extra", BoxArray, queue_size=10)

    def on_stats(self, msg):
        with self.condition:
            self.stats.append(msg)
            self.condition.notify_all()

    def publish_clock(self):
        self.clock.publish(Clock(clock=rospy.Time(0, 0) + rospy.Duration(0, self.now_ns)))

    def wait(self, predicate, what, timeout=WAIT):
        with self.condition:
            if not self.condition.wait_for(predicate, timeout):
                self.fail("%s within %.0f s" % (what, timeout))

    def wait_connected(self, what, ready):
        wait_until(ready, what, WAIT)

    def computed(self):
        with self.condition:
            return max((s.frames_computed for s in self.stats), default=0)

    def test_rate_and_time_outs_follow_the_clock(self):
        self.publish_clock()
        # The node and this test's own rospy listen to /clock.
        self.wait_connected("node on /clock", lambda: self.clock.get_num_connections() >= 2)
        self.wait_connected("node on boxes", lambda: self.boxes.get_num_connections() >= 1)
        self.wait_connected("node on extra", lambda: self.extra.get_num_connections() >= 1)
        self.wait_connected("node's stats", lambda: self.stats_sub.get_num_connections() >= 1)

        rng = random.Random(7)
        msg = BoxArray()
        msg.header.frame_id = "world"
        msg.header.stamp = rospy.Time(100, 0)
        for _ in range(60):
            low = [rng.uniform(0.0, 5.0) for _ in range(3)]
            msg.bounds += low + [v + rng.uniform(0.2, 1.5) for v in low]
        self.boxes.publish(msg)

        # Until the delivery is in: a period at a time, each answered or not within a bound.
        for _ in range(int(WAIT / 0.2)):
            self.now_ns += PERIOD_NS
            self.publish_clock()
            with self.condition:
                if self.condition.wait_for(lambda: self.stats, 0.2):
                    break
        self.assertTrue(self.stats, "no frame computed while /clock advanced")
        first = self.computed()

        # Each period of ROS time: one frame.
        for step in range(1, 6):
            self.now_ns += PERIOD_NS
            self.publish_clock()
            self.wait(lambda: self.computed() >= first + step,
                      "no frame for clock step %d" % step)
            self.assertEqual(self.computed(), first + step,
                             "more than one frame for one period of ROS time")

        # The clock stands still: no frame, however long the wall clock runs.
        time.sleep(HOLD)
        self.assertEqual(self.computed(), first + 5,
                         "frames computed while /clock stood still: ~rate ticks on the wall clock")

        # Beyond ~source_timeout of ROS time without a frame, the source on `boxes` drops out
        # while the one on `extra`, sent at every step, stays.
        self.now_ns += 6 * 10**9
        extra = BoxArray()
        extra.header.frame_id = "world"
        extra.ids = [1000]
        extra.bounds = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]
        # (`extra` may time out once too: its first frame can reach the node before the
        # clock's jump does, and is then received at the old time.)
        dropped = lambda: any(s.sources_timed_out >= 1 and s.sources == 1 for s in self.stats)
        for _ in range(int(WAIT / 0.2)):
            extra.header.stamp = rospy.Time(0, 0) + rospy.Duration(0, self.now_ns)
            self.extra.publish(extra)
            self.now_ns += PERIOD_NS
            self.publish_clock()
            with self.condition:
                if self.condition.wait_for(dropped, 0.2):
                    break
        with self.condition:
            last = self.stats[-1]
            self.assertTrue(dropped(), "the silent source did not time out in ROS time: the "
                            "last frame had %d sources, %d timed out, stamp %s"
                            % (last.sources, last.sources_timed_out, last.header.stamp))

        self.clock_jumping_back_restarts_the_time_outs(msg, extra)
        self.silent_sources_are_not_live()

    def clock_jumping_back_restarts_the_time_outs(self, boxes, extra):
        """The clock jumps back 60 s (a bag played again, a simulation restarted): a source
        silent from then on times out ~source_timeout of the new clock later, as it would have
        on the old one; received on the old clock, it would lie in the new one's future and
        stay in the world until the clock came back past it."""
        def step(publish_boxes, accept):
            with self.condition:
                mark = len(self.stats)
            for _ in range(int(WAIT / 0.2)):
                stamp = rospy.Time(0, 0) + rospy.Duration(0, self.now_ns)
                extra.header.stamp = stamp
                self.extra.publish(extra)
                if publish_boxes:
                    boxes.header.stamp = stamp
                    self.boxes.publish(boxes)
                self.now_ns += PERIOD_NS
                self.publish_clock()
                with self.condition:
                    if self.condition.wait_for(lambda: any(map(accept, self.stats[mark:])), 0.2):
                        return True
            return False

        self.assertTrue(step(True, lambda s: s.sources == 2), "`boxes` never joined again")
        with self.condition:
            timed_out = max(s.sources_timed_out for s in self.stats)
        self.now_ns -= 60 * 10**9
        self.publish_clock()
        self.assertTrue(
            step(False, lambda s: s.sources_timed_out > timed_out and s.sources == 1),
            "the source silent since the clock jumped back never timed out")

    def silent_sources_are_not_live(self):
        """Both sources fall silent: once ~source_timeout of ROS time has passed, /diagnostics
        counts no live source and warns that the node computes nothing (not "OK, computing"
        with the dead sources still counted live)."""
        reports = []

        def on_diagnostics(msg):
            with self.condition:
                reports.extend(s for s in msg.status if s.name.endswith("broadphase"))
                self.condition.notify_all()

        sub = rospy.Subscriber("/diagnostics", DiagnosticArray, on_diagnostics)
        self.wait_connected("node's /diagnostics", lambda: sub.get_num_connections() >= 1)
        value = lambda status, key: next((v.value for v in status.values if v.key == key), None)
        dead = lambda s: (s.level == DiagnosticStatus.WARN and value(s, "live sources") == "0"
                          and s.message.startswith("computing nothing"))
        for _ in range(int(2 * WAIT / 0.2)):
            self.now_ns += PERIOD_NS
            self.publish_clock()
            with self.condition:
                if self.condition.wait_for(lambda: any(map(dead, reports)), 0.2):
                    break
        with self.condition:
            seen = [(s.level, s.message, value(s, "live sources")) for s in reports[-5:]]
            self.assertTrue(any(map(dead, reports)),
                            "no WARN without live sources in %d reports; the last: %s"
                            % (len(reports), seen))
        sub.unregister()


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "clock", ClockTest)
