#!/usr/bin/python3
"""Five soft cubes stacked on a floor, through the node (config/scenes/stack.yaml): stepped five
seconds, they stand where they were put, none sinks into the one below by more than the contact's
tolerance, and ~contacts gives each pair the weight of what rests on it (averaged over the last
ten ticks: a tick's force jitters by about 2 %, doc/physics.md)."""
import math
import unittest

import rospy
import rostest

from deformable_sim.msg import ContactPair, Contacts
from sim_client import SimClient, positions

CUBES = 5
SIDE = 0.1                                 # m
WEIGHT = 100.0 * SIDE ** 3 * 9.81          # N, of one cube
TOLERANCE = 0.01 * math.sqrt(3.0) * SIDE   # 1 % of a cube's size (its diagonal)
STEPS = 500
AVERAGED = 10                              # last ticks whose contact forces are averaged


class Stack(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_stack')
        cls.sim = SimClient()
        cls.contacts = {}  # step -> message
        rospy.Subscriber('/deformable_sim/contacts', Contacts, cls.on_contacts, queue_size=100)
        response = cls.sim.step(STEPS - AVERAGED)
        for _ in range(AVERAGED):  # a tick each, so that each publishes its contacts
            response = cls.sim.step(1)
        assert response.success and response.step == STEPS, response

    @classmethod
    def on_contacts(cls, message):
        cls.contacts[message.step] = message

    def cube(self, k):
        return positions(self.sim.wait('state', lambda m: m.step == STEPS, body='cube%d' % k))

    def test_the_cubes_stand_where_they_were_put_none_inside_another(self):
        below_top = None
        for k in range(CUBES):
            points = self.cube(k)
            centre = [sum(p[i] for p in points) / len(points) for i in range(3)]
            self.assertLess(math.hypot(centre[0], centre[1]), 0.01 * SIDE, 'cube%d' % k)
            self.assertAlmostEqual(centre[2], (k + 0.5) * SIDE, delta=0.02 * SIDE, msg='cube%d' % k)
            bottom = min(p[2] for p in points)
            if below_top is not None:
                self.assertGreater(bottom, below_top - TOLERANCE, 'cube%d in the one below' % k)
            below_top = max(p[2] for p in points)

    def test_each_pair_carries_the_weight_of_what_rests_on_it(self):
        last = range(STEPS - AVERAGED + 1, STEPS + 1)
        deadline = rospy.Time.now() + rospy.Duration(10.0)
        while any(s not in self.contacts for s in last) and rospy.Time.now() < deadline:
            rospy.sleep(0.05)
        self.assertEqual([s for s in last if s not in self.contacts], [])
        ticks = [{(p.body, p.other): p for p in self.contacts[s].pairs} for s in last]

        def mean_z(key):
            return sum(pairs[key].force.z for pairs in ticks) / len(ticks)
        pairs = ticks[-1]
        floor = pairs[('cube0', 'floor')]
        self.assertEqual(floor.kind, ContactPair.OBSTACLE)
        self.assertAlmostEqual(mean_z(('cube0', 'floor')), CUBES * WEIGHT,
                               delta=0.02 * CUBES * WEIGHT)
        for k in range(1, CUBES):
            above = pairs[('cube%d' % k, 'cube%d' % (k - 1))]
            below = pairs[('cube%d' % (k - 1), 'cube%d' % k)]
            carried = (CUBES - k) * WEIGHT
            self.assertEqual(above.kind, ContactPair.BODY)
            self.assertAlmostEqual(mean_z(('cube%d' % k, 'cube%d' % (k - 1))), carried,
                                   delta=0.02 * carried, msg='cube%d' % k)
            self.assertAlmostEqual(below.force.z, -above.force.z, delta=1e-9 * carried)
            self.assertLessEqual(above.depth, TOLERANCE)
            self.assertEqual(below.depth, above.depth)
            self.assertGreaterEqual(above.penetration, 0.0)
            self.assertGreater(above.points, 0)
        for pair in self.contacts[STEPS].pairs:  # nothing else touches: no cube reaches two below
            self.assertIn((pair.body, pair.other),
                          [('cube0', 'floor')] +
                          [('cube%d' % k, 'cube%d' % (k + d)) for k in range(CUBES) for d in (-1, 1)])


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'stack', Stack)
