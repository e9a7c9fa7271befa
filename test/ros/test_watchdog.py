#!/usr/bin/python3
"""A body whose steps blow up: the watchdog undoes each one, so that what the node publishes stays
finite where it was; ~stats counts the recoveries, /rosout warns naming the body, and
/diagnostics goes WARN saying the watchdog acted and why. Private parameters say which blow-up
the launch file's scene makes: ~body, ~reason (the warning's words after the step number),
~summary (the diagnostics message), ~z_range (the published nodes' lowest and highest z, m, to
~z_tolerance)."""
import re
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rosgraph_msgs.msg import Log

from sim_client import SimClient, all_finite, positions


class Watchdog(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_watchdog')
        cls.lock = threading.Lock()
        cls.warnings = []
        cls.diagnostics = []
        rospy.Subscriber('/rosout', Log, cls.on_log, queue_size=1000)
        rospy.Subscriber('/diagnostics', DiagnosticArray, cls.on_diagnostics, queue_size=100)
        cls.body = rospy.get_param('~body', 'block')
        cls.reason = rospy.get_param('~reason', 'left a non-finite value')
        cls.summary = rospy.get_param('~summary',
                                      'the watchdog undid a step that left a non-finite value')
        cls.z_range = rospy.get_param('~z_range', [0.0, 0.1])
        cls.z_tolerance = rospy.get_param('~z_tolerance', 1e-12)
        cls.sim = SimClient()
        deadline = time.time() + 30.0
        while time.time() < deadline and not (cls.warnings and cls.undone()):
            time.sleep(0.1)

    @classmethod
    def on_log(cls, message):
        if message.name == '/deformable_sim' and 'watchdog' in message.msg:
            with cls.lock:
                cls.warnings.append(message)

    @classmethod
    def on_diagnostics(cls, message):
        with cls.lock:
            cls.diagnostics += [s for s in message.status if s.name.endswith('simulation')]

    @classmethod
    def undone(cls):
        with cls.lock:
            return [s for s in cls.diagnostics if 'watchdog' in s.message]

    def test_diagnostics_say_the_watchdog_undid_a_step(self):
        undone = self.undone()
        self.assertTrue(undone, 'no /diagnostics status naming the watchdog within 30 s')
        self.assertEqual(undone[-1].level, DiagnosticStatus.WARN)
        self.assertEqual(undone[-1].message, self.summary)

    def test_a_warning_names_the_body(self):
        self.assertTrue(self.warnings, 'no watchdog warning on /rosout within 30 s')
        self.assertEqual(self.warnings[0].level, Log.WARN)
        self.assertRegex(self.warnings[0].msg,
                         r"body '%s': step [0-9]+ %s" % (self.body, re.escape(self.reason)))

    def test_what_is_published_stays_finite_where_it_started(self):
        stats = self.sim.wait('stats', lambda m: m.step > 5 and
                              sum(b.recoveries for b in m.bodies) > 0)
        self.assertGreater(sum(b.recoveries for b in stats.bodies), 0)
        state = self.sim.wait('state', lambda m: m.step > 5)
        points = positions(state)
        self.assertTrue(all_finite(points))
        # Undone, at rest: the bodies are about where the scene put them.
        self.assertAlmostEqual(min(p[2] for p in points), self.z_range[0], delta=self.z_tolerance)
        self.assertAlmostEqual(max(p[2] for p in points), self.z_range[1], delta=self.z_tolerance)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'watchdog', Watchdog)
