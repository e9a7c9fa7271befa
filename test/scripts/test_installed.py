#!/usr/bin/python3
"""The package as `catkin_make install` lays it out: this build installed (cmake --install) into a
folder of its own, every installed program answers --help (it starts: its libraries are
installed too), and deformable_sim_identify's plot script lies beside it and draws a chart.

  test_installed.py --build-dir CATKIN_BUILD_DIR
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import rosunit

BUILD_DIR = None  # set by main


class Installed(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.prefix = tempfile.mkdtemp(prefix='deformable_sim_install_')
        install = subprocess.run(['cmake', '--install', BUILD_DIR, '--prefix', cls.prefix],
                                 capture_output=True, text=True, timeout=300)
        assert install.returncode == 0, install.stdout + install.stderr
        cls.bin = os.path.join(cls.prefix, 'lib', 'deformable_sim')

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.prefix, ignore_errors=True)

    def run_installed(self, *command):
        environment = dict(os.environ)
        # Only the installed libraries, not the build's (LD_LIBRARY_PATH of the devel space).
        environment['LD_LIBRARY_PATH'] = os.path.join(self.prefix, 'lib')
        return subprocess.run(command, capture_output=True, text=True, timeout=60,
                              env=environment)

    def test_every_installed_program_starts(self):
        programs = ['deformable_sim_node', 'deformable_sim_run', 'deformable_sim_mesh',
                    'deformable_sim_replay', 'deformable_sim_identify', 'deformable_sim_bench',
                    'deformable_sim_perf']
        for program in programs:
            with self.subTest(program=program):
                path = os.path.join(self.bin, program)
                self.assertTrue(os.path.exists(path), path + ' not installed')
                run = self.run_installed(path, '--help')
                self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
                self.assertNotIn('error while loading shared libraries', run.stderr)

    def test_identify_finds_its_plot_script_beside_it_and_it_draws(self):
        script = os.path.join(self.bin, 'plot_identify.py')
        self.assertTrue(os.path.exists(script), 'plot_identify.py is not installed beside '
                        'deformable_sim_identify')
        table = os.path.join(self.prefix, 'fit.png.csv')
        with open(table, 'w') as f:
            f.write('observation,component,time,measured,guess,fitted\n')
            for k in range(20):
                t = 0.01 * k
                f.write('marker,z,%g,%g,%g,%g\n' % (t, 0.001 * k, 0.002 * k, 0.001 * k))
        chart = os.path.join(self.prefix, 'fit.png')
        run = self.run_installed('/usr/bin/python3', script, table, chart)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertGreater(os.path.getsize(chart), 5000)


if __name__ == '__main__':
    parser = argparse.ArgumentParser()
    parser.add_argument('--build-dir', required=True)
    arguments, rest = parser.parse_known_args()
    BUILD_DIR = arguments.build_dir
    rosunit.unitrun('deformable_sim', 'test_installed', Installed, sysargs=[sys.argv[0]] + rest)
