#!/usr/bin/python3
"""A Python client of the sap_broadphase node, as a user's program would be written:

1. calls the `compute_pairs` service with three boxes of its own and prints their pairs;
2. subscribes to `pairs` (the world of the node's sources) and `id_names` (what the ids of
   MarkerArray, vision_msgs and jsk sources stand for) and prints each frame's pairs by name.

Parameters: ~frames (pairs messages to print before exiting; 0 = until shut down).
Exit status 0 once it has printed its answer and ~frames frames, 1 when the service refuses.

    rosrun sap_broadphase pairs_client.py _frames:=5
"""
import sys
import threading

import rospy
from sap_broadphase.msg import BoxArray, IdNames, PairArray
from sap_broadphase.srv import ComputePairs


def ask_service():
    """Three unit-ish boxes: 0 and 1 overlap, 1 and 2 touch (closed intervals), 0 and 2 not."""
    rospy.wait_for_service("compute_pairs")
    compute_pairs = rospy.ServiceProxy("compute_pairs", ComputePairs)
    boxes = BoxArray(header=rospy.Header(frame_id="map"), ids=[10, 11, 12],
                     bounds=[0.0, 0.0, 0.0, 1.0, 1.0, 1.0,
                             0.5, 0.5, 0.5, 2.0, 2.0, 2.0,
                             2.0, 0.0, 0.0, 3.0, 1.0, 1.0])
    answer = compute_pairs(boxes)
    if not answer.success:
        print("compute_pairs refused the boxes: %s" % answer.message)
        return False
    ids = answer.pairs.pairs
    print("compute_pairs: %s" % ", ".join("(%d, %d)" % (ids[k], ids[k + 1])
                                          for k in range(0, len(ids), 2)))
    return True


class PairPrinter:
    """Prints pairs by name; the names come latched on id_names and grow as sources name boxes."""

    def __init__(self, frames):
        self.frames_left = frames
        self.names = {}
        self.done = threading.Event()
        self.lock = threading.Lock()
        rospy.Subscriber("id_names", IdNames, self.on_names, queue_size=1)
        rospy.Subscriber("pairs", PairArray, self.on_pairs, queue_size=1)

    def on_names(self, msg):
        with self.lock:
            self.names = dict(zip(msg.ids, msg.names))

    def name(self, box_id):
        return "%d %s" % (box_id, self.names[box_id]) if box_id in self.names else str(box_id)

    def on_pairs(self, msg):
        ids = msg.pairs
        with self.lock:
            if self.done.is_set():
                return  # ~frames printed; frames arriving before the exit are not
            pairs = ["(%s | %s)" % (self.name(ids[k]), self.name(ids[k + 1]))
                     for k in range(0, len(ids), 2)]
            print("pairs at %.3f in '%s': %d%s" % (msg.header.stamp.to_sec(),
                                                   msg.header.frame_id, len(pairs),
                                                   (": " + ", ".join(pairs)) if pairs else ""))
            sys.stdout.flush()
            if self.frames_left > 0:
                self.frames_left -= 1
                if self.frames_left == 0:
                    self.done.set()


def main():
    rospy.init_node("pairs_client", anonymous=True)
    frames = int(rospy.get_param("~frames", 0))
    if not ask_service():
        return 1
    printer = PairPrinter(frames)
    while not rospy.is_shutdown() and not printer.done.wait(0.1):
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
