#!/usr/bin/python3
"""The three body models in one node (config/scenes/three_models.yaml): the stats name each
body's model and effects, every body has its tf frames, a wrench swings the rigid pendulum about
its pivot, and a grasp drags the pseudo-rigid cushion's top with the gripper."""
import math
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Point, TransformStamped, WrenchStamped

from deformable_sim.msg import Grasp
from deformable_sim.srv import SetGrasp
from sim_client import FrameBroadcaster, SimClient, connected, grasp_when_in_tf, positions

PIVOT = (0.0, 0.3, 0.0)


class BodyModels(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_body_models')
        cls.sim = SimClient()
        cls.buffer = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.buffer)
        cls.wrench_pub = rospy.Publisher('/deformable_sim/wrench', WrenchStamped, queue_size=10)
        connected(cls.wrench_pub)
        rospy.wait_for_service('/deformable_sim/grasp')
        cls.grasp = rospy.ServiceProxy('/deformable_sim/grasp', SetGrasp)
        cls.frames = FrameBroadcaster()

    def body_state(self, body, predicate=lambda m: True):
        return self.sim.wait('state', predicate, body=body)

    def frame(self, name):
        return self.buffer.lookup_transform('world', name, rospy.Time(0), rospy.Duration(10.0))

    def test_stats_name_each_bodys_model_and_effects(self):
        stats = self.sim.wait('stats')
        bodies = {b.body: b for b in stats.bodies}
        self.assertEqual(sorted(bodies), ['beam', 'cushion', 'pendulum'])
        self.assertEqual(bodies['beam'].model, 'fem')
        self.assertEqual(bodies['pendulum'].model, 'rigid')
        self.assertEqual(bodies['cushion'].model, 'pseudo_rigid')
        self.assertEqual(list(bodies['beam'].effects), ['warping', 'gravity', 'damping', 'reactions'])
        # A rigid body has nothing to warp; the pendulum's own damping replaces the scene's.
        self.assertEqual(list(bodies['pendulum'].effects), ['gravity', 'damping', 'reactions'])
        self.assertEqual(list(bodies['cushion'].effects),
                         ['warping', 'gravity', 'damping', 'reactions'])
        self.assertEqual(bodies['pendulum'].fixed_nodes, 1)

    def test_wrench_swings_the_rigid_pendulum_about_its_pivot(self):
        bottom = self.frame('pendulum/bottom').transform.translation
        self.assertAlmostEqual(bottom.z, -0.3, delta=1e-3)
        wrench = WrenchStamped()
        wrench.header.frame_id = 'pendulum/bottom'
        wrench.wrench.force.x = 20.0  # N; the bar weighs 3.7 kg
        for _ in range(3):
            wrench.header.stamp = rospy.Time.now()
            self.wrench_pub.publish(wrench)
            rospy.sleep(0.2)
        state = self.body_state('pendulum', lambda m: max(p.x for p in m.positions) > 0.05)
        # Turned about the pivot, which stayed: no node is farther from it than the bar's corners.
        for p in positions(state):
            self.assertLess(math.dist(p, PIVOT), math.hypot(0.3, 0.02, 0.02) + 1e-9)
        pivot = min(positions(state), key=lambda p: math.dist(p, PIVOT))
        self.assertLess(math.dist(pivot, PIVOT), 1e-9)
        # The frame of its bottom face went with it: at the face's centre at the state's time
        # (within the bar's motion in one step, ~1 m/s x 10 ms: tf interpolates its samples).
        face = [p for p in positions(state) if math.dist(p, PIVOT) > 0.3 - 1e-6]
        self.assertEqual(len(face), 9)
        centre = [sum(c) / len(face) for c in zip(*face)]
        at = self.buffer.lookup_transform('world', 'pendulum/bottom', state.header.stamp,
                                          rospy.Duration(5.0)).transform.translation
        self.assertLess(math.dist((at.x, at.y, at.z), centre), 0.01)

    def test_grasp_drags_the_pseudo_rigid_cushion(self):
        gripper = TransformStamped()
        gripper.header.frame_id = 'world'
        gripper.child_frame_id = 'gripper'
        gripper.transform.translation.x, gripper.transform.translation.y = 0.0, -0.3
        gripper.transform.translation.z = -0.2
        gripper.transform.rotation.w = 1.0
        self.frames.transform = gripper
        self.assertTrue(self.buffer.can_transform('world', 'gripper', rospy.Time(0),
                                                  rospy.Duration(10.0)))
        # The top face, a little below z = -0.2 where its weight squashes the cushion.
        request = Grasp(name='hand', body='cushion', action=Grasp.ATTACH, region=Grasp.REGION_BOX,
                        box_min=Point(-0.2, -0.2, -0.01), box_max=Point(0.2, 0.2, 0.01))
        request.header.frame_id = 'gripper'
        answer = grasp_when_in_tf(self.grasp, request)
        self.assertTrue(answer.success, answer.message)
        held = self.body_state('cushion', lambda m: True)
        top_z = max(p[2] for p in positions(held))
        gripper.transform.translation.z = -0.17  # pull the top 3 cm up
        state = self.body_state('cushion', lambda m: max(p.z for p in m.positions) > top_z + 0.0295)
        top = [p[2] for p in positions(state) if p[2] > top_z + 0.01]
        self.assertEqual(len(top), 25)
        for z in top:
            self.assertAlmostEqual(z, top_z + 0.03, delta=1e-6)
        # Homogeneous: the middle layer stays halfway between the base and the top.
        middle = [p[2] for p in positions(state) if -0.29 < p[2] < top_z - 0.01]
        self.assertEqual(len(middle), 25)
        for z in middle:
            self.assertAlmostEqual(z, (-0.3 + top_z + 0.03) / 2, delta=1e-6)
        self.assertTrue(self.grasp(Grasp(name='hand', action=Grasp.RELEASE)).success)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'body_models', BodyModels)
