#!/usr/bin/python3
"""Grasps through tf: grasped nodes follow a moving frame exactly, a hanging body's reaction wrench
is its weight about its centre of mass, a release lets it fall from where it was, and bad grasps
are refused with a clear message."""
import math
import time
import unittest

import numpy as np
import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Point, TransformStamped, WrenchStamped

from deformable_sim.msg import Grasp
from deformable_sim.srv import SetGrasp
from sim_client import FrameBroadcaster, SimClient, grasp_when_in_tf, positions

MASS = 200.0 * 0.1 ** 3  # kg: density x volume of the block
G = 9.81


def rotation(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k


def quaternion(r):
    w = math.sqrt(max(0.0, 1.0 + r[0, 0] + r[1, 1] + r[2, 2])) / 2.0
    x = math.copysign(math.sqrt(max(0.0, 1.0 + r[0, 0] - r[1, 1] - r[2, 2])) / 2.0, r[2, 1] - r[1, 2])
    y = math.copysign(math.sqrt(max(0.0, 1.0 - r[0, 0] + r[1, 1] - r[2, 2])) / 2.0, r[0, 2] - r[2, 0])
    z = math.copysign(math.sqrt(max(0.0, 1.0 - r[0, 0] - r[1, 1] + r[2, 2])) / 2.0, r[1, 0] - r[0, 1])
    return x, y, z, w


class GraspTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_grasp')
        cls.sim = SimClient()
        cls.frames = FrameBroadcaster()
        cls.buffer = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.buffer)
        rospy.wait_for_service('/deformable_sim/grasp')
        cls.grasp = rospy.ServiceProxy('/deformable_sim/grasp', SetGrasp)

    def move_gripper(self, translation, r=np.eye(3)):
        """Sets the gripper's pose (broadcast at 50 Hz, as a robot would) and waits until the node
        has it."""
        t = TransformStamped()
        t.header.frame_id = 'world'
        t.child_frame_id = 'gripper'
        t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = translation
        (t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
         t.transform.rotation.w) = quaternion(r)
        self.frames.transform = t
        rospy.sleep(0.3)

    def attach_top_corner(self):
        """Grasps the nodes within 2.6 cm of the block's top corner (0, 0, 0.1)."""
        request = Grasp(name='hand', body='block', action=Grasp.ATTACH, region=Grasp.REGION_BOX,
                        box_min=Point(-0.001, -0.001, -0.026), box_max=Point(0.026, 0.026, 0.001))
        request.header.frame_id = 'gripper'
        return grasp_when_in_tf(self.grasp, request)

    def setUp(self):
        self.sim.pause()
        self.grasp(Grasp(name='hand', action=Grasp.RELEASE))
        self.sim.reset()
        self.move_gripper((0.0, 0.0, 0.1))

    def test_grasped_nodes_follow_a_fast_frame_exactly(self):
        answer = self.attach_top_corner()
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(answer.nodes, 8)
        state = self.sim.state_at(0)
        grasped = [k for k, p in enumerate(positions(state))
                   if p[0] < 0.026 and p[1] < 0.026 and p[2] > 0.074]
        origin = np.array([0.0, 0.0, 0.1])
        local = {k: np.array(positions(state)[k]) - origin for k in grasped}
        for step in range(1, 9):
            # 10 cm and 0.3 rad per 10 ms step: fast.
            translation = origin + np.array([0.1 * step, 0.0, 0.05 * step])
            r = rotation((0.3, 1.0, 0.2), 0.3 * step)
            self.move_gripper(translation, r)
            self.sim.step(1)
            state = self.sim.state_at(step)
            for k in grasped:
                error = np.linalg.norm(np.array(positions(state)[k]) - (translation + r @ local[k]))
                self.assertLess(error, 1e-9, 'node %d is %g m from its target' % (state.node_ids[k], error))
            self.assertTrue(np.all(np.isfinite(positions(state))))
        # The object as seen from the gripper is in tf.
        self.buffer.lookup_transform('gripper', 'hand/object', rospy.Time(0), rospy.Duration(5.0))

    def test_hanging_body_reaction_is_its_weight_and_release_lets_it_fall(self):
        self.assertTrue(self.attach_top_corner().success)
        for _ in range(3):  # the heavy damping brings it to rest (at most 1000 steps a call)
            self.sim.step(500)
        state = self.sim.state_at(1500)
        self.assertLess(max(abs(c) for v in state.velocities for c in (v.x, v.y, v.z)), 1e-8)
        wrench = rospy.wait_for_message('/deformable_sim/grasps/hand/wrench', WrenchStamped, timeout=5.0)
        self.assertEqual(wrench.header.frame_id, 'gripper')
        force = np.array([wrench.wrench.force.x, wrench.wrench.force.y, wrench.wrench.force.z])
        weight = np.array([0.0, 0.0, -MASS * G])
        self.assertLess(np.linalg.norm(force + weight), 1e-6 * MASS * G, force)
        # Its torque about the gripper cancels the weight's about the same point.
        body = self.buffer.lookup_transform('world', 'block', rospy.Time(0), rospy.Duration(5.0))
        centre = np.array([body.transform.translation.x, body.transform.translation.y,
                           body.transform.translation.z])
        torque = np.array([wrench.wrench.torque.x, wrench.wrench.torque.y, wrench.wrench.torque.z])
        expected = -np.cross(centre - np.array([0.0, 0.0, 0.1]), weight)
        self.assertGreater(np.linalg.norm(expected), 0.01)  # held off-centre: it hangs tilted
        self.assertLess(np.linalg.norm(torque - expected), 1e-5 * np.linalg.norm(expected),
                        '%s vs %s' % (torque, expected))
        # Release: no jump, then it falls.
        answer = self.grasp(Grasp(name='hand', action=Grasp.RELEASE))
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(answer.nodes, 8)
        self.assertEqual(positions(self.sim.state_at(1500)), positions(state))
        self.sim.step(10)
        fallen = positions(self.sim.state_at(1510))
        self.assertLess(max(p[2] for p in fallen), max(p[2] for p in positions(state)) - 1e-3)
        # The released grasp's wrench topic is closed: names used once do not pile up.
        topic = '/deformable_sim/grasps/hand/wrench'
        deadline = time.time() + 5.0
        while time.time() < deadline and topic in dict(rospy.get_published_topics()):
            time.sleep(0.05)
        self.assertNotIn(topic, dict(rospy.get_published_topics()))

    def test_bad_grasps_are_refused_with_a_clear_message(self):
        empty = Grasp(name='hand', action=Grasp.ATTACH, region=Grasp.REGION_SPHERE,
                      sphere_center=Point(5.0, 5.0, 5.0), sphere_radius=0.01)
        empty.header.frame_id = 'gripper'
        # After setUp's reset the node hears of the gripper again a moment later (sim time jumped
        # back, which clears its tf buffer).
        answer = grasp_when_in_tf(self.grasp, empty)
        self.assertFalse(answer.success)
        self.assertEqual(answer.message, "grasp 'hand': body 'block': the sphere contains no node")
        unknown = Grasp(name='hand', action=Grasp.ATTACH, region=Grasp.REGION_SPHERE,
                        sphere_radius=0.05)
        unknown.header.frame_id = 'no_gripper'
        answer = self.grasp(unknown)
        self.assertFalse(answer.success)
        self.assertIn("unknown frame 'no_gripper'", answer.message)
        link = Grasp(name='hand', action=Grasp.ATTACH, region=Grasp.REGION_LINK, link='finger')
        link.header.frame_id = 'gripper'
        answer = self.grasp(link)
        self.assertFalse(answer.success)
        self.assertIn('finger', answer.message)
        self.assertFalse(self.grasp(Grasp(name='nothing', action=Grasp.RELEASE)).success)
        # A name that cannot be a topic (~grasps/<name>/wrench) is refused before anything is held.
        dashed = Grasp(name='left-hand', action=Grasp.ATTACH, region=Grasp.REGION_SPHERE,
                       sphere_radius=0.05)
        dashed.header.frame_id = 'gripper'
        answer = self.grasp(dashed)
        self.assertFalse(answer.success)
        self.assertIn("grasp 'left-hand': not a valid ROS name", answer.message)
        stats = self.sim.wait('stats')
        self.assertEqual(stats.bodies[0].fixed_nodes, 0)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'grasp', GraspTest)
