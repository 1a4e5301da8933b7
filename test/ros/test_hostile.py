#!/usr/bin/python3
"""Messages built byte by byte, as any process on the robot's network can send them: length
prefixes that claim far more than the bytes that follow (10^9 markers, 2^32 - 1 points of a
CUBE_LIST, 2^27 bounds of a BoxArray on a topic and in a compute_pairs request, a point cloud
of 2^32 - 1 bytes inside a vision_msgs detection), and a request with bytes left over. The
publishers send the real type name and MD5 sum, so the node takes the bytes for a message of
that type. Each must be refused, counted in `stats` and named, and the node must go on
answering: a process that died fails every later check.

No timing is asserted: every wait is for a condition, bounded by WAIT only so that a broken
node fails the test instead of hanging it.
"""
import struct
import threading
import unittest

import genpy
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from sap_broadphase.msg import BoxArray, FrameStats, PairArray
from sap_broadphase.srv import ComputePairs, ComputePairsRequest, ComputePairsResponse
from std_msgs.msg import Header
from visualization_msgs.msg import Marker, MarkerArray

from ros_test_support import poll_until
from test_adapters import foreign_classes

PACKAGE = "sap_broadphase"
WAIT = 60.0  # seconds; a bound on waiting, never a speed check


def raw_class(type_name, md5sum):
    """A message class whose instances serialize to the bytes they hold, under a real type."""

    class Raw(genpy.Message):
        _type = type_name
        _md5sum = md5sum
        _full_text = ""
        _has_header = False
        _slot_types = ["string"]
        __slots__ = ["data"]

        def __init__(self, data=b""):
            self.data = data

        def serialize(self, buff):
            buff.write(self.data)

        def deserialize(self, data):
            self.data = data
            return self

    return Raw


def serialized(message):
    from io import BytesIO
    buff = BytesIO()
    message.serialize(buff)
    return buff.getvalue()


def header_bytes(frame_id="map"):
    return serialized(Header(seq=0, stamp=rospy.Time(1, 0), frame_id=frame_id))


def marker_array_claiming_markers(count):
    return struct.pack("<I", count)


def box_marker(marker_type, ns, marker_id, x=0.0):
    """A unit CUBE or CUBE_LIST marker in `map`, centred at (x, 0, 0)."""
    marker = Marker(type=marker_type, action=Marker.ADD, ns=ns, id=marker_id)
    marker.header.frame_id = "map"
    marker.pose.orientation.w = 1.0
    marker.pose.position.x = x
    marker.scale.x = marker.scale.y = marker.scale.z = 1.0
    return marker


def cube_list_claiming_points(count):
    """One CUBE_LIST marker whose points prefix claims `count` points, none following (the
    marker's other fields do)."""
    marker = box_marker(Marker.CUBE_LIST, "lying", 1)
    whole = serialized(MarkerArray(markers=[marker]))
    # points is the first array after frame_locked; with no points, colors, text or mesh, the
    # marker ends with: points (4), colors (4), text (4), mesh_resource (4), mesh_use_embedded (1).
    points_at = len(whole) - 17
    assert whole[points_at:points_at + 4] == b"\0\0\0\0"
    return whole[:points_at] + struct.pack("<I", count) + whole[points_at + 4:]


def box_array_claiming_bounds(count):
    return header_bytes() + struct.pack("<I", 0) + struct.pack("<I", count)


def detection_claiming_cloud(count):
    """A Detection3DArray of one detection whose source_cloud data claims `count` bytes."""
    classes = foreign_classes("vision_msgs/Detection3DArray")
    detection = classes["vision_msgs/Detection3D"]()
    detection.header.frame_id = "map"
    detection.bbox.center.orientation.w = 1.0
    array = classes["vision_msgs/Detection3DArray"](detections=[detection])
    array.header.frame_id = "map"
    whole = serialized(array)
    # The cloud ends with data (4 bytes of length, none of data) and is_dense (1).
    data_at = len(whole) - 5
    assert whole[data_at:data_at + 4] == b"\0\0\0\0"
    return whole[:data_at] + struct.pack("<I", count) + b"\0"


