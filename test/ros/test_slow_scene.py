#!/usr/bin/python3
"""A node that cannot keep real time says so: once its real-time factor has stayed under 0.9 for
5 s of wall time, a warning on /rosout gives the step time and its costliest part, /diagnostics
goes WARN with the same, and ~stats splits each body's step time (elasticity, solve, contact)."""
import re
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rosgraph_msgs.msg import Log

from deformable_sim.msg import Stats

# A part of a step against the whole: the wall time, or the work summed over bodies that step
# side by side when that is more.
PART = (r'(elasticity|linear solves|contact with obstacles|contact between bodies) '
        r'([0-9.e+-]+) of ([0-9.e+-]+) ms (of work )?a step')


def check_part(test, message):
    """The costliest part is named and never more than its whole."""
    match = re.search(PART, message)
    test.assertIsNotNone(match, message)
    test.assertLessEqual(float(match.group(2)), float(match.group(3)), message)


class SlowScene(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_slow_scene')
        cls.lock = threading.Lock()
        cls.warnings = []      # (wall time, text) of the node's slow-tick warnings
        cls.diagnostics = []
        cls.stats = None
        rospy.Subscriber('/rosout', Log, cls.on_log, queue_size=1000)
        rospy.Subscriber('/diagnostics', DiagnosticArray, cls.on_diagnostics, queue_size=100)
        rospy.Subscriber('/deformable_sim/stats', Stats, cls.on_stats, queue_size=100)
        deadline = time.time() + 60.0
        while time.time() < deadline and not (cls.warnings and cls.slow_diagnostics()):
            time.sleep(0.1)

    @classmethod
    def on_log(cls, message):
        if message.name == '/deformable_sim' and 'slower than real time' in message.msg:
            with cls.lock:
                cls.warnings.append((time.time(), message))

    @classmethod
    def on_diagnostics(cls, message):
        with cls.lock:
            cls.diagnostics += [s for s in message.status if s.name.endswith('simulation')]

    @classmethod
    def on_stats(cls, message):
        with cls.lock:
            cls.stats = message

    @classmethod
    def slow_diagnostics(cls):
        with cls.lock:
            return [s for s in cls.diagnostics if s.level == DiagnosticStatus.WARN]

    def test_a_warning_names_the_step_time_and_its_costliest_part(self):
        self.assertTrue(self.warnings, 'no warning on /rosout within 60 s')
        _, log = self.warnings[0]
        self.assertEqual(log.level, Log.WARN)
        self.assertRegex(log.msg, r'slower than real time for [0-9]+ s \([0-9.e+-]+ x real time\): '
                         + PART)
        check_part(self, log.msg)
        factor = float(re.search(r'\(([0-9.e+-]+) x', log.msg).group(1))
        self.assertLess(factor, 0.9)
        # Not at the first slow tick: after 5 s of them (core/driver/slow_tick_watch.h). The span
        # is the node's own: when this test's subscriptions connected is not when stepping began.
        slow_for = float(re.search(r'for ([0-9]+) s', log.msg).group(1))
        self.assertGreaterEqual(slow_for, 5.0)

    def test_diagnostics_go_warn_with_the_costliest_part(self):
        slow = self.slow_diagnostics()
        self.assertTrue(slow, 'no WARN on /diagnostics within 60 s')
        self.assertRegex(slow[-1].message, r'cannot keep real time \([0-9.e+-]+ x real time\): '
                         + PART)
        check_part(self, slow[-1].message)

    def test_stats_split_each_bodys_step_time(self):
        with self.lock:
            stats = self.stats
        self.assertEqual(len(stats.bodies), 5)
        self.assertLess(stats.real_time_factor, 0.9)
        for body in stats.bodies:
            parts = (body.elasticity_time, body.solve_time, body.contact_time)
            self.assertTrue(all(p > 0.0 for p in parts), (body.body, parts))
            # One step of the body, within the tick's 20 steps.
            self.assertLess(sum(parts), stats.step_time, body.body)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'slow_scene', SlowScene)
