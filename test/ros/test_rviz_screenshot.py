#!/usr/bin/python3
"""rviz in a real viewer: Xvfb + rviz with rviz/demo.rviz while the demo runs.

Takes a screenshot and asserts that the colour of the colliding-box marker is present in the
3D view. The screenshot is kept as build/artifacts/rviz_demo.png. Every process this test
starts (Xvfb, rviz) is stopped by its PID.
"""
import os
import select
import subprocess
import time
import unittest

import rosgraph
import rospy
import rostest
from visualization_msgs.msg import MarkerArray

PACKAGE = "sap_broadphase"
REPO = os.path.realpath(os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", ".."))
ARTIFACTS = os.path.join(REPO, "build", "artifacts")
RVIZ_CONFIG = os.path.join(REPO, "rviz", "demo.rviz")
CONVERT = "/usr/bin/convert"  # Debian's imagemagick, not whatever /usr/local/bin holds
SCREEN = (1280, 800)
# The 3D view of rviz/demo.rviz: right of the Displays panel, below the toolbar.
VIEW_BOX = (0.30, 0.10, 0.98, 0.95)  # left, top, right, bottom as fractions of the screen
MIN_FRACTION = 0.001  # of the 3D view's pixels in the colliding colour
RVIZ_NAME = "rviz_screenshot"


def stop(process, timeout=5.0):
    """Stops one process we started: SIGTERM, then SIGKILL after timeout seconds."""
    if process.poll() is not None:
        return
    process.terminate()
    try:
        process.wait(timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


class RvizScreenshotTest(unittest.TestCase):
    def setUp(self):
        self.processes = []
        os.makedirs(ARTIFACTS, exist_ok=True)
        rospy.init_node("test_rviz_screenshot", anonymous=True)

    def tearDown(self):
        for process in reversed(self.processes):
            stop(process)

    def start_xvfb(self):
        """Starts Xvfb on a free display (Xvfb picks it) and returns the display number."""
        read_end, write_end = os.pipe()
        log = open(os.path.join(ARTIFACTS, "xvfb.log"), "w")
        xvfb = subprocess.Popen(
            ["Xvfb", "-displayfd", str(write_end), "-screen", "0",
             "%dx%dx24" % SCREEN, "-nolisten", "tcp"],
            pass_fds=(write_end,), stdout=log, stderr=log)
        self.processes.append(xvfb)
        os.close(write_end)
        # Xvfb writes the number, then a newline: read both before closing our end, or its
        # second write fails and it exits.
        reported = b""
        end = time.monotonic() + 20.0
        while not reported.endswith(b"\n") and time.monotonic() < end:
            ready, _, _ = select.select([read_end], [], [], max(0.0, end - time.monotonic()))
            chunk = os.read(read_end, 16) if ready else b""
            if not chunk:
                break
            reported += chunk
        os.close(read_end)
        self.assertTrue(reported.endswith(b"\n"),
                        "Xvfb did not report a display (see build/artifacts/xvfb.log)")
        return int(reported.decode().strip())

    def start_rviz(self, display):
        env = dict(os.environ, DISPLAY=":%d" % display, LIBGL_ALWAYS_SOFTWARE="1")
        log = open(os.path.join(ARTIFACTS, "rviz.log"), "w")
        rviz = subprocess.Popen(
            ["rosrun", "rviz", "rviz", "-d", RVIZ_CONFIG, "__name:=" + RVIZ_NAME],
            env=env, stdout=log, stderr=log)
        self.processes.append(rviz)
        return rviz

    def wait_subscribed(self, topic, node, timeout):
        """Waits until node subscribes to topic (rviz needs several seconds here)."""
        master = rosgraph.Master(rospy.get_name())
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            _, subscribers, _ = master.getSystemState()
            if any(name == topic and node in nodes for name, nodes in subscribers):
                return True
            time.sleep(0.5)
        return False

    def screenshot(self, display, path):
        xwd = subprocess.Popen(["xwd", "-root", "-silent", "-display", ":%d" % display],
                               stdout=subprocess.PIPE)
        subprocess.run([CONVERT, "xwd:-", "png:" + path], stdin=xwd.stdout, check=True,
                       timeout=60)
        xwd.stdout.close()
        self.assertEqual(xwd.wait(timeout=30), 0, "xwd failed")

    def colour_fraction(self, path, rgb):
        """Fraction of the 3D view's pixels within 40 levels of rgb on every channel."""
        left, top = int(VIEW_BOX[0] * SCREEN[0]), int(VIEW_BOX[1] * SCREEN[1])
        width = int(VIEW_BOX[2] * SCREEN[0]) - left
        height = int(VIEW_BOX[3] * SCREEN[1]) - top
        raw = subprocess.run(
            [CONVERT, path, "-crop", "%dx%d+%d+%d" % (width, height, left, top), "+repage",
             "-depth", "8", "rgb:-"], check=True, capture_output=True, timeout=60).stdout
        red, green, blue = raw[0::3], raw[1::3], raw[2::3]
        hits = sum(1 for r, g, b in zip(red, green, blue)
                   if abs(r - rgb[0]) <= 40 and abs(g - rgb[1]) <= 40 and abs(b - rgb[2]) <= 40)
        return hits / max(1, len(red))

    def test_colliding_boxes_visible_in_rviz(self):
        markers = rospy.wait_for_message("markers", MarkerArray, timeout=60)
        colliding = [m for m in markers.markers if m.ns == "colliding"]
        self.assertTrue(colliding and colliding[0].points, "the demo frame has no colliding box")
        colour = colliding[0].color
        rgb = tuple(int(round(255 * c)) for c in (colour.r, colour.g, colour.b))

        display = self.start_xvfb()
        rviz = self.start_rviz(display)
        self.assertTrue(self.wait_subscribed(rospy.resolve_name("markers"), "/" + RVIZ_NAME, 60),
                        "rviz never subscribed to markers (see build/artifacts/rviz.log)")
        path = os.path.join(ARTIFACTS, "rviz_demo.png")
        fraction = 0.0
        for _ in range(20):  # a bound on waiting for the first rendered frame, not a speed check
            time.sleep(2.0)
            self.assertIsNone(rviz.poll(), "rviz exited (see build/artifacts/rviz.log)")
            self.screenshot(display, path)
            fraction = self.colour_fraction(path, rgb)
            if fraction >= MIN_FRACTION:
                break
        rospy.loginfo("colliding colour %s covers %.2f %% of the 3D view; screenshot %s",
                      rgb, 100.0 * fraction, path)
        self.assertGreaterEqual(fraction, MIN_FRACTION,
                                "colliding colour %s not in the 3D view of %s" % (rgb, path))


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "rviz_screenshot", RvizScreenshotTest)
