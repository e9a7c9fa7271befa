#!/usr/bin/python3
"""Five soft cubes stacked on a floor, through the node (config/scenes/stack.yaml): stepped five
seconds, they stand where they were put, none sinks into the one below by more than the contact's
tolerance, and ~contacts gives each pair the weight of what rests on it."""
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


class Stack(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_stack')
        cls.sim = SimClient()
        cls.contacts = None
        rospy.Subscriber('/deformable_sim/contacts', Contacts, cls.on_contacts, queue_size=10)
        response = cls.sim.step(STEPS)
        assert response.success and response.step == STEPS, response

    @classmethod
    def on_contacts(cls, message):
        cls.contacts = message

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
        deadline = rospy.Time.now() + rospy.Duration(10.0)
        while (self.contacts is None or self.contacts.step != STEPS) and rospy.Time.now() < deadline:
            rospy.sleep(0.05)
        self.assertEqual(self.contacts.step, STEPS)
        pairs = {(p.body, p.other): p for p in self.contacts.pairs}
        floor = pairs[('cube0', 'floor')]
        self.assertEqual(floor.kind, ContactPair.OBSTACLE)
        self.assertAlmostEqual(floor.force.z, CUBES * WEIGHT, delta=0.02 * CUBES * WEIGHT)
        for k in range(1, CUBES):
            above = pairs[('cube%d' % k, 'cube%d' % (k - 1))]
            below = pairs[('cube%d' % (k - 1), 'cube%d' % k)]
            carried = (CUBES - k) * WEIGHT
            self.assertEqual(above.kind, ContactPair.BODY)
            self.assertAlmostEqual(above.force.z, carried, delta=0.02 * carried, msg='cube%d' % k)
            self.assertAlmostEqual(below.force.z, -above.force.z, delta=1e-9 * carried)
            self.assertLessEqual(above.penetration, TOLERANCE)
            self.assertGreater(above.points, 0)
        for pair in self.contacts.pairs:  # nothing else touches: no cube reaches two below
            self.assertIn((pair.body, pair.other),
                          [('cube0', 'floor')] +
                          [('cube%d' % k, 'cube%d' % (k + d)) for k in range(CUBES) for d in (-1, 1)])


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'stack', Stack)
