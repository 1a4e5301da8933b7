#!/usr/bin/python3
"""~sources of the types robots publish, sent by publishers of exactly those types:
visualization_msgs/MarkerArray (CUBE and CUBE_LIST, then DELETE), and vision_msgs/
BoundingBox3DArray, vision_msgs/Detection3DArray and jsk_recognition_msgs/BoundingBoxArray,
whose classes are built at run time from the node's embedded ROS 1 definitions
(src/ros/adapters_msgs) with genpy.dynamic, as rosbag does: the type name and MD5 sum on the
wire are the real ones. The node's pairs equal the brute-force oracle's over the exact
axis-aligned boxes of the rotated and axis-aligned boxes; ~id_names names every id; a message
of another definition (another MD5 sum) is refused with a message saying so.

No timing is asserted: every wait is for a condition (an answer equal to the oracle's, a
refusal), bounded by WAIT only so that a broken node fails the test instead of hanging it.
"""
import math
import os
import random
import threading
import unittest

import genpy.dynamic
import rospkg
import rospy
import rostest
from geometry_msgs.msg import Point, Pose, Quaternion, Vector3
from sap_broadphase.msg import FrameStats, IdNames, PairArray
from visualization_msgs.msg import Marker, MarkerArray

PACKAGE = "sap_broadphase"
WAIT = 60.0  # seconds; a bound on waiting, never a speed check
SEED = 20261124
BOXES_PER_SOURCE = 30
FRAME = "map"
# id_offset, group and mask of each source, as adapters.test gives them to the node.
OFFSETS = {"robot_markers": 1000, "vision_boxes": 2000, "detections": 3000, "jsk_boxes": 4000}
JSK_GROUP, JSK_MASK = 0x2, 0xFFFFFFFD  # jsk boxes never pair among themselves
DEFAULT_GROUP, DEFAULT_MASK = 0x1, 0xFFFFFFFF


def foreign_classes(type_name):
    """The message classes of type_name from the node's embedded definition."""
    path = os.path.join(rospkg.RosPack().get_path(PACKAGE), "src", "ros", "adapters_msgs",
                        type_name.replace("/", "__") + ".msg")
    with open(path) as definition:
        return genpy.dynamic.generate_dynamic(type_name, definition.read())


def random_unit_quaternion(rng):
    while True:
        q = [rng.uniform(-1.0, 1.0) for _ in range(4)]
        norm = math.sqrt(sum(v * v for v in q))
        if 0.1 < norm <= 1.0:
            return [v / norm for v in q]


def rotation_matrix(q):
    x, y, z, w = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


class OrientedBox:
    """A box of `size` centred on `centre` (in its own frame), placed by (position, q)."""

    def __init__(self, position, q, size, centre=(0.0, 0.0, 0.0)):
        self.position, self.q, self.size, self.centre = position, q, size, centre

    def pose(self):
        return Pose(Point(*self.position), Quaternion(*self.q))

    def aabb(self):
        r = rotation_matrix(self.q)
        corners = []
        for corner in range(8):
            local = [self.centre[k] + (0.5 if corner >> k & 1 else -0.5) * self.size[k]
                     for k in range(3)]
            corners.append([self.position[a] + sum(r[a][k] * local[k] for k in range(3))
                            for a in range(3)])
        return ([min(c[a] for c in corners) for a in range(3)] +
                [max(c[a] for c in corners) for a in range(3)])


def random_boxes(rng, count):
    """Boxes in a cube of 20 with edges up to 3: every other one rotated, the others not."""
    boxes = []
    for k in range(count):
        q = random_unit_quaternion(rng) if k % 2 == 0 else [0.0, 0.0, 0.0, 1.0]
        boxes.append(OrientedBox([rng.uniform(0.0, 20.0) for _ in range(3)], q,
                                 [rng.uniform(0.0, 3.0) for _ in range(3)]))
    return boxes


