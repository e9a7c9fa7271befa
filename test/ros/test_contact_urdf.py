#!/usr/bin/python3
"""A body dropped on a URDF obstacle: the table link's collision box, posed by tf from
robot_state_publisher, stops the falling block; it comes to rest on the tilted top face with no node
below the surface by more than round-off (the contact effect projects nodes out after every step)."""
import time
import unittest

import numpy as np
import rospy
import rostest
import tf2_ros
from visualization_msgs.msg import Marker, MarkerArray

from sim_client import SimClient, positions

SURFACE_TOLERANCE = 1e-9  # m: README, "URDF obstacles"


def quaternion_matrix(q):
    x, y, z, w = q.x, q.y, q.z, q.w
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


class ContactWithUrdf(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_contact_urdf')
        cls.sim = SimClient()
        buffer = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(buffer)
        t = buffer.lookup_transform('world', 'table', rospy.Time(0), rospy.Duration(20.0)).transform
        cls.rotation = quaternion_matrix(t.rotation)
        cls.origin = np.array([t.translation.x, t.translation.y, t.translation.z])

    def heights(self, state):
        """Each node's height above the table's top face, along its normal (negative: inside)."""
        local = (np.array(positions(state)) - self.origin) @ self.rotation
        inside = (np.abs(local[:, 0]) < 0.3) & (np.abs(local[:, 1]) < 0.3)
        self.assertTrue(np.all(inside), 'the block left the table top')
        return local[:, 2]

    def step(self, steps):
        # The node does not step before tf has placed every obstacle link.
        deadline = time.time() + 20.0
        while True:
            answer = self.sim.step(steps)
            if answer.success or time.time() > deadline:
                break
            rospy.sleep(0.2)
        self.assertTrue(answer.success, answer.message)
        return self.sim.state_at(answer.step)

    def test_a_dropped_block_comes_to_rest_on_the_table(self):
        start = self.sim.state_at(0)
        self.assertGreater(self.heights(start).min(), 0.04)
        landed = False
        for _ in range(40):  # 4 s in steps of 0.1 s
            state = self.step(10)
            h = self.heights(state)
            self.assertGreater(h.min(), -SURFACE_TOLERANCE, 'a node is %.3g m inside the table' % -h.min())
            self.assertTrue(np.all(np.isfinite(positions(state))))
            landed = landed or h.min() < 1e-6
        self.assertTrue(landed, 'the block never reached the table')
        # At rest, its bottom face (5 x 5 nodes) on the top face, stuck by friction on the slope
        # (a corner of the tilted, squashed block may lift by a few microns).
        self.assertLess(max(abs(c) for v in state.velocities for c in (v.x, v.y, v.z)), 1e-3)
        h = self.heights(state)
        self.assertGreaterEqual(int(np.sum(h < 1e-5)), 21)
        self.assertLessEqual(int(np.sum(h < 1e-3)), 25)
        drift = np.linalg.norm(np.mean(positions(state), axis=0)[:2] - np.mean(positions(start), axis=0)[:2])
        self.assertLess(drift, 0.02, 'it slid %.3f m down the slope' % drift)
        stats = self.sim.wait('stats')
        self.assertGreaterEqual(stats.bodies[0].contacts, 21)
        self.assertLessEqual(stats.bodies[0].contacts, 25)
        self.assertEqual(stats.bodies[0].fixed_nodes, 0)  # contacts are not fixed nodes

    def test_the_links_among_the_obstacles_are_drawn_in_their_own_namespace(self):
        """~obstacles draws the table link in namespace 'links', which a config that draws the
        robot model hides (config/grasp_friction.rviz): not drawn twice, no z-fighting."""
        array = rospy.wait_for_message('/deformable_sim/obstacles', MarkerArray, timeout=20.0)
        added = [m for m in array.markers if m.action == Marker.ADD]
        self.assertEqual([m.ns for m in added], ['links'])

if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'contact_urdf', ContactWithUrdf)
