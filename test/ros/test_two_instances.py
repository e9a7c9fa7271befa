#!/usr/bin/python3
"""Two simulators side by side (launch/two_instances.launch): each under its own namespace, with
its own topics and tf frames prefixed by the namespace."""
import unittest

import rospy
import rostest
import tf2_ros

from sim_client import SimClient, surface_marker


class TwoInstances(unittest.TestCase):
    def test_each_has_its_own_topics_and_frames(self):
        left = SimClient('/left/deformable_sim')
        right = SimClient('/right/deformable_sim')
        self.assertEqual(left.wait('state').body, 'beam')
        self.assertEqual(right.wait('state').body, 'sponge')
        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        beam = buffer.lookup_transform('world', 'left/beam', rospy.Time(0), rospy.Duration(10.0))
        sponge = buffer.lookup_transform('world', 'right/sponge', rospy.Time(0), rospy.Duration(10.0))
        self.assertAlmostEqual(beam.transform.translation.x, 0.25, delta=0.01)
        self.assertAlmostEqual(sponge.transform.translation.y, 0.6, delta=0.01)
        buffer.lookup_transform('world', 'right/sponge/top', rospy.Time(0), rospy.Duration(5.0))
        # The sponge's scene asks for stress colouring: a colour per vertex.
        mesh = surface_marker('/right/deformable_sim/mesh')
        self.assertEqual(len(mesh.colors), len(mesh.points))
        self.assertEqual(mesh.ns, 'sponge')
        plain = surface_marker('/left/deformable_sim/mesh')
        self.assertEqual(len(plain.colors), 0)
        # Pausing one leaves the other running.
        left.pause()
        paused = left.wait('stats', lambda m: m.paused).step
        running = right.wait('stats').step
        rospy.sleep(0.5)
        self.assertEqual(left.wait('stats').step, paused)
        self.assertGreater(right.wait('stats').step, running)
        left.resume()


if __name__ == '__main__':
    rospy.init_node('test_two_instances')
    rostest.rosrun('deformable_sim', 'two_instances', TwoInstances)