def oracle_pairs(boxes):
    """boxes: {id: (aabb, group, mask)}; every pair of overlapping closed boxes the filters allow,
    as sorted (a, b) with a < b."""
    ids = sorted(boxes)
    pairs = []
    for i, a in enumerate(ids):
        box_a, group_a, mask_a = boxes[a]
        for b in ids[i + 1:]:
            box_b, group_b, mask_b = boxes[b]
            if (all(box_a[k] <= box_b[k + 3] and box_b[k] <= box_a[k + 3] for k in range(3))
                    and group_a & mask_b and group_b & mask_a):
                pairs.append((a, b))
    return pairs


def as_pairs(msg):
    ids = list(msg.pairs)
    return sorted((min(ids[k], ids[k + 1]), max(ids[k], ids[k + 1]))
                  for k in range(0, len(ids), 2))


class Scene:
    """The boxes of every source, their messages and the world the node should build."""

    def __init__(self):
        rng = random.Random(SEED)
        self.cubes = random_boxes(rng, BOXES_PER_SOURCE)
        self.list_points = [[rng.uniform(0.0, 20.0) for _ in range(3)] for _ in range(5)]
        self.list_pose = OrientedBox([1.0, -2.0, 0.5], random_unit_quaternion(rng), [0.0] * 3)
        self.vision = random_boxes(rng, BOXES_PER_SOURCE)
        self.detections = random_boxes(rng, BOXES_PER_SOURCE)
        self.jsk = random_boxes(rng, BOXES_PER_SOURCE)
        self.deleted_cubes = set()

    def list_boxes(self):
        size = [1.5, 0.5, 2.0]
        return [OrientedBox(self.list_pose.position, self.list_pose.q, size, point)
                for point in self.list_points]

    def world(self):
        """{id: (aabb, group, mask)} as the node should hold it. Marker ids follow the
        adapter's naming: (ns, id) in order, "cubes" before "list"."""
        world = {}
        base = OFFSETS["robot_markers"]
        for k, box in enumerate(self.cubes):
            if k not in self.deleted_cubes:
                world[base + k] = (box.aabb(), DEFAULT_GROUP, DEFAULT_MASK)
        for j, box in enumerate(self.list_boxes()):
            world[base + len(self.cubes) + j] = (box.aabb(), DEFAULT_GROUP, DEFAULT_MASK)
        for name, boxes in (("vision_boxes", self.vision), ("detections", self.detections)):
            for k, box in enumerate(boxes):
                world[OFFSETS[name] + k] = (box.aabb(), DEFAULT_GROUP, DEFAULT_MASK)
        for k, box in enumerate(self.jsk):
            world[OFFSETS["jsk_boxes"] + k] = (box.aabb(), JSK_GROUP, JSK_MASK)
        return world

    def marker_array(self):
        header = rospy.Header(frame_id=FRAME, stamp=rospy.Time(5))
        markers = [Marker(header=header, ns="cubes", id=k, type=Marker.CUBE, action=Marker.ADD,
                          pose=box.pose(), scale=Vector3(*box.size))
                   for k, box in enumerate(self.cubes)]
        # An unset orientation (all zero) on a CUBE_LIST: the identity for rviz, a refusal of
        # none here; this one has a real rotation.
        markers.append(Marker(header=header, ns="list", id=0, type=Marker.CUBE_LIST,
                              action=Marker.ADD, pose=self.list_pose.pose(),
                              scale=Vector3(1.5, 0.5, 2.0),
                              points=[Point(*p) for p in self.list_points]))
        # A sphere is no box: it adds nothing.
        markers.append(Marker(header=header, ns="sphere", id=0, type=Marker.SPHERE,
                              action=Marker.ADD, pose=Pose(orientation=Quaternion(0, 0, 0, 1)),
                              scale=Vector3(100, 100, 100)))
        return MarkerArray(markers=markers)


class AdaptersTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_adapters", anonymous=True)
        cls.lock = threading.Condition()
        cls.pairs = []  # every pairs message received
        cls.stats = []
        cls.id_names = None
        rospy.Subscriber("pairs", PairArray, cls.on_message, ("pairs",), queue_size=100)
        rospy.Subscriber("stats", FrameStats, cls.on_message, ("stats",), queue_size=100)
        rospy.Subscriber("id_names", IdNames, cls.on_message, ("id_names",), queue_size=10)
        cls.scene = Scene()
        cls.publish_scene()

    @classmethod
    def on_message(cls, msg, args):
        with cls.lock:
            if args[0] == "pairs":
                cls.pairs.append(as_pairs(msg))
            elif args[0] == "stats":
                cls.stats.append(msg)
            else:
                cls.id_names = msg
            cls.lock.notify_all()

    @classmethod
    def publish_scene(cls):
        """One latched message per source: delivered to the node whenever it connects."""
        scene = cls.scene
        header = rospy.Header(frame_id=FRAME, stamp=rospy.Time(5))
        cls.markers_pub = rospy.Publisher("robot_markers", MarkerArray, queue_size=10, latch=True)
        cls.markers_pub.publish(scene.marker_array())

        vision = foreign_classes("vision_msgs/BoundingBox3DArray")
        box_array, box3d = vision["vision_msgs/BoundingBox3DArray"], vision["vision_msgs/BoundingBox3D"]
        cls.vision_pub = rospy.Publisher("vision_boxes", box_array, queue_size=1, latch=True)
        cls.vision_pub.publish(box_array(header=header, boxes=[
            box3d(center=box.pose(), size=Vector3(*box.size)) for box in scene.vision]))

        detection = foreign_classes("vision_msgs/Detection3DArray")
        detection_array = detection["vision_msgs/Detection3DArray"]
        detection3d = detection["vision_msgs/Detection3D"]
        hypothesis = detection["vision_msgs/ObjectHypothesisWithPose"]
        cls.detections_pub = rospy.Publisher("detections", detection_array, queue_size=1,
                                             latch=True)
        cls.detections_pub.publish(detection_array(header=header, detections=[
            detection3d(header=header, results=[hypothesis(id=7, score=0.9)] * (k % 3),
                        bbox=detection["vision_msgs/BoundingBox3D"](
                            center=box.pose(), size=Vector3(*box.size)))
            for k, box in enumerate(scene.detections)]))

        jsk = foreign_classes("jsk_recognition_msgs/BoundingBoxArray")
        jsk_array, jsk_box = jsk["jsk_recognition_msgs/BoundingBoxArray"], jsk["jsk_recognition_msgs/BoundingBox"]
        cls.jsk_pub = rospy.Publisher("jsk_boxes", jsk_array, queue_size=1, latch=True)
        cls.jsk_pub.publish(jsk_array(header=header, boxes=[
            jsk_box(header=header, pose=box.pose(), dimensions=Vector3(*box.size), value=0.5,
                    label=100 + k) for k, box in enumerate(scene.jsk)]))

    def wait_for_pairs(self, expected, what):
        """Waits until a pairs message equals expected; fails with the last one's difference."""
        deadline = rospy.get_time() + WAIT
        with self.lock:
            while not rospy.is_shutdown():
                if self.pairs and self.pairs[-1] == expected:
                    return
                left = deadline - rospy.get_time()
                if left <= 0:
                    break
                self.lock.wait(left)
            last = set(self.pairs[-1]) if self.pairs else set()
        self.fail("%s: no pairs message equal to the oracle's (%d pairs) within %.0f s; the last "
                  "one lacks %s and has extra %s" % (what, len(expected), WAIT,
                                                     sorted(set(expected) - last)[:10],
                                                     sorted(last - set(expected))[:10]))

    def test_pairs_equal_the_oracle_then_a_marker_delete(self):
        expected = oracle_pairs(self.scene.world())
        self.assertGreater(len(expected), 20, "the scene should have pairs of every kind")
        self.wait_for_pairs(expected, "all four sources")
        # DELETE the first two cubes that have pairs: the source's other markers stay.
        base = OFFSETS["robot_markers"]
        paired_cubes = sorted({i - base for pair in expected for i in pair
                               if base <= i < base + BOXES_PER_SOURCE})
        self.scene.deleted_cubes = set(paired_cubes[:2])
        self.markers_pub.publish(MarkerArray(markers=[
            Marker(ns="cubes", id=k, action=Marker.DELETE) for k in sorted(self.scene.deleted_cubes)]))
        after_delete = oracle_pairs(self.scene.world())
        self.assertNotEqual(after_delete, expected, "the deleted cubes should have had pairs")
        self.wait_for_pairs(after_delete, "after DELETE of cubes %s" % sorted(self.scene.deleted_cubes))

    def test_id_names_name_every_box(self):
        expected = {OFFSETS["robot_markers"] + k: "robot_markers: cubes/%d" % k
                    for k in range(BOXES_PER_SOURCE)}
        for j in range(5):
            expected[OFFSETS["robot_markers"] + BOXES_PER_SOURCE + j] = \
                "robot_markers: list/0[%d]" % j
        for k in range(BOXES_PER_SOURCE):
            expected[OFFSETS["vision_boxes"] + k] = "vision_boxes: box %d" % k
            expected[OFFSETS["detections"] + k] = "detections: detection %d" % k
            expected[OFFSETS["jsk_boxes"] + k] = "jsk_boxes: label %d" % (100 + k)
        deadline = rospy.get_time() + WAIT
        names = {}
        with self.lock:
            while not rospy.is_shutdown() and rospy.get_time() < deadline:
                if self.id_names is not None:
                    names = dict(zip(self.id_names.ids, self.id_names.names))
                    if len(names) >= len(expected):
                        break
                self.lock.wait(deadline - rospy.get_time())
        self.assertEqual(names, expected)

    def test_another_definition_is_refused_by_its_md5(self):
        # vision_msgs 2 (ROS 2) renamed a field: another definition, another MD5 sum.
        other = genpy.dynamic.generate_dynamic(
            "vision_msgs/BoundingBox3DArray",
            "std_msgs/Header header\nBoundingBox3D[] boxes\n" + "=" * 80 +
            "\nMSG: vision_msgs/BoundingBox3D\ngeometry_msgs/Pose origin\n"
            "geometry_msgs/Vector3 size\n" + "=" * 80 + "\nMSG: std_msgs/Header\nuint32 seq\n"
            "time stamp\nstring frame_id\n" + "=" * 80 + "\nMSG: geometry_msgs/Pose\n"
            "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n" + "=" * 80 +
            "\nMSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n" + "=" * 80 +
            "\nMSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n" +
            "=" * 80 + "\nMSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n")
        array = other["vision_msgs/BoundingBox3DArray"]
        self.assertNotEqual(array._md5sum, foreign_classes(
            "vision_msgs/BoundingBox3DArray")["vision_msgs/BoundingBox3DArray"]._md5sum)
        publisher = rospy.Publisher("other_vision_boxes", array, queue_size=1, latch=True)
        publisher.publish(array(header=rospy.Header(frame_id=FRAME), boxes=[]))
        deadline = rospy.get_time() + WAIT
        refusal = ""
        with self.lock:
            while not rospy.is_shutdown() and rospy.get_time() < deadline:
                refusals = [s.last_refusal for s in self.stats if "other_vision_boxes" in s.last_refusal]
                if refusals:
                    refusal = refusals[-1]
                    break
                self.lock.wait(deadline - rospy.get_time())
        self.assertIn("with MD5 sum %s, not 9e1a3932308592aa1b20232d818486db" % array._md5sum,
                      refusal)


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "adapters", AdaptersTest)
