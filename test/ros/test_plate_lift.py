#!/usr/bin/python3
"""[one-contact]: a plate link pressed 3 mm on a foam cube and lifted away carried the cube off the
table (its lowest node 17.6 mm up for 0.87 s, the plate's wrench reading zero). Here the plate is
a robot link posed only through tf, broadcast at 50 Hz as a robot's would be, over four nodes that
tick at 100 Hz (plates wider and narrower than the 6 cm cube, friction 0.5 and 1.0): it presses
3 mm, lifts 10 cm in 2 s (cosine ramp), comes back, presses again and lifts 2 cm in 0.05 s. Once
a lift starts the cube's lowest node stays within 1 mm of the table; the table never pulls on it,
nor does a wide plate (its flat face only pushes: every contact's normal impulse is >= 0 by
construction, tests of core/contact). A narrow plate sinks its edges into the foam, and friction on
them may drag the top up a little as it leaves: it stays far below the cube's weight."""
import math
import threading
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import TransformStamped

from deformable_sim.msg import BodyState, Contacts

NODES = ['wide_05', 'wide_10', 'narrow_05', 'narrow_10']
TOP = 0.06  # m: the cube's top face at rest
PRESSED = TOP - 0.003
# (start s, end s, height at the start, height at the end) of the plate's underside: cosine ramps.
PLAN = [(0.0, 1.5, TOP + 0.005, TOP + 0.005),  # the cube settles
        (1.5, 2.5, TOP + 0.005, PRESSED),       # pressed 3 mm
        (2.5, 3.5, PRESSED, PRESSED),
        (3.5, 5.5, PRESSED, PRESSED + 0.10),    # lifted slowly: 10 cm in 2 s
        (5.5, 6.0, PRESSED + 0.10, PRESSED + 0.10),
        (6.0, 7.5, PRESSED + 0.10, PRESSED),    # back down, pressed again
        (7.5, 8.5, PRESSED, PRESSED),
        (8.5, 8.55, PRESSED, PRESSED + 0.02),   # lifted fast: 2 cm in 0.05 s
        (8.55, 10.0, PRESSED + 0.02, PRESSED + 0.02)]
LIFTS = [(3.5, 6.0), (8.5, 10.0)]  # s: from each lift's start until the plate comes back
HOLDS = [(3.0, 3.5), (8.0, 8.5)]   # s: pressed, still
TOLERANCE = 1e-9  # N: a force the contact calls pushing may be round-off the other way
WEIGHT = 0.06 ** 3 * 150.0 * 9.81  # N: the cube's


def plate_height(t):
    for start, end, low, high in PLAN:
        if t <= end:
            s = min(max((t - start) / (end - start), 0.0), 1.0)
            return low + (high - low) * (0.5 - 0.5 * math.cos(math.pi * s))
    return PLAN[-1][3]


class Watch:
    """What one node reports: its cube's lowest node and the forces of the plate and the table,
    each with the plan's time it belongs to (the tick's stamp less the node's link delay)."""

    def __init__(self, name, start, delay):
        self.start, self.delay = start, delay
        self.lowest, self.plate, self.table = [], [], []
        rospy.Subscriber('/%s/deformable_sim/state' % name, BodyState, self.on_state, queue_size=100)
        rospy.Subscriber('/%s/deformable_sim/contacts' % name, Contacts, self.on_contacts,
                         queue_size=100)

    def when(self, header):
        return (header.stamp - self.start).to_sec() - self.delay

    def on_state(self, m):
        self.lowest.append((self.when(m.header), min(p.z for p in m.positions)))

    def on_contacts(self, m):
        t = self.when(m.header)
        forces = {pair.other: pair.force.z for pair in m.pairs if pair.body == 'cube'}
        self.plate.append((t, forces.get('plate', 0.0)))
        self.table.append((t, forces.get('table', 0.0)))


def within(samples, spans):
    return [value for t, value in samples if any(a <= t <= b for a, b in spans)]


class PlateLift(unittest.TestCase):
    def test_a_plate_lifted_away_leaves_the_cube_on_the_table(self):
        rospy.init_node('test_plate_lift')
        broadcaster = tf2_ros.TransformBroadcaster()
        start = rospy.Time.now()
        delay = rospy.get_param('/wide_05/deformable_sim/link_delay', 0.05)
        watches = {name: Watch(name, start, delay) for name in NODES}
        plate = TransformStamped()
        plate.header.frame_id, plate.child_frame_id = 'world', 'plate'
        plate.transform.rotation.w = 1.0
        rate = rospy.Rate(50)
        while not rospy.is_shutdown():
            now = rospy.Time.now()
            t = (now - start).to_sec()
            if t > PLAN[-1][1] + 0.5:
                break
            plate.header.stamp = now
            plate.transform.translation.z = plate_height(t)
            broadcaster.sendTransform(plate)
            rate.sleep()
        for name, watch in watches.items():
            pressed = within(watch.plate, HOLDS)
            self.assertGreater(len(pressed), 10, name)  # of ~100 ticks, on a busy machine
            self.assertLess(max(pressed), -0.1, '%s: the plate did not press the cube' % name)
            lowest = within(watch.lowest, LIFTS)
            self.assertGreater(len(lowest), 40, name)
            self.assertLess(max(lowest), 0.001, '%s: the cube rose %.1f mm off the table'
                            % (name, 1000 * max(lowest)))
            self.assertGreater(min(lowest), -0.001, name)
            plate_forces = [f for _, f in watch.plate]
            table_forces = [f for _, f in watch.table]
            pull = WEIGHT / 10 if name.startswith('narrow') else TOLERANCE
            self.assertLessEqual(max(plate_forces), pull, '%s: the plate pulled up' % name)
            self.assertGreaterEqual(min(table_forces), -TOLERANCE, '%s: the table pulled' % name)
            print('%s: lowest node during the lifts %.3f mm; plate pressed with %.2f N, pulled '
                  'with at most %.2g N' % (name, 1000 * max(lowest), -min(pressed), max(plate_forces)))


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'plate_lift', PlateLift)
