"""What the rostest Python nodes of test/ros share: where they leave their artifacts, stopping
the processes they start, waiting for a condition, and asking the master who is connected.

A wait is always for a condition; its bound only turns a broken system into a failure that
names what was awaited, instead of a hang. Conditions that a callback signals are waited for
on its threading.Condition; poll_until is for those that notify nobody (connection counts, the
master's graph, a service's answer).
"""
import os
import subprocess
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
from sap_broadphase.msg import PairArray

REPO = os.path.realpath(os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", ".."))
ARTIFACTS = os.path.join(REPO, "build", "artifacts")


def artifact(name):
    """The path of name in build/artifacts/ (created if missing): bags, logs and screenshots a
    test keeps for a person to look at afterwards."""
    os.makedirs(ARTIFACTS, exist_ok=True)
    return os.path.join(ARTIFACTS, name)


def stop(process, timeout=5.0):
    """Stops one process the test started: SIGTERM, then SIGKILL after timeout seconds."""
    if process.poll() is not None:
        return
    process.terminate()
    try:
        process.wait(timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def poll_until(ready, timeout, interval=0.05):
    """Checks ready() every interval seconds of wall time (not ROS time: a test may drive
    /clock itself) until it holds, for at most timeout seconds; returns whether it held."""
    end = time.monotonic() + timeout
    while not ready():
        if time.monotonic() > end or rospy.is_shutdown():
            return False
        time.sleep(interval)
    return True


def wait_until(ready, what, timeout):
    """poll_until, failing the test with "no <what> within <timeout> s" if ready() never held."""
    if not poll_until(ready, timeout):
        raise AssertionError("no %s within %.0f s" % (what, timeout))


def sends_to(node, topic, subscriber):
    """True once node has an outbound connection on topic to subscriber (its getBusInfo)."""
    master = rosgraph.Master(rospy.get_name())
    try:
        info = xmlrpc.client.ServerProxy(master.lookupNode(node)).getBusInfo(rospy.get_name())[2]
    except (rosgraph.MasterError, OSError):
        return False
    return any(len(c) > 4 and c[2] == "o" and c[4] == topic and c[1] == subscriber for c in info)


def subscribed(topic, node_prefix):
    """True once the master lists a subscriber of topic whose name starts with node_prefix."""
    _, subscribers, _ = rosgraph.Master(rospy.get_name()).getSystemState()
    return any(name == topic and any(n.startswith(node_prefix) for n in nodes)
               for name, nodes in subscribers)


def sorted_pairs(msg):
    """The pairs of a PairArray as a sorted list of (a, b) tuples."""
    flat = list(msg.pairs)
    return sorted(zip(flat[0::2], flat[1::2]))


class PairsByStamp:
    """The pairs a node publishes on topic, by stamp (sorted_pairs). condition guards them and
    is notified at each message; a caller may pass its own, to wait on other messages too."""

    def __init__(self, topic, condition=None, queue_size=100):
        self.condition = condition or threading.Condition()
        self.pairs = {}
        self.subscriber = rospy.Subscriber(topic, PairArray, self.on_pairs, queue_size=queue_size)

    def on_pairs(self, msg):
        with self.condition:
            self.pairs[msg.header.stamp] = sorted_pairs(msg)
            self.condition.notify_all()

    def wait_for(self, stamp, timeout):
        """The pairs of the frame stamped stamp, or None if none came within timeout seconds."""
        with self.condition:
            if not self.condition.wait_for(lambda: stamp in self.pairs, timeout):
                return None
            return self.pairs[stamp]
