#!/usr/bin/python3
"""Hostile input: every bad message is refused with a warning naming the problem, counted on
~stats, and leaves the simulation exactly as it was; the node stays up and obeys good messages.

The scene has no gravity and no load, so the beam stays at rest (to round-off) unless a command
moves it.
"""
import unittest

import rospy
import rostest
from geometry_msgs.msg import Point, Vector3, WrenchStamped
from rosgraph_msgs.msg import Log

from deformable_sim.msg import FixedNodes, NodeWrench
from sim_client import (SimClient, all_finite, connected, node_wrench, positions,
                        wrench_stamped)

NAN = float('nan')
INF = float('inf')


class HostileInput(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_hostile_input')
        cls.warnings = []
        rospy.Subscriber('/rosout', Log, cls.on_log, queue_size=1000)
        cls.sim = SimClient()
        cls.wrench = rospy.Publisher('/deformable_sim/wrench', WrenchStamped, queue_size=1000)
        cls.node_wrench = rospy.Publisher('/deformable_sim/node_wrench', NodeWrench, queue_size=1000)
        cls.fixed = rospy.Publisher('/deformable_sim/fixed_nodes', FixedNodes, queue_size=1000)
        connected(cls.wrench, cls.node_wrench, cls.fixed)
        cls.rest = positions(cls.sim.state_at(0))

    @classmethod
    def on_log(cls, log):
        if log.level == Log.WARN and log.name.endswith('deformable_sim'):
            cls.warnings.append(log.msg)

    def assertAtRest(self, state):
        # Round-off alone moves the resting beam by ~1e-15 m; any applied force (even 1 mN) would
        # move it by more than a micrometre in five steps.
        moved = max(abs(a - b) for p, q in zip(positions(state), self.rest) for a, b in zip(p, q))
        self.assertLess(moved, 1e-12, 'a refused message moved the body by %g m' % moved)

    def refused(self, publisher, message, words):
        """Publishes a bad message; checks it is refused, named, counted, and changed nothing."""
        before = self.sim.wait('stats')
        publisher.publish(message)
        stats = self.sim.wait('stats', lambda m: m.dropped_messages > before.dropped_messages)
        self.assertEqual(stats.dropped_messages, before.dropped_messages + 1)
        for w in words:
            self.assertIn(w, stats.last_refusal)
        self.assertEqual(stats.bodies[0].applied_wrenches, 0)
        self.assertEqual(stats.bodies[0].fixed_nodes, 9)
        step = self.sim.step(0).step
        self.sim.step(5)
        state = self.sim.state_at(step + 5)
        self.assertTrue(all_finite(positions(state)))
        self.assertAtRest(state)
        return stats.last_refusal

    def test_wrench_stamped(self):
        first = self.refused(self.wrench, wrench_stamped('beam/tip', force=(0, 0, NAN)),
                             ['~wrench', 'beam/tip', 'NaN'])
        self.refused(self.wrench, wrench_stamped('beam/tip', torque=(INF, 0, 0)), ['NaN or infinite'])
        self.refused(self.wrench, wrench_stamped('beam/tip', force=(0, 0, -1e9)), ['exceeds the limits'])
        self.refused(self.wrench, wrench_stamped('gripper_link', force=(0, 0, -1)),
                     ["unknown frame 'gripper_link'"])
        self.refused(self.wrench, wrench_stamped('beam/middle', force=(0, 0, -1)),
                     ["has no group 'middle'", 'corner, tip'])
        self.refused(self.wrench, wrench_stamped('', force=(0, 0, -1)), ['frame_id is empty'])
        self.refused(self.wrench, wrench_stamped('beam/corner', torque=(0, 0, 1)),
                     ['cannot carry a torque'])
        # The first refusal on the topic was also logged as a warning naming the problem.
        deadline = rospy.Time.now() + rospy.Duration(5.0)
        while not any(first in w for w in self.warnings) and rospy.Time.now() < deadline:
            rospy.sleep(0.05)
        self.assertTrue(any(first in w for w in self.warnings), self.warnings)

    def test_node_wrench(self):
        self.refused(self.node_wrench, node_wrench(nodes=[3, 123456], force=(0, 0, -1)),
                     ['123456'])
        self.refused(self.node_wrench, node_wrench(body='sponge', group='tip', force=(0, 0, -1)),
                     ["unknown body 'sponge'", "'beam'"])
        self.refused(self.node_wrench, node_wrench(group='nope', force=(0, 0, -1)), ["no group 'nope'"])
        self.refused(self.node_wrench, node_wrench(force=(0, 0, -1)), ['exactly one of'])
        self.refused(self.node_wrench, node_wrench(group='tip', force=(NAN, 0, 0)), ['NaN'])

    def test_fixed_nodes(self):
        fix = FixedNodes.FIX
        self.refused(self.fixed, FixedNodes(body='beam', action=fix, region=FixedNodes.REGION_BOX,
                                            box_min=Point(5, 5, 5), box_max=Point(6, 6, 6)),
                     ['box contains no node'])
        self.refused(self.fixed, FixedNodes(body='beam', action=fix, region=FixedNodes.REGION_SPHERE,
                                            sphere_center=Point(0.5, 0, 0), sphere_radius=-1.0),
                     ['radius'])
        self.refused(self.fixed, FixedNodes(body='beam', action=fix, region=FixedNodes.REGION_BOX,
                                            box_min=Point(1, 1, 1), box_max=Point(0, 0, 0)),
                     ['box: min must not exceed max'])
        self.refused(self.fixed, FixedNodes(body='beam', action=fix, nodes=[9],
                                            targets=[Point(0.5, NAN, 0)]), ['NaN or infinite'])
        self.refused(self.fixed, FixedNodes(body='beam', action=fix, nodes=[9],
                                            targets=[Point(1e6, 0, 0)]), ['more than'])
        self.refused(self.fixed, FixedNodes(body='beam', action=fix, nodes=[9, 18],
                                            targets=[Point(0.5, 0, 0)]), ['1 targets for 2 nodes'])
        self.refused(self.fixed, FixedNodes(body='beam', action=fix, group='tip',
                                            translation=Vector3(INF, 0, 0)), ['NaN or infinite'])
        self.refused(self.fixed, FixedNodes(body='nobody', action=fix, group='tip'),
                     ["unknown body 'nobody'"])
        self.refused(self.fixed, FixedNodes(body='beam', action=7, group='tip'),
                     ['neither FIX (0) nor RELEASE (1)'])
        self.refused(self.fixed, FixedNodes(body='beam', action=fix, nodes=[-4]), ['-4'])
        header_frame = FixedNodes(body='beam', action=fix, group='tip')
        header_frame.header.frame_id = 'no_such_frame'
        self.refused(self.fixed, header_frame, ["unknown frame 'no_such_frame'"])

    def test_zz_a_flood_is_counted_and_throttled_and_good_input_still_works(self):
        before = self.sim.wait('stats')
        warnings_before = len(self.warnings)
        start = rospy.Time.now()
        for _ in range(200):
            self.wrench.publish(wrench_stamped('beam/tip', force=(NAN, NAN, NAN)))
            rospy.sleep(0.002)
        stats = self.sim.wait('stats', lambda m: m.dropped_messages >= before.dropped_messages + 200,
                              timeout=20.0)
        self.assertEqual(stats.dropped_messages, before.dropped_messages + 200)
        elapsed = (rospy.Time.now() - start).to_sec()
        rospy.sleep(0.5)
        # At most one warning a second on the topic, each saying how many were silenced.
        self.assertLessEqual(len(self.warnings) - warnings_before, elapsed + 2)
        self.assertAtRest(self.sim.wait('state'))
        # A good wrench after all that still bends the beam.
        self.wrench.publish(wrench_stamped('beam/tip', force=(0, 0, -0.5)))
        self.sim.wait('stats', lambda m: m.bodies[0].applied_wrenches == 1)
        step = self.sim.step(20).step
        bent = positions(self.sim.state_at(step))
        self.assertLess(min(p[2] for p in bent), -0.05 - 1e-4)
        self.wrench.publish(wrench_stamped('beam/tip'))  # a zero wrench clears it
        self.sim.wait('stats', lambda m: m.bodies[0].applied_wrenches == 0)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'hostile_input', HostileInput)
