#!/usr/bin/python3
"""The node's life as a ROS user sees it: --help starts nothing, outputs come at the rates asked
for, and rviz is told to forget the markers of an earlier run when a node starts and stops."""
import signal
import subprocess
import threading
import time
import unittest

import rosnode
import rospy
import rostest
from visualization_msgs.msg import Marker, MarkerArray

from deformable_sim.msg import Stats


class Recorder:
    """Every message of a topic, with the time it arrived."""

    def __init__(self, topic, kind):
        self.lock = threading.Lock()
        self.messages = []
        self.subscriber = rospy.Subscriber(topic, kind, self.on_message, queue_size=1000)

    def on_message(self, message):
        with self.lock:
            self.messages.append((time.time(), message))

    def wait_for(self, count, timeout=20.0):
        deadline = time.time() + timeout
        while time.time() < deadline:
            with self.lock:
                if len(self.messages) >= count:
                    return list(self.messages)
            time.sleep(0.05)
        raise AssertionError('%d messages on %s within %.0f s, not %d' %
                             (len(self.messages), self.subscriber.name, timeout, count))


def rate(recorder, seconds):
    """Messages a second over `seconds`, counted after the first message."""
    first = recorder.wait_for(1)[0][0]
    time.sleep(seconds)
    with recorder.lock:
        arrived = [t for t, _ in recorder.messages if first < t <= first + seconds]
    return len(arrived) / seconds


class NodeLifecycle(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_node_lifecycle')

    def test_help_prints_the_usage_and_starts_nothing(self):
        done = subprocess.run(['rosrun', 'deformable_sim', 'deformable_sim_node', '--help'],
                              capture_output=True, text=True, timeout=20)
        self.assertEqual(done.returncode, 0, done.stderr)
        for words in ('usage: deformable_sim_node', '~scene', '~max_steps_per_call', '~step'):
            self.assertIn(words, done.stdout)
        # The node the launch file started (same name) still runs.
        self.assertIn('/deformable_sim', rosnode.get_node_names())
        rospy.wait_for_message('/deformable_sim/stats', Stats, timeout=5.0)

    def test_outputs_come_at_the_rates_asked_for(self):
        mesh = Recorder('/deformable_sim/mesh', Marker)  # ~marker_rate 30 in the launch file
        stats = Recorder('/deformable_sim/stats', Stats)  # ~stats_rate 10
        self.assertAlmostEqual(rate(mesh, 10.0), 30.0, delta=1.0)
        self.assertAlmostEqual(rate(stats, 10.0), 10.0, delta=0.35)

    def test_markers_are_cleared_on_start_and_on_shutdown(self):
        node = subprocess.Popen(['rosrun', 'deformable_sim', 'deformable_sim_node',
                                 '__name:=short_lived'], stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
        try:
            mesh = Recorder('/short_lived/mesh', Marker)
            markers = Recorder('/short_lived/markers', MarkerArray)
            first_mesh = mesh.wait_for(3)[0][1]
            first_markers = markers.wait_for(2)[0][1]
            self.assertEqual(first_mesh.action, Marker.DELETEALL)
            self.assertEqual(first_markers.markers[0].action, Marker.DELETEALL)
            self.assertEqual(mesh.wait_for(3)[1][1].action, Marker.ADD)
            node.send_signal(signal.SIGINT)
            self.assertEqual(node.wait(timeout=20), 0)
            time.sleep(0.5)
            with mesh.lock:
                self.assertEqual(mesh.messages[-1][1].action, Marker.DELETEALL)
            with markers.lock:
                self.assertEqual(markers.messages[-1][1].markers[0].action, Marker.DELETEALL)
        finally:
            if node.poll() is None:
                node.kill()


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'node_lifecycle', NodeLifecycle)
