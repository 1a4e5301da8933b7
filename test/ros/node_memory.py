#!/usr/bin/python3
"""Peak memory of the node per box (docs/NODE.md, "Memory"): not a test, a measurement.

With a roscore running (loopback), starts the node binary given, feeds it frames of N uniform
boxes from scene_publisher (--frames of them) or one compute_pairs request of N boxes
(--service), waits until the node answered, and prints the node's VmHWM (peak resident set)
and VmRSS from /proc/<pid>/status, also per box. Stops every process it started by its PID.

Usage: node_memory.py --node BIN --scene-publisher BIN --n N [--frames K | --service]
                      [-- NODE_ARGS, e.g. _skin:=off]
"""
import argparse
import array
import random
import subprocess
import threading

import rospy
from sap_broadphase.msg import BoxArray, FrameStats
from sap_broadphase.srv import ComputePairs

WAIT = 120.0


def status_kib(pid, field):
    with open("/proc/%d/status" % pid) as status:
        for line in status:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    raise KeyError(field)


def stop(process):
    if process.poll() is None:
        process.terminate()
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


def uniform_request(n, seed=1):
    """n boxes of edge 1 in a cube holding them at 5 % density (as the uniform scene)."""
    rng = random.Random(seed)
    side = (n / 0.05) ** (1.0 / 3.0)
    bounds = array.array("d", bytes(8 * 6 * n))
    for i in range(n):
        for k in range(3):
            low = rng.uniform(0.0, side - 1.0)
            bounds[6 * i + k] = low
            bounds[6 * i + k + 3] = low + 1.0
    boxes = BoxArray()
    boxes.header.frame_id = "map"
    boxes.bounds = bounds
    return boxes


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--node", required=True)
    parser.add_argument("--scene-publisher", required=True)
    parser.add_argument("--n", type=int, required=True)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--service", action="store_true")
    parser.add_argument("node_args", nargs="*", help="more node arguments, e.g. _skin:=off")
    args = parser.parse_args()

    rospy.init_node("node_memory", anonymous=True)
    computed = threading.Event()
    counts = {"frames": 0}

    def on_stats(msg):
        if msg.path != "refused" and msg.boxes == args.n:
            counts["frames"] += 1
            if counts["frames"] >= args.frames:
                computed.set()

    rospy.Subscriber("/mem/stats", FrameStats, on_stats)
    node = subprocess.Popen([args.node, "__name:=sap_broadphase", "__ns:=/mem",
                             "_publish_markers:=false"] + args.node_args)
    publisher = None
    try:
        if args.service:
            rospy.wait_for_service("/mem/compute_pairs", WAIT)
            request = uniform_request(args.n)
            response = rospy.ServiceProxy("/mem/compute_pairs", ComputePairs)(request)
            assert response.success, response.message
            what = "1 compute_pairs call, %d pairs" % (len(response.pairs.pairs) // 2)
        else:
            publisher = subprocess.Popen([
                args.scene_publisher, "__name:=scene_publisher", "__ns:=/mem",
                "_scene:=uniform", "_n:=%d" % args.n, "_rate:=1.0", "_max_frames:=0"])
            if not computed.wait(WAIT):
                raise SystemExit("the node answered %d of %d frames" % (counts["frames"], args.frames))
            what = "%d frames of scene_publisher's uniform scene" % args.frames
        hwm = status_kib(node.pid, "VmHWM")
        rss = status_kib(node.pid, "VmRSS")
        print("n %d (%s): VmHWM %.1f MiB = %.0f B/box, VmRSS %.1f MiB" %
              (args.n, what, hwm / 1024.0, hwm * 1024.0 / args.n, rss / 1024.0))
    finally:
        if publisher:
            stop(publisher)
        stop(node)


if __name__ == "__main__":
    main()
