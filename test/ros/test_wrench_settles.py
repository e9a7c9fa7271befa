#!/usr/bin/python3
"""A WrenchStamped on a node group's frame moves the body where the quasi-static solution says:
the node (damped, stepped until it settles) against deformable_sim_run --static on the same scene
with the same wrench as a scene load."""
import csv
import os
import subprocess
import tempfile
import unittest

import rospy
import rostest
from geometry_msgs.msg import WrenchStamped

from sim_client import SimClient, connected, positions

FORCE = (0.0, 0.2, -0.5)    # N, on the tip face
TORQUE = (0.02, 0.0, 0.0)   # N m about the tip face's centroid (a twist)


class WrenchSettles(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_wrench_settles')
        cls.sim = SimClient()
        cls.wrench_pub = rospy.Publisher('/deformable_sim/wrench', WrenchStamped, queue_size=10)
        connected(cls.wrench_pub)
        cls.scene = rospy.get_param('~scene')

    def static_solution(self):
        """Node number -> displacement, from the offline runner with the wrench as a scene load."""
        with open(self.scene) as f:
            text = f.read()
        text += ('    loads: [{box: {min: [0.499999, -1, -1], max: [0.500001, 1, 1]}, '
                 'wrench: {force: [%r, %r, %r], torque: [%r, %r, %r]}}]\n' % (FORCE + TORQUE))
        folder = tempfile.mkdtemp()
        scene = os.path.join(folder, 'loaded.yaml')
        with open(scene, 'w') as f:
            f.write(text)
        out = os.path.join(folder, 'static.csv')
        run = subprocess.run(['rosrun', 'deformable_sim', 'deformable_sim_run', scene, '--static',
                              '--out', out], capture_output=True, text=True, timeout=120)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        with open(out) as f:
            return {int(row['node']): (float(row['ux']), float(row['uy']), float(row['uz']))
                    for row in csv.DictReader(f)}

    def test_settles_to_the_static_solution(self):
        # The node starts paused at rest, so the tip frame is aligned with the world.
        self.assertEqual(self.sim.step(0).step, 0)
        rest = {n: p for n, p in zip(self.sim.state_at(0).node_ids, positions(self.sim.state_at(0)))}
        wrench = WrenchStamped()
        wrench.header.frame_id = 'beam/tip'
        wrench.header.stamp = rospy.Time.now()
        wrench.wrench.force.x, wrench.wrench.force.y, wrench.wrench.force.z = FORCE
        wrench.wrench.torque.x, wrench.wrench.torque.y, wrench.wrench.torque.z = TORQUE
        self.wrench_pub.publish(wrench)
        stats = self.sim.wait('stats', lambda m: m.bodies[0].applied_wrenches == 1)
        self.assertEqual(stats.dropped_messages, 0, stats.last_refusal)
        self.sim.step(600)  # 6 s simulated; the heavy damping settles it
        state = self.sim.state_at(600)
        speed = max(abs(c) for v in state.velocities for c in (v.x, v.y, v.z))
        self.assertLess(speed, 1e-6)
        expected = self.static_solution()
        largest = max(max(abs(c) for c in u) for u in expected.values())
        self.assertGreater(largest, 0.05)  # a real deflection: gravity and the wrench
        worst = 0.0
        for node, p in zip(state.node_ids, positions(state)):
            u = [a - b for a, b in zip(p, rest[node])]
            worst = max(worst, max(abs(a - b) for a, b in zip(u, expected[node])))
        self.assertLess(worst, 1e-5 * largest, 'worst node differs by %g m' % worst)
        # The wrench did something of its own: without it the tip would not move sideways.
        tip_y = [u[1] for n, u in expected.items() if abs(rest[n][0] - 0.5) < 1e-9]
        self.assertGreater(min(tip_y), 0.0)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'wrench_settles', WrenchSettles)
