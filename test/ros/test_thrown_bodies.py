#!/usr/bin/python3
"""Two soft cubes thrown at each other at 5 m/s without gravity, through the node
(test/data/scenes/thrown_bodies.yaml, velocity keys): they meet and stop each other without
passing through, and their total momentum stays zero to 1e-6 of either cube's."""
import unittest

import rospy
import rostest

from deformable_sim.msg import Contacts, Scene
from sim_client import SimClient

DENSITY = 100.0  # kg/m^3, both cubes
SPEED = 5.0      # m/s


def lumped_masses(mesh):
    """Each node's lumped mass, kg: a quarter of each of its tetrahedra's."""
    x = mesh.rest_positions
    masses = [0.0] * len(mesh.node_ids)
    for t in range(0, len(mesh.tetrahedra), 4):
        corners = mesh.tetrahedra[t:t + 4]
        a, b, c, d = [x[3 * i:3 * i + 3] for i in corners]
        u, v, w = [[p[k] - a[k] for k in range(3)] for p in (b, c, d)]
        volume = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                  u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0
        for i in corners:
            masses[i] += DENSITY * volume / 4.0
    return masses


class ThrownBodies(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_thrown_bodies')
        cls.sim = SimClient()
        scene = rospy.wait_for_message('/deformable_sim/scene', Scene, timeout=10.0)
        cls.masses = {m.body: lumped_masses(m) for m in scene.meshes}
        cls.touching = 0
        rospy.Subscriber('/deformable_sim/contacts', Contacts, cls.on_contacts, queue_size=100)

    @classmethod
    def on_contacts(cls, message):
        cls.touching += sum(1 for p in message.pairs if p.body == 'left' and p.other == 'right')

    def state(self, body, step):
        return self.sim.wait('state', lambda m: m.step == step, body=body)

    def momentum(self, step):
        total = [0.0, 0.0, 0.0]
        centres = {}
        for body in ('left', 'right'):
            state = self.state(body, step)
            for m, v in zip(self.masses[body], state.velocities):
                total = [total[0] + m * v.x, total[1] + m * v.y, total[2] + m * v.z]
            centres[body] = sum(p.x for p in state.positions) / len(state.positions)
        return total, centres

    def test_they_stop_each_other_on_their_own_sides_with_momentum_kept(self):
        scale = SPEED * sum(self.masses['left'])  # either cube's momentum at the start
        self.assertAlmostEqual(scale, SPEED * DENSITY * 0.2 ** 3, delta=1e-9)
        total, _ = self.momentum(0)
        self.assertLess(max(abs(p) for p in total), 1e-9 * scale)
        for step in range(1, 31):
            self.assertTrue(self.sim.step(1).success)
            total, centres = self.momentum(step)
            self.assertLess(max(abs(p) for p in total), 1e-6 * scale, 'step %d' % step)
            self.assertLess(centres['left'], centres['right'], 'step %d' % step)
        self.assertGreater(self.touching, 0)
        left = self.state('left', 30)
        pushed = sum(m * v.x for m, v in zip(self.masses['left'], left.velocities))
        self.assertLess(pushed, 0.1 * scale)  # stopped: no longer flying on at 5 m/s


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'thrown_bodies', ThrownBodies)
