#!/usr/bin/python3
"""The reference session (test/data/reference/session.bag, recorded by the node on session.yaml)
re-simulates bit for bit with this build: a change meant to keep behaviour (a move, a refactor)
must keep every recorded state to the last bit. The bag holds every kind of command, a rigid body
beside finite-element ones, obstacle contact with friction and contact between bodies. No roscore:
deformable_sim_replay reads the bag.

  test_reference_bag.py --bin-dir DEVEL/lib/deformable_sim
"""
import argparse
import os
import re
import subprocess
import sys
import unittest

import rosbag
import rosunit

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BAG = os.path.join(SOURCE, 'test', 'data', 'reference', 'session.bag')
NODE = '/deformable_sim'
BIN_DIR = None  # set by main: where the C++ executables were built


class ReferenceBag(unittest.TestCase):
    def test_the_session_holds_what_it_was_recorded_to_exercise(self):
        kinds = set()
        with rosbag.Bag(BAG) as bag:
            topics = [NODE + '/scene', NODE + '/applied']
            for topic, message, _ in bag.read_messages(topics=topics):
                if topic.endswith('/applied'):
                    kinds.add(message.kind)
                else:
                    scene = message.yaml
        # WRENCH, CLEAR_WRENCH, FIX, RELEASE, GRASP, RELEASE_GRASP, MOVE_GRASP, OBSTACLES, TUNE,
        # RESET: Applied's kinds 0 to 9.
        self.assertEqual(kinds, set(range(10)))
        for key in ('model: rigid', 'friction: 0.5', 'bodies: true', 'obstacles:'):
            self.assertIn(key, scene)

    def test_the_session_re_simulates_bit_for_bit(self):
        # One thread, as the node ran: any count gives the same bits, one is quickest when the
        # machine is busy.
        replay = os.path.join(BIN_DIR, 'deformable_sim_replay')
        result = subprocess.run([replay, BAG, '--quiet', '--threads', '1'], capture_output=True,
                                text=True, timeout=300)
        self.assertEqual(result.returncode, 0, result.stderr)
        match = re.search(r'compared (\d+) recorded states: largest difference (\S+) m in '
                          r'position, (\S+) m/s in velocity \(bit-exact\)', result.stdout)
        self.assertIsNotNone(match, result.stdout)
        self.assertGreater(int(match.group(1)), 1200)  # 3 bodies, 420 steps
        self.assertEqual(float(match.group(2)), 0.0)
        self.assertEqual(float(match.group(3)), 0.0)


def main():
    global BIN_DIR
    parser = argparse.ArgumentParser()
    parser.add_argument('--bin-dir', required=True)
    arguments, rest = parser.parse_known_args()
    BIN_DIR = arguments.bin_dir
    rosunit.unitrun('deformable_sim', 'reference_bag', ReferenceBag, sysargs=[sys.argv[0]] + rest)


if __name__ == '__main__':
    main()
