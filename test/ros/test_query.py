#!/usr/bin/env python3
"""query_boxes against the node's world: the scenery and the latest frame of a source, query
boxes moved from their frame into ~fixed_frame, ids and filters, refusals that name the box,
answers while frames flow; the nodelet answers too, refuses a query with more hits than the
bound and a frame with more pairs than ~max_pairs, and goes on. Beside: a frame without a
frame_id refused with a reason under ~fixed_frame, and ~sources given as a YAML string on the
command line."""
import threading
import unittest

import rosgraph
import rospy
import rostest
from rosgraph_msgs.msg import Log
from sap_broadphase.msg import BoxArray, FrameStats
from sap_broadphase.srv import ComputePairs, QueryBoxes

from ros_test_support import poll_until, wait_until

WAIT = 60.0
SCENERY = {100: [0, 0, 0, 1, 1, 1], 101: [5, 5, 5, 6, 6, 6]}
ROBOT_BOX = [0, 0, 0, 1, 1, 1]  # id 1, in frame robot: x 10..11 in map
# The two frames the flowing source alternates between: id 2 at x 20..21 or id 3 at x 30..31.
FLOWING = [([2], [20, 0, 0, 21, 1, 1]), ([3], [30, 0, 0, 31, 1, 1])]


def box_array(frame_id, bounds, ids=(), groups=(), masks=()):
    msg = BoxArray()
    msg.header.frame_id = frame_id
    msg.bounds = [float(v) for v in bounds]
    msg.ids, msg.groups, msg.masks = list(ids), list(groups), list(masks)
    return msg


def nodelet_query_and_publisher():
    """The nodelet's query_boxes service and a publisher of its boxes, connected to it."""
    rospy.wait_for_service("nodelet/query_boxes", WAIT)
    query = rospy.ServiceProxy("nodelet/query_boxes", QueryBoxes)
    publisher = rospy.Publisher("nodelet/boxes", BoxArray, queue_size=1)
    wait_until(lambda: publisher.get_num_connections() > 0, "nodelet subscriber", WAIT)
    return query, publisher


def pairs_of(hits):
    return [(hits[i], hits[i + 1]) for i in range(0, len(hits), 2)]


class QueryBoxesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("query_client")
        cls.scenery = rospy.Publisher("static_boxes", BoxArray, queue_size=1, latch=True)
        bounds = [v for key in sorted(SCENERY) for v in SCENERY[key]]
        cls.scenery.publish(box_array("map", bounds, sorted(SCENERY)))
        cls.boxes = rospy.Publisher("boxes", BoxArray, queue_size=10)
        rospy.wait_for_service("query_boxes", WAIT)
        cls.query = rospy.ServiceProxy("query_boxes", QueryBoxes)
        # Early, so that the cmdline node's log reaches the test once it drops a source.
        cls.drop_outs = []
        cls.log_condition = threading.Condition()
        cls.log_subscriber = rospy.Subscriber("/rosout", Log, cls.on_log)

    @classmethod
    def on_log(cls, msg):
        if msg.name == "/cmdline/sap_broadphase" and "dropped out" in msg.msg:
            with cls.log_condition:
                cls.drop_outs.append(msg)
                cls.log_condition.notify_all()

    def wait_for_hits(self, request, expected, service=None, feed=None):
        """Asks until the answer is `expected` (the world fills as frames arrive); feed(), when
        given, publishes before each question (a frame may wait for tf and be skipped)."""
        service = service or self.query
        answer = None

        def answered():
            nonlocal answer
            if feed:
                feed()
            answer = service(request)
            self.assertTrue(answer.success, answer.message)
            return pairs_of(answer.hits) == expected

        if not poll_until(answered, WAIT):
            self.fail("hits %s, expected %s" % (pairs_of(answer.hits) if answer else None,
                                                expected))

    def publish_robot(self):
        self.assertTrue(poll_until(lambda: self.boxes.get_num_connections() > 0, WAIT),
                        "the node never subscribed to boxes")
        msg = box_array("robot", ROBOT_BOX, [1])
        msg.header.stamp = rospy.Time.now()
        self.boxes.publish(msg)

    def test_1_scenery_and_source_hits_in_their_frames(self):
        # Query 7 touches scenery 100 at a corner (closed intervals) and the robot's box in map;
        # query 8, in frame robot, overlaps the robot's box there; query 9 nothing.
        request = box_array("map", [1, 1, 1, 2, 2, 2, 10.5, 0.5, 0.5, 12, 0.6, 0.6], [7, 8])
        self.wait_for_hits(request, [(7, 100), (8, 1)], feed=self.publish_robot)
        in_robot = box_array("robot", [0.5, 0.5, 0.5, 0.6, 0.6, 0.6, -10, 0, 0, -9, 1, 1,
                                       50, 50, 50, 51, 51, 51])
        self.wait_for_hits(in_robot, [(0, 1), (1, 100)])  # indexes when ids are empty

    def test_2_filters(self):
        everything = [-100, -100, -100, 100, 100, 100]
        self.wait_for_hits(box_array("map", everything, [4]), [(4, 1), (4, 100), (4, 101)],
                           feed=self.publish_robot)
        # A query box whose mask admits no group pairs with nothing.
        self.wait_for_hits(box_array("map", everything, [4], [1], [0]), [])

    def test_3_bad_boxes_refused_with_their_reason(self):
        answer = self.query(box_array("map", [0, 0, 0, 1, 1, 1, 0, 2, 0, 1, 1, 1], [5, 6]))
        self.assertFalse(answer.success)
        self.assertIn("box 1 (id 6)", answer.message)
        self.assertIn("min_y", answer.message)
        self.assertEqual(list(answer.hits), [])
        answer = self.query(box_array("map", [0, 0, 0, 1, 1, float("nan")]))
        self.assertFalse(answer.success)
        self.assertIn("NaN", answer.message)
        answer = self.query(box_array("", [0, 0, 0, 1, 1, 1]))
        self.assertFalse(answer.success)
        self.assertIn("empty header.frame_id", answer.message)
        answer = self.query(box_array("nowhere", [0, 0, 0, 1, 1, 1]))
        self.assertFalse(answer.success)
        self.assertIn("no transform into 'map'", answer.message)
        answer = self.query(box_array("map", [0, 0, 0, 1, 1], [1]))
        self.assertFalse(answer.success)
        self.assertIn("bounds", answer.message)

    def test_4_queries_while_frames_flow(self):
        self.publish_robot()
        # Every frame of this source (frame map) holds exactly one of ids 2 and 3, beside the
        # robot's box (its own source, frame robot): a query over all of them sees one of 2
        # and 3 (none before the first frame), never both, whatever frame is in progress. Each
        # answer's header names the frame it was answered on: the flowing frame of that stamp
        # (the world's newest) holds the id the answer saw. Several callers at once.
        stop = threading.Event()
        flowing_id = {}  # stamp -> the id of ids 2 and 3 that frame holds
        flowing_lock = threading.Lock()

        def flow():
            k = 0
            while not stop.is_set() and not rospy.is_shutdown():
                ids, bounds = FLOWING[k % 2]
                msg = box_array("map", bounds, ids)
                msg.header.stamp = rospy.Time.now()
                with flowing_lock:
                    flowing_id[msg.header.stamp.to_nsec()] = ids[0]
                self.boxes.publish(msg)
                k += 1
                rospy.sleep(0.002)

        seen, problems = set(), []
        request = box_array("map", [0.5, 0.5, 0.5, 40, 0.6, 0.6], [9])

        def ask():
            query = rospy.ServiceProxy("query_boxes", QueryBoxes, persistent=True)
            deadline = rospy.get_time() + WAIT
            while len(seen) < 2 and rospy.get_time() < deadline and not problems:
                answer = query(request)
                hits = pairs_of(answer.hits)
                if not answer.success or hits not in [[(9, 1), (9, 100)],
                                                      [(9, 1), (9, 2), (9, 100)],
                                                      [(9, 1), (9, 3), (9, 100)]]:
                    problems.append("answer %s %r" % (hits, answer.message))
                    break
                flowing = [world for _, world in hits if world in (2, 3)]
                if flowing:
                    with flowing_lock:
                        expected = flowing_id.get(answer.header.stamp.to_nsec())
                    if answer.header.frame_id != "map" or expected != flowing[0]:
                        problems.append("hit %d answered on frame %r stamped %s, which holds %s"
                                        % (flowing[0], answer.header.frame_id,
                                           answer.header.stamp, expected))
                        break
                seen.update(flowing)
            query.close()

        flowing = threading.Thread(target=flow)
        flowing.start()
        callers = [threading.Thread(target=ask) for _ in range(4)]
        try:
            for caller in callers:
                caller.start()
            for caller in callers:
                caller.join()
            self.assertEqual(problems, [])
            self.assertTrue({2, 3} <= seen, "saw only %s" % sorted(seen))
        finally:
            stop.set()
            flowing.join()

    def test_5_nodelet_answers(self):
        query, publisher = nodelet_query_and_publisher()
        msg = box_array("world", [0, 0, 0, 1, 1, 1], [42])
        self.wait_for_hits(box_array("world", [1, 1, 1, 2, 2, 2], [3]), [(3, 42)], query,
                           feed=lambda: publisher.publish(msg))
        answer = query(box_array("world", [1, 0, 0, 0, 1, 1]))
        self.assertFalse(answer.success)
        self.assertIn("box 0", answer.message)


    def test_6_frame_without_frame_id_refused_with_reason(self):
        refusals = []
        condition = threading.Condition()

        def on_stats(msg):
            if msg.path == "refused" and "empty header.frame_id" in msg.last_refusal:
                with condition:
                    refusals.append(msg)
                    condition.notify_all()

        subscriber = rospy.Subscriber("stats", FrameStats, on_stats)
        try:
            deadline = rospy.get_time() + WAIT
            with condition:
                while not refusals and rospy.get_time() < deadline:
                    msg = box_array("", [0, 0, 0, 1, 1, 1], [77])
                    msg.header.stamp = rospy.Time.now()
                    self.boxes.publish(msg)
                    condition.wait(0.2)
            self.assertTrue(refusals, "no refusal of a frame without a frame_id")
            self.assertIn("cannot be placed in ~fixed_frame 'map'", refusals[0].last_refusal)
            self.assertGreater(refusals[0].frames_refused, 0)
        finally:
            subscriber.unregister()

    def test_7_sources_as_yaml_string_on_the_command_line(self):
        master = rosgraph.Master("/query_client")
        wanted = {"/cmdline/boxes", "/cmdline/obstacles"}
        subscribed = set()

        def all_subscribed():
            nonlocal subscribed
            _, subscribers, _ = master.getSystemState()
            subscribed = {topic for topic, nodes in subscribers
                          if "/cmdline/sap_broadphase" in nodes}
            return wanted <= subscribed

        self.assertTrue(poll_until(all_subscribed, WAIT, interval=0.1),
                        "/cmdline/sap_broadphase subscribes to %s, not %s"
                        % (sorted(subscribed), sorted(wanted)))


    def test_8_one_frame_drops_out_at_info_a_stream_at_warn(self):
        # The cmdline node has the default ~source_timeout (1 s): a frame published once (as
        # by `rostopic pub -1`) drops out as expected (INFO), a stream that stops is a WARN.
        logs, condition = self.drop_outs, self.log_condition
        # Latched: the node's publisher check connects to a publisher before its subscription
        # does, so a connection alone does not mean the subscription will see the frame; a
        # latched frame reaches every connection that comes, once.
        once = rospy.Publisher("/cmdline/boxes", BoxArray, queue_size=10, latch=True)
        try:
            while once.get_num_connections() == 0:
                rospy.sleep(0.05)
            once.publish(box_array("world", [0, 0, 0, 1, 1, 1], [1]))
            with condition:
                self.assertTrue(condition.wait_for(lambda: logs, WAIT), "no drop-out logged")
            self.assertEqual(logs[0].level, Log.INFO, logs[0].msg)
            self.assertIn("published one frame", logs[0].msg)
            for _ in range(3):
                once.publish(box_array("world", [0, 0, 0, 1, 1, 1], [1]))
                rospy.sleep(0.1)
            with condition:
                self.assertTrue(condition.wait_for(lambda: len(logs) > 1, WAIT),
                                "no drop-out of the stream logged")
            self.assertEqual(logs[1].level, Log.WARN, logs[1].msg)
            self.assertIn("silent for more than ~source_timeout", logs[1].msg)
        finally:
            once.unregister()

    def test_9_more_hits_than_the_bound_refused_and_the_node_goes_on(self):
        # kMaxQueryHits (2^24 = 16 777 216) from outside the node: the nodelet's world is 4100
        # boxes at one place (group 1, mask 2: they pair with nothing among themselves), and
        # 4100 query boxes there (group 2, mask 1) would have 16 810 000 hits.
        query, publisher = nodelet_query_and_publisher()
        count = 4100
        cube = [0, 0, 0, 1, 1, 1]
        world = box_array("world", cube * count, range(count), [1] * count, [2] * count)
        one = box_array("world", cube, [0], [2], [1])
        self.wait_for_hits(one, [(0, i) for i in range(count)], query,
                           feed=lambda: publisher.publish(world))
        many = box_array("world", cube * count, range(count), [2] * count, [1] * count)
        answer = query(many)
        self.assertFalse(answer.success)
        self.assertIn("more than 16777216 hits", answer.message)
        self.assertEqual(list(answer.hits), [])
        # The node still answers, from the same world.
        answer = query(one)
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(len(answer.hits), 2 * count)

    def test_9b_frame_past_max_pairs_refused_and_the_node_goes_on(self):
        # The nodelet runs with ~max_pairs 10: six boxes at one place (15 pairs) are refused,
        # by compute_pairs and as a frame of its source; five (10 pairs) pass, after.
        rospy.wait_for_service("nodelet/compute_pairs", WAIT)
        compute = rospy.ServiceProxy("nodelet/compute_pairs", ComputePairs)
        cube = [0, 0, 0, 1, 1, 1]
        six = box_array("world", cube * 6, range(6))
        five = box_array("world", cube * 5, range(5))
        answer = compute(six)
        self.assertFalse(answer.success)
        self.assertIn("more than 10 pairs (max_pairs)", answer.message)
        answer = compute(five)
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(len(answer.pairs.pairs), 2 * 10)
        stats = []
        condition = threading.Condition()

        def on_stats(msg):
            with condition:
                stats.append(msg)
                condition.notify_all()

        publisher = rospy.Publisher("nodelet/boxes", BoxArray, queue_size=1)
        subscriber = rospy.Subscriber("nodelet/stats", FrameStats, on_stats)
        try:
            while publisher.get_num_connections() == 0:
                rospy.sleep(0.05)
            for frame, seen in ((six, lambda m: m.path == "refused" and
                                 "more than 10 pairs (max_pairs)" in m.last_refusal),
                                (five, lambda m: m.path != "refused" and m.pairs == 10)):
                deadline = rospy.get_time() + WAIT
                with condition:
                    while not any(seen(m) for m in stats) and rospy.get_time() < deadline:
                        publisher.publish(frame)
                        condition.wait(0.2)
                    self.assertTrue(any(seen(m) for m in stats),
                                    [(m.path, m.pairs, m.last_refusal) for m in stats[-3:]])
        finally:
            subscriber.unregister()


if __name__ == "__main__":
    rostest.rosrun("sap_broadphase", "query", QueryBoxesTest)
