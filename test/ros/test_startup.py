#!/usr/bin/python3
"""Start-up refusals that need the node's namespace: ~sources topics are compared as the node
subscribes to them, resolved in its namespace and through its remappings. One topic spelled
two ways (`boxes` and `/ns/boxes` in /ns), two names remapped onto one topic, or a source that
is the scenery topic `static_boxes` stop the node at start-up (exit status 1) with a FATAL
naming both spellings, as docs/NODE.md says for a topic listed twice; read twice, every message
would be refused as its own duplicate on every frame. scene_publisher's numbers out of their
rows of the limits table stop it alike.

Each node is run to its end; WAIT only bounds a node that wrongly keeps running.
"""
import subprocess
import unittest

import rospy
import rostest

PACKAGE = "sap_broadphase"
WAIT = 30.0  # seconds; a bound on waiting, never a speed check


class StartupTest(unittest.TestCase):
    def run_node(self, name, sources, *arguments):
        command = ["rosrun", PACKAGE, "node", "__ns:=/ns", "__name:=%s" % name,
                   "_sources:=%s" % sources] + list(arguments)
        node = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True)
        try:
            output, _ = node.communicate(timeout=WAIT)
        except subprocess.TimeoutExpired:
            node.terminate()
            output, _ = node.communicate()
            self.fail("the node with ~sources %s %s kept running:\n%s"
                      % (sources, " ".join(arguments), output[-2000:]))
        return node.returncode, output

    def assert_refused(self, name, sources, expected, *arguments):
        status, output = self.run_node(name, sources, *arguments)
        self.assertEqual(status, 1, output[-2000:])
        self.assertIn(expected, output)

    def test_one_topic_spelled_two_ways(self):
        self.assert_refused("spelled", "[boxes, /ns/boxes]",
                            "~sources lists 'boxes' and '/ns/boxes', one topic twice (/ns/boxes)")

    def test_two_names_remapped_onto_one_topic(self):
        self.assert_refused("remapped", "[boxes, more_boxes]",
                            "~sources lists 'boxes' and 'more_boxes', one topic twice (/ns/boxes)",
                            "more_boxes:=boxes")

    def test_the_scenery_topic_as_a_source(self):
        self.assert_refused(
            "scenery", "[boxes, {topic: /ns/static_boxes, type: sap_broadphase/BoxArray}]",
            "~sources lists '/ns/static_boxes', which is the scenery topic static_boxes")

    def test_scene_publisher_parameters_out_of_range_stop_it_naming_them(self):
        """scene_publisher's numbers are rows of the limits table: outside, a FATAL naming the
        parameter and exit status 1 (a negative ~n or ~max_frames, or a ~rate of 0, were
        taken before)."""
        for parameter, value in (("n", "-1"), ("n", "1e9"), ("rate", "0"), ("density", "0"),
                                 ("seed", "-1"), ("scene_frames", "0"), ("max_frames", "-1"),
                                 ("plane_axis", "3"), ("speed", "inf")):
            command = ["rosrun", PACKAGE, "scene_publisher", "__ns:=/ns",
                       "__name:=scene_limits_%s" % parameter, "_%s:=%s" % (parameter, value)]
            node = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                  text=True, timeout=WAIT)
            self.assertEqual(node.returncode, 1,
                             "_%s:=%s: exit %s\n%s" % (parameter, value, node.returncode,
                                                        node.stdout[-2000:]))
            self.assertIn("FATAL", node.stdout, "_%s:=%s" % (parameter, value))
            self.assertIn("~%s must be" % parameter, node.stdout)


if __name__ == "__main__":
    rospy.init_node("test_startup", anonymous=True)
    rostest.rosrun(PACKAGE, "startup", StartupTest)
