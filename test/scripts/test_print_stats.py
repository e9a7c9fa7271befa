#!/usr/bin/python3
"""scripts/print_stats's line, from stand-ins for deformable_sim/Stats and deformable_sim/Contacts
(no ROS): the real-time factor, and per body how many pairs touch it and at how many points."""
import importlib.machinery
import importlib.util
import os
import sys
import unittest
from types import SimpleNamespace

import rosunit

SCRIPT = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                      'scripts', 'print_stats')


def load_print_stats():
    loader = importlib.machinery.SourceFileLoader('print_stats', SCRIPT)
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader(loader.name, loader))
    loader.exec_module(module)
    return module


print_stats = load_print_stats()


def body(name, **fields):
    values = dict(body=name, solver_iterations=12, solver_residual=3e-6, kinetic_energy=1e-3,
                  elastic_energy=2e-2, fixed_nodes=0, applied_wrenches=0, inverted_elements=0)
    values.update(fields)
    return SimpleNamespace(**values)


def stats(*bodies, **fields):
    values = dict(step=120, sim_time=1.2, real_time_factor=0.97, step_time=0.0042, paused=False,
                  dropped_messages=0, last_refusal='', bodies=list(bodies))
    values.update(fields)
    return SimpleNamespace(**values)


def pair(body_name, other, points):
    return SimpleNamespace(body=body_name, other=other, points=points)


def contacts(*pairs):
    return SimpleNamespace(pairs=list(pairs))


def part_of(line, name):
    """The text of one body in the line."""
    return next(p for p in line.split('  | ')[1:] if p.startswith(name + ':'))


class PrintStatsLine(unittest.TestCase):
    def test_real_time_factor_step_and_wall_time(self):
        line = print_stats.line(stats(body('beam')))
        self.assertRegex(line, r'^step +120  t +1\.20 s  real-time factor +0\.97  step +4\.20 ms  \| ')

    def test_contact_pairs_and_points_per_body(self):
        touching = contacts(pair('block', 'table', 9), pair('block', 'left_finger', 4),
                            pair('sponge', 'block', 1), pair('block', 'sponge', 2))
        line = print_stats.line(stats(body('block'), body('sponge'), body('beam')), touching)
        self.assertIn('contact 3 pairs at 15 points', part_of(line, 'block'))
        self.assertIn('contact 1 pair at 1 point', part_of(line, 'sponge'))
        self.assertNotIn('contact', part_of(line, 'beam'))

    def test_no_contacts_message_yet_or_none_touching(self):
        for message in (None, contacts()):
            line = print_stats.line(stats(body('beam', applied_wrenches=2)), message)
            self.assertNotIn('contact', line)
            self.assertIn('2 wrenches', line)

    def test_pairs_of_a_body_not_in_the_stats_are_left_out(self):
        line = print_stats.line(stats(body('beam')), contacts(pair('gone', 'floor', 3)))
        self.assertNotIn('gone', line)
        self.assertNotIn('contact', line)

    def test_paused_and_refusals(self):
        line = print_stats.line(stats(body('beam'), paused=True, dropped_messages=2,
                                      last_refusal='~wrench: force 1e3 N above 49 N'))
        self.assertIn('(paused)', line)
        self.assertIn('dropped 2 (last: ~wrench: force 1e3 N above 49 N)', line)


if __name__ == '__main__':
    rosunit.unitrun('deformable_sim', 'test_print_stats', PrintStatsLine, sysargs=sys.argv)
