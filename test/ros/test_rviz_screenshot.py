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

import rospy
import rostest
from visualization_msgs.msg import MarkerArray

from ros_test_support import REPO, artifact, poll_until, stop, subscribed

PACKAGE = "sap_broadphase"
RVIZ_CONFIG = os.path.join(REPO, "rviz", "demo.rviz")
CONVERT = "/usr/bin/convert"  # Debian's imagemagick, not whatever /usr/local/bin holds
SCREEN = (1280, 800)
# The 3D view of rviz/demo.rviz: right of the Displays panel, below the toolbar.
VIEW_BOX = (0.30, 0.10, 0.98, 0.95)  # left, top, right, bottom as fractions of the screen
MIN_FRACTION = 0.001  # of the 3D view's pixels in the colliding colour
# Not the test's own name (rostest names it after the test-name, rviz_screenshot): the master
# shuts down a node when another registers under its name.
RVIZ_NAME = "rviz_viewer"


class RvizScreenshotTest(unittest.TestCase):
    def setUp(self):
        self.processes = []
        rospy.init_node("test_rviz_screenshot", anonymous=True)

    def tearDown(self):
        for process in reversed(self.processes):
            stop(process)

    def start_xvfb(self):
        """Starts Xvfb on a free display (Xvfb picks it) and returns the display number."""
        read_end, write_end = os.pipe()
        log = open(artifact("xvfb.log"), "w")
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
        log = open(artifact("rviz.log"), "w")
        rviz = subprocess.Popen(
            ["rosrun", "rviz", "rviz", "-d", RVIZ_CONFIG, "__name:=" + RVIZ_NAME],
            env=env, stdout=log, stderr=log)
        self.processes.append(rviz)
        return rviz

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
        # rviz needs several seconds to subscribe here.
        self.assertTrue(poll_until(lambda: subscribed(rospy.resolve_name("markers"),
                                                      "/" + RVIZ_NAME), 60, interval=0.5),
                        "rviz never subscribed to markers (see build/artifacts/rviz.log)")
        path = artifact("rviz_demo.png")
        fraction = 0.0

        def drawn():
            nonlocal fraction
            self.assertIsNone(rviz.poll(), "rviz exited (see build/artifacts/rviz.log)")
            self.screenshot(display, path)
            fraction = self.colour_fraction(path, rgb)
            return fraction >= MIN_FRACTION

        # Screenshots until rviz has rendered the markers; the bound only ends a broken run.
        poll_until(drawn, 40.0, interval=2.0)
        rospy.loginfo("colliding colour %s covers %.2f %% of the 3D view; screenshot %s",
                      rgb, 100.0 * fraction, path)
        self.assertGreaterEqual(fraction, MIN_FRACTION,
                                "colliding colour %s not in the 3D view of %s" % (rgb, path))


if __name__ == "__main__":
    rostest.rosrun(PACKAGE, "rviz_screenshot", RvizScreenshotTest)