class Hostile(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_hostile")
        cls.lock = threading.Condition()
        cls.stats = []
        cls.pairs = []
        rospy.Subscriber("stats", FrameStats, cls.on_stats, queue_size=1000)
        rospy.Subscriber("pairs", PairArray, cls.on_pairs, queue_size=1000)
        cls.publishers = {}

    @classmethod
    def on_stats(cls, msg):
        with cls.lock:
            cls.stats.append(msg)
            cls.lock.notify_all()

    @classmethod
    def on_pairs(cls, msg):
        with cls.lock:
            cls.pairs.append(msg)
            cls.lock.notify_all()

    def publisher(self, topic, type_name, md5sum):
        key = (topic, type_name, md5sum)
        if key not in self.publishers:
            self.publishers[key] = rospy.Publisher(topic, raw_class(type_name, md5sum),
                                                   queue_size=10)
        pub = self.publishers[key]
        poll_until(lambda: pub.get_num_connections() > 0, WAIT)
        self.assertGreater(pub.get_num_connections(), 0, "the node never subscribed to " + topic)
        return pub

    def wait_refusal(self, accept, republish):
        """Waits for a refusal in stats that accept() likes, republishing meanwhile."""
        return self.wait_stats(lambda msg: msg.path == "refused" and accept(msg.last_refusal),
                               republish, 0)

    def expect_alive(self):
        """The node still computes: a BoxArray frame on `boxes` is answered."""
        pub = rospy.Publisher("boxes", BoxArray, queue_size=10)
        poll_until(lambda: pub.get_num_connections() > 0, WAIT)
        stamp = rospy.Time(12345, len(self.pairs) + 1)
        msg = BoxArray(ids=[1, 2], bounds=[0, 0, 0, 1, 1, 1, 0.5, 0.5, 0.5, 2, 2, 2])
        msg.header.stamp = stamp
        msg.header.frame_id = "map"
        deadline = rospy.get_time() + WAIT
        while rospy.get_time() < deadline:
            pub.publish(msg)
            with self.lock:
                self.lock.wait(0.5)
                if any(p.header.stamp == stamp for p in self.pairs):
                    return
        self.fail("the node no longer answers frames")

    def refuse_on_topic(self, topic, type_name, md5sum, data, words):
        pub = self.publisher(topic, type_name, md5sum)
        refusal = self.wait_refusal(lambda text: all(w in text for w in words),
                                    lambda: pub.publish(raw_class(type_name, md5sum)(data)))
        self.assertIsNotNone(refusal, "no refusal naming %s on %s" % (words, topic))
        self.expect_alive()

    def test_marker_array_claiming_a_billion_markers(self):
        self.refuse_on_topic("robot_markers", MarkerArray._type, MarkerArray._md5sum,
                             marker_array_claiming_markers(10**9),
                             ["robot_markers", "markers: claims 1000000000 elements"])

    def test_cube_list_claiming_every_point(self):
        self.refuse_on_topic("robot_markers", MarkerArray._type, MarkerArray._md5sum,
                             cube_list_claiming_points(2**32 - 1),
                             ["robot_markers", "markers[0].points: claims 4294967295"])

    def test_box_array_on_a_topic_claiming_2_27_bounds(self):
        self.refuse_on_topic("boxes", BoxArray._type, BoxArray._md5sum,
                             box_array_claiming_bounds(2**27),
                             ["'boxes'", "bounds: claims 134217728 elements"])

    def test_scenery_claiming_2_27_bounds(self):
        pub = rospy.Publisher("static_boxes", raw_class(BoxArray._type, BoxArray._md5sum),
                              queue_size=1, latch=True)
        refusal = self.wait_refusal(
            lambda text: "static_boxes" in text and "bounds: claims" in text,
            lambda: pub.publish(pub.data_class(box_array_claiming_bounds(2**27))))
        self.assertIsNotNone(refusal)
        self.expect_alive()

    def test_detection_claiming_a_huge_point_cloud(self):
        classes = foreign_classes("vision_msgs/Detection3DArray")
        self.refuse_on_topic("detections", "vision_msgs/Detection3DArray",
                             classes["vision_msgs/Detection3DArray"]._md5sum,
                             detection_claiming_cloud(2**32 - 1),
                             ["detections", "source_cloud.data: claims 4294967295"])

    def test_marker_state_of_a_silent_publisher_is_dropped(self):
        """A MarkerArray publisher silent past its source's time-out (1 s in hostile.test) is
        forgotten: when it comes back with another cube, its old cube is not in the world."""
        self.expect_alive()  # the sources of the other tests stay (source_timeout 0)
        with self.lock:
            base = [s for s in self.stats if s.path != "refused"][-1]
        pub = self.publisher("leaving_markers", MarkerArray._type, MarkerArray._md5sum)
        cube = box_marker(Marker.CUBE, "leaving", 1)
        send = lambda markers: pub.publish(pub.data_class(serialized(MarkerArray(markers))))
        with self.lock:
            seen = len(self.stats)
        joined = self.wait_stats(
            lambda s: s.sources == base.sources + 1 and s.boxes == base.boxes + 1,
            lambda: send([cube]), seen)
        self.assertIsNotNone(joined, "the marker source never joined")
        boxes = rospy.Publisher("boxes", BoxArray, queue_size=10)
        frame = BoxArray(ids=[1, 2], bounds=[0, 0, 0, 1, 1, 1, 0.5, 0.5, 0.5, 2, 2, 2])
        frame.header.frame_id = "map"
        # Frames on `boxes` keep stats coming while the marker source falls silent.
        timed_out = self.wait_stats(lambda s: s.sources_timed_out > joined.sources_timed_out,
                                    lambda: boxes.publish(frame), seen)
        self.assertIsNotNone(timed_out, "the marker source never timed out")
        with self.lock:
            seen = len(self.stats)
        other = box_marker(Marker.CUBE, "leaving", 2, x=10.0)
        back = self.wait_stats(lambda s: s.sources == base.sources + 1 and s.path != "refused",
                               lambda: send([other]), seen)
        self.assertIsNotNone(back, "the marker source never joined again")
        self.assertEqual(back.boxes, base.boxes + 1, "the cube of the publisher's old set came back")

    def wait_stats(self, accept, republish, seen):
        """The first stats message from index `seen` on that accept() likes, or None."""
        deadline = rospy.get_time() + WAIT
        while rospy.get_time() < deadline:
            republish()
            with self.lock:
                self.lock.wait(0.5)
                for msg in self.stats[seen:]:
                    if accept(msg):
                        return msg
        return None

    def test_a_burst_of_marker_updates_is_applied_or_its_loss_counted(self):
        """500 MarkerArray messages of one new CUBE each, each sent as soon as the connection
        takes it: the node applies every one (the cubes touch in a row: 499 pairs), or stats
        count the messages its queue lost. Which of the two happens depends on the machine; a
        loss nobody is told of fails."""
        count = 500
        pub = rospy.Publisher("burst_markers", raw_class(MarkerArray._type, MarkerArray._md5sum),
                              queue_size=None)  # synchronous: rospy itself drops nothing
        poll_until(lambda: pub.get_num_connections() > 0, WAIT)
        with self.lock:
            seen = len(self.stats)
        for k in range(count):
            marker = box_marker(Marker.CUBE, "burst", k, x=1000.0 + k)
            pub.publish(pub.data_class(serialized(MarkerArray([marker]))))
        boxes = rospy.Publisher("boxes", BoxArray, queue_size=10)
        frame = BoxArray(ids=[1, 2], bounds=[0, 0, 0, 1, 1, 1, 0.5, 0.5, 0.5, 2, 2, 2])
        frame.header.frame_id = "map"
        def whole(pairs):
            ids = pairs.pairs
            return sum(1 for k in range(0, len(ids), 2) if ids[k] >= 100000) == count - 1

        def applied_or_counted(stats):
            with_pairs = any(whole(p) for p in self.pairs)  # under self.lock (wait_stats)
            return stats.messages_lost > 0 or with_pairs

        told = self.wait_stats(applied_or_counted, lambda: boxes.publish(frame), seen)
        self.assertIsNotNone(told, "markers of the burst lost without a trace")

    def test_a_publisher_of_another_md5_never_locks_the_topic(self):
        """wrong_md5_publisher publishes on shared_vision from the start: it is refused by name
        (stats and /diagnostics), and this test's publisher of the right definition, connecting
        after it, still feeds the source (its box pairs with those of `boxes`)."""
        self.expect_alive()
        # The publisher is refused once, when the node first asks it, possibly before this
        # test subscribed to stats: every later stats message still carries that refusal as
        # the last one (nothing else is refused meanwhile), so a frame on `boxes` brings it.
        boxes = rospy.Publisher("boxes", BoxArray, queue_size=10)
        frame = BoxArray(ids=[1, 2], bounds=[0, 0, 0, 1, 1, 1, 0.5, 0.5, 0.5, 2, 2, 2])
        frame.header.frame_id = "map"
        named_in = lambda text: ("/wrong_md5_publisher" in text and "shared_vision" in text and
                                 "with MD5 sum 00000000000000000000000000000000" in text)
        refusal = self.wait_stats(lambda msg: named_in(msg.last_refusal),
                                  lambda: boxes.publish(frame), 0)
        self.assertIsNotNone(refusal, "the publisher of another MD5 sum was not refused by name")
        named = threading.Event()

        def on_diagnostics(msg):
            for status in msg.status:
                for pair in status.values:
                    if pair.key == "refused publishers" and "/wrong_md5_publisher" in pair.value:
                        named.set()

        diagnostics = rospy.Subscriber("/diagnostics", DiagnosticArray, on_diagnostics)
        self.assertTrue(named.wait(WAIT), "/diagnostics does not name the refused publisher")
        diagnostics.unregister()
        classes = foreign_classes("vision_msgs/BoundingBox3DArray")
        array_class = classes["vision_msgs/BoundingBox3DArray"]
        box = classes["vision_msgs/BoundingBox3D"]()
        box.center.orientation.w = 1.0
        box.center.position.x = 0.5
        box.size.x = box.size.y = box.size.z = 1.0
        array = array_class(boxes=[box])
        array.header.frame_id = "map"
        pub = self.publisher("shared_vision", array_class._type, array_class._md5sum)
        with self.lock:
            seen = len(self.pairs)
        deadline = rospy.get_time() + WAIT
        while rospy.get_time() < deadline:
            pub.publish(pub.data_class(serialized(array)))
            with self.lock:
                self.lock.wait(0.5)
                if any(50000 <= i < 60000 for p in self.pairs[seen:] for i in p.pairs):
                    return
        self.fail("the right publisher of shared_vision never fed the source")

    def test_sources_of_every_type_with_a_fixed_frame(self):
        """The `framed` node (~fixed_frame map, tf map -> robot: +10 in x): a box of every
        source type, published in `robot` around (0.5, 0, 0), is moved into `map` and pairs
        with the BoxArray box [10, 11] x [0, 1]^2 published there."""
        def unit_box(box, pose_field, size_field):
            pose = getattr(box, pose_field)
            pose.position.x = 0.5
            pose.orientation.w = 1.0
            size = getattr(box, size_field)
            size.x = size.y = size.z = 1.0
            return box

        messages = {"markers_in": MarkerArray([box_marker(Marker.CUBE, "m", 0, x=0.5)])}
        for m in messages["markers_in"].markers:
            m.header.frame_id = "robot"
        vision = foreign_classes("vision_msgs/BoundingBox3DArray")
        array = vision["vision_msgs/BoundingBox3DArray"](
            boxes=[unit_box(vision["vision_msgs/BoundingBox3D"](), "center", "size")])
        messages["vision_in"] = array
        detections = foreign_classes("vision_msgs/Detection3DArray")
        detection = detections["vision_msgs/Detection3D"]()
        unit_box(detection.bbox, "center", "size")
        messages["detections_in"] = detections["vision_msgs/Detection3DArray"](
            detections=[detection])
        jsk = foreign_classes("jsk_recognition_msgs/BoundingBoxArray")
        messages["jsk_in"] = jsk["jsk_recognition_msgs/BoundingBoxArray"](
            boxes=[unit_box(jsk["jsk_recognition_msgs/BoundingBox"](), "pose", "dimensions")])
        messages["boxes_offset"] = BoxArray(bounds=[0, -0.5, -0.5, 1, 0.5, 0.5])
        for message in messages.values():
            if hasattr(message, "header"):
                message.header.frame_id = "robot"
        publishers = {topic: self.publisher("framed/" + topic, message._type, message._md5sum)
                      for topic, message in messages.items()}
        anchor = BoxArray(ids=[1], bounds=[10, 0, 0, 11, 1, 1])
        anchor.header.frame_id = "map"
        anchor_pub = self.publisher("framed/boxes", BoxArray._type, BoxArray._md5sum)
        expected = {(1, offset) for offset in (1000, 2000, 3000, 4000, 5000)}
        got = set()
        pairs_seen = []
        pairs_sub = rospy.Subscriber("framed/pairs", PairArray, pairs_seen.append)
        deadline = rospy.get_time() + WAIT
        while rospy.get_time() < deadline and not expected <= got:
            anchor_pub.publish(anchor_pub.data_class(serialized(anchor)))
            for topic, message in messages.items():
                publishers[topic].publish(publishers[topic].data_class(serialized(message)))
            rospy.sleep(0.5)
            for msg in list(pairs_seen):
                got.update(zip(msg.pairs[0::2], msg.pairs[1::2]))
        pairs_sub.unregister()
        self.assertLessEqual(expected, got, "missing pairs with the fixed frame's box")

    def call_raw(self, data):
        request_class = raw_class(ComputePairsRequest._type, ComputePairsRequest._md5sum)

        class Service:
            _type = ComputePairs._type
            _md5sum = ComputePairs._md5sum
            _request_class = request_class
            _response_class = ComputePairsResponse

        rospy.wait_for_service("compute_pairs", WAIT)
        return rospy.ServiceProxy("compute_pairs", Service)(request_class(data))

    def test_compute_pairs_request_claiming_2_27_bounds(self):
        answer = self.call_raw(box_array_claiming_bounds(2**27))
        self.assertFalse(answer.success)
        self.assertIn("bounds: claims 134217728 elements", answer.message)

    def test_compute_pairs_request_with_bytes_left_over(self):
        valid = serialized(ComputePairsRequest(boxes=BoxArray(bounds=[0, 0, 0, 1, 1, 1])))
        self.assertTrue(self.call_raw(valid).success)
        answer = self.call_raw(valid + b"\x07")
        self.assertFalse(answer.success)
        self.assertIn("1 bytes left after the last field", answer.message)


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "hostile", Hostile)
