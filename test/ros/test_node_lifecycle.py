#!/usr/bin/python3
"""The node's life as a ROS user sees it: --help starts nothing, and rviz is told to forget the
markers of an earlier run when a node starts, and when it stops (Ctrl-C or rosnode kill)."""
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

    def stop_and_check_markers_cleared(self, name, stop):
        """Starts a node called `name`, checks its first message on ~mesh is a mesh (what a new
        subscriber must see; an earlier run's meshes expire by their lifetime), stops it with
        stop(process) and checks the last message on ~mesh and ~markers clears everything."""
        node = subprocess.Popen(['rosrun', 'deformable_sim', 'deformable_sim_node',
                                 '__name:=' + name], stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
        try:
            mesh = Recorder('/%s/mesh' % name, Marker)
            markers = Recorder('/%s/markers' % name, MarkerArray)
            first = mesh.wait_for(1)[0][1]
            self.assertEqual(first.action, Marker.ADD)
            self.assertGreater(len(first.points), 0)
            self.assertGreater(first.lifetime.to_sec(), 0.0)
            markers.wait_for(2)
            stop(node)
            self.assertEqual(node.wait(timeout=20), 0)
            time.sleep(0.5)
            with mesh.lock:
                self.assertEqual(mesh.messages[-1][1].action, Marker.DELETEALL)
            with markers.lock:  # every array starts with a DELETEALL: the last is nothing else
                self.assertEqual([m.action for m in markers.messages[-1][1].markers],
                                 [Marker.DELETEALL])
        finally:
            if node.poll() is None:
                node.kill()

    def test_markers_are_cleared_on_ctrl_c(self):
        self.stop_and_check_markers_cleared('short_lived', lambda p: p.send_signal(signal.SIGINT))

    def test_markers_are_cleared_on_rosnode_kill(self):
        self.stop_and_check_markers_cleared(
            'killed', lambda p: subprocess.run(['rosnode', 'kill', '/killed'], timeout=20,
                                               capture_output=True))


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'node_lifecycle', NodeLifecycle)
