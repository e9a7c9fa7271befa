#!/usr/bin/python3
"""scripts/print_stats's line, from stand-ins for deformable_sim/Stats and deformable_sim/Contacts
(no ROS): the real-time factor, and per body how many pairs touch it and at how many points; and
its summary of whether a node kept real time over a span of messages."""
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


class PrintStatsSummary(unittest.TestCase):
    @staticmethod
    def run_span(samples):
        """samples: (stamp, sim_time, step_time[, paused]) per message."""
        keeping = print_stats.KeepingTime()
        for sample in samples:
            paused = sample[3] if len(sample) > 3 else False
            keeping.add(sample[0], stats(sim_time=sample[1], step_time=sample[2], paused=paused))
        return keeping

    def test_simulated_time_per_second_over_the_span_and_tick_times(self):
        # 11 messages 0.1 s apart; the simulation falls 0.02 s behind over the second.
        samples = [(10.0 + 0.1 * k, 3.0 + 0.098 * k, 0.001 * (k + 1)) for k in range(11)]
        text = self.run_span(samples).text()
        self.assertIn('over 1.0 s: simulated 0.980 s, real-time factor 0.9800', text)
        self.assertIn('6.00 ms (median of 11 sampled), 10.00 ms (90th percentile), '
                      '11.00 ms (longest sampled)', text)

    def test_a_reset_or_a_pause_starts_the_span_again(self):
        before = [(1.0, 5.0, 0.1), (2.0, 6.0, 0.1)]
        reset = [(3.0, 0.0, 0.002), (4.0, 0.5, 0.002)]  # sim time back to 0: counted from here
        self.assertIn('real-time factor 0.5000', self.run_span(before + reset).text())
        paused = [(3.0, 7.0, 0.0, True), (4.0, 7.0, 0.004), (5.0, 8.0, 0.004)]
        self.assertIn('over 1.0 s: simulated 1.000 s', self.run_span(before + paused).text())

    def test_a_span_must_be_positive(self):
        self.assertEqual(print_stats.parse_arguments(['--summary', '30']).summary, 30.0)
        with self.assertRaises(SystemExit):
            print_stats.parse_arguments(['--summary', '0'])

    def test_no_span_yet(self):
        self.assertIn('no span yet', print_stats.KeepingTime().text())
        self.assertIn('no span yet', self.run_span([(1.0, 1.0, 0.01)]).text())


if __name__ == '__main__':
    rosunit.unitrun('deformable_sim', 'test_print_stats', __name__, sysargs=sys.argv)
