#!/usr/bin/python3
"""What the node refuses, and how it says so: too many steps a call, impossible live tuning,
a push the body cannot take, a wrench in a frame far from every body."""
import math
import unittest

import dynamic_reconfigure.client
import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import TransformStamped, WrenchStamped

from sim_client import SimClient, all_finite, connected, positions, wrench_stamped


class NodeLimits(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_node_limits')
        cls.sim = SimClient()
        cls.wrench = rospy.Publisher('/deformable_sim/wrench', WrenchStamped, queue_size=10)
        connected(cls.wrench)
        cls.tf = tf2_ros.StaticTransformBroadcaster()
        far = TransformStamped()
        far.header.stamp = rospy.Time.now()
        far.header.frame_id = 'world'
        far.child_frame_id = 'far_frame'
        far.transform.translation.x = 3.5  # 3 m beyond the beam's free end
        far.transform.rotation.w = 1.0
        cls.tf.sendTransform(far)

    def setUp(self):
        self.sim.pause()
        self.sim.reset()

    def refusal(self, send):
        """Calls send(); returns ~stats' last refusal once the node counted one more."""
        before = self.sim.wait('stats')
        send()
        stats = self.sim.wait('stats', lambda m: m.dropped_messages > before.dropped_messages)
        return stats.last_refusal

    def test_step_refuses_more_than_a_call_may_take(self):
        start = self.sim.step(0)
        self.assertTrue(start.success)
        answer = self.sim.step(3000000000)
        self.assertFalse(answer.success)
        self.assertIn('max_steps_per_call', answer.message)
        self.assertEqual(answer.step, start.step)
        self.assertFalse(self.sim.step(1001).success)
        self.assertEqual(self.sim.step(1000).step, start.step + 1000)

    def test_live_tuning_refuses_what_it_cannot_be(self):
        client = dynamic_reconfigure.client.Client('/deformable_sim', timeout=10.0)
        for name, value, words in (('youngs_modulus', -5.0, 'youngs_modulus is -5'),
                                   ('poisson_ratio', 0.5, 'poisson_ratio is 0.5'),
                                   ('solver_tolerance', -1.0, 'tolerance'),
                                   ('rate', 0.0, 'rate')):
            before = client.get_configuration(timeout=10.0)[name]
            reason = self.refusal(lambda: client.update_configuration({name: value}))
            self.assertIn(words, reason)
            self.assertEqual(client.get_configuration(timeout=10.0)[name], before, name)
        # The beam still sags as the scene's foam does: nothing was clamped into effect.
        self.sim.step(30)
        state = self.sim.state_at(30)
        self.assertGreater(min(p[2] for p in positions(state)), -0.2)

    def test_a_push_the_body_cannot_take_is_refused(self):
        reason = self.refusal(lambda: self.wrench.publish(
            wrench_stamped('beam/tip', force=(0, 0, -9000))))
        self.assertIn("exceeds the limits of body 'beam'", reason)
        self.assertIn('at most 49.05', reason)  # ten times the 0.5 kg beam's weight
        self.wrench.publish(wrench_stamped('beam/tip', force=(0, 0, -49)))
        self.sim.wait('stats', lambda m: m.bodies[0].applied_wrenches == 1)
        for _ in range(3):
            self.sim.step(100)
        stats = self.sim.wait('stats')
        self.assertEqual(stats.bodies[0].inverted_elements, 0)
        state = self.sim.wait('state')
        self.assertTrue(all_finite(positions(state)))
        self.assertLess(max(math.dist(p, (0.0, 0.0, 0.0)) for p in positions(state)), 0.8)
        self.wrench.publish(wrench_stamped('beam/tip'))

    def test_a_wrench_in_a_far_frame_names_the_frame_body_distance_and_radius(self):
        reason = self.refusal(lambda: self.wrench.publish(
            wrench_stamped('far_frame', force=(0, 0, -1))))
        for words in ('far_frame', "'beam'", '3 m', 'wrench_radius 0.05 m'):
            self.assertIn(words, reason)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'node_limits', NodeLimits)
