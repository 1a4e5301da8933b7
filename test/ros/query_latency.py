#!/usr/bin/python3
"""Latency of `query_boxes` while large frames flow: a measurement, not a test.

Publishes frames of BOXES random boxes on `boxes` at RATE Hz and runs CALLERS threads, each
calling `query_boxes` (one box, persistent connection) in a loop for SECONDS; prints the
median, p90, p99 and largest latency, and how many frames newer than the call the answer was
(from the response's header, when the service has one). Run it against a node started with
`rosrun sap_broadphase node` in the same ROS master:

    python3 test/ros/query_latency.py [--boxes 100000] [--rate 20] [--callers 20] [--seconds 20]
"""
import argparse
import threading
import time

import numpy
import rospy
from rospy.numpy_msg import numpy_msg
from sap_broadphase.msg import BoxArray
from sap_broadphase.srv import QueryBoxes, QueryBoxesRequest


def random_frames(count, boxes, seed=11):
    rng = numpy.random.default_rng(seed)
    extent = (boxes ** (1.0 / 3.0)) * 2.0  # about one box a 2x2x2 cell: a sparse scene
    frames = []
    for _ in range(count):
        low = rng.uniform(0.0, extent, size=(boxes, 3))
        high = low + rng.uniform(0.2, 1.0, size=(boxes, 3))
        msg = numpy_msg(BoxArray)()
        msg.header.frame_id = "world"
        msg.bounds = numpy.hstack([low, high]).astype(numpy.float64).ravel()
        msg.ids = numpy.arange(boxes, dtype=numpy.uint32)
        msg.groups = numpy.zeros(0, dtype=numpy.uint32)  # numpy_msg writes arrays only
        msg.masks = numpy.zeros(0, dtype=numpy.uint32)
        frames.append(msg)
    return frames, extent


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--boxes", type=int, default=100000)
    parser.add_argument("--rate", type=float, default=20.0)
    parser.add_argument("--callers", type=int, default=20)
    parser.add_argument("--seconds", type=float, default=20.0)
    args = parser.parse_args()
    rospy.init_node("query_latency", anonymous=True)
    frames, extent = random_frames(4, args.boxes)
    pub = rospy.Publisher("boxes", numpy_msg(BoxArray), queue_size=1)
    while pub.get_num_connections() == 0 and not rospy.is_shutdown():
        time.sleep(0.05)
    stop = threading.Event()
    published = []  # stamps, in order

    def publish():
        period = 1.0 / args.rate
        next_time = time.monotonic()
        k = 0
        while not stop.is_set():
            msg = frames[k % len(frames)]
            msg.header.stamp = rospy.Time.now()
            pub.publish(msg)
            published.append(msg.header.stamp)
            k += 1
            next_time += period
            stop.wait(max(0.0, next_time - time.monotonic()))

    rospy.wait_for_service("query_boxes")
    publisher = threading.Thread(target=publish)
    publisher.start()
    time.sleep(2.0)  # frames flowing before the callers start
    latencies, newer = [], []
    lock = threading.Lock()

    def call(seed):
        rng = numpy.random.default_rng(seed)
        proxy = rospy.ServiceProxy("query_boxes", QueryBoxes, persistent=True)
        end = time.monotonic() + args.seconds
        while time.monotonic() < end and not rospy.is_shutdown():
            request = QueryBoxesRequest()
            request.boxes.header.frame_id = "world"
            low = list(rng.uniform(0.0, extent, size=3))
            request.boxes.bounds = low + [v + 1.0 for v in low]
            latest = published[-1]
            start = time.monotonic()
            response = proxy(request)
            elapsed = time.monotonic() - start
            header = getattr(response, "header", None)
            with lock:
                latencies.append(elapsed)
                if header is not None and header.stamp >= latest:
                    newer.append(sum(1 for s in published[-200:] if latest < s <= header.stamp))

    callers = [threading.Thread(target=call, args=(k,)) for k in range(args.callers)]
    for c in callers:
        c.start()
    for c in callers:
        c.join()
    stop.set()
    publisher.join()
    lat = numpy.array(latencies) * 1000.0
    print("boxes %d rate %.0f Hz callers %d: %d calls, latency ms median %.1f p90 %.1f p99 %.1f "
          "max %.1f (frame period %.1f ms)" % (
              args.boxes, args.rate, args.callers, len(lat), numpy.median(lat),
              numpy.percentile(lat, 90), numpy.percentile(lat, 99), lat.max(), 1000.0 / args.rate))
    if newer:
        print("answered on a frame newer than the latest published at the call: median %d, "
              "max %d frames" % (numpy.median(newer), max(newer)))


if __name__ == "__main__":
    main()
