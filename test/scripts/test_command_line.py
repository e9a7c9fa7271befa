#!/usr/bin/python3
"""What a user sees first: every executable of CMakeLists.txt and every script of scripts/ answers
--help and -h with its usage and exit status 0, without a ROS master (one that would be reached
hangs or fails here), ROS remapping arguments or not; and deformable_sim_node --help names the
topics, services and parameters README.md's tables list, and no others.

  test_command_line.py --bin-dir DEVEL/lib/deformable_sim [--text]
"""
import argparse
import os
import re
import signal
import subprocess
import sys
import tempfile
import unittest

import rosunit

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TIMEOUT_S = 20.0  # a program that waits for a master, or does its work, takes longer
BIN_DIR = None  # set by main: where the C++ executables were built


def executables():
    """The names of CMakeLists.txt's add_executable targets."""
    with open(os.path.join(SOURCE, 'CMakeLists.txt')) as cmake:
        return re.findall(r'^\s*add_executable\((\w+)', cmake.read(), re.MULTILINE)


def scripts():
    """The executable files of scripts/."""
    folder = os.path.join(SOURCE, 'scripts')
    return sorted(os.path.join(folder, name) for name in os.listdir(folder)
                  if os.access(os.path.join(folder, name), os.X_OK))


def uses_ros(path):
    with open(path) as script:
        return 'rospy' in script.read()


def run(command):
    """(exit status, stdout, stderr) of the command, with no reachable ROS master; status None
    when it did not finish in TIMEOUT_S (then it is stopped, with whatever it started)."""
    with tempfile.TemporaryDirectory() as home:
        environment = dict(os.environ, ROS_MASTER_URI='http://127.0.0.1:9/', ROS_HOME=home,
                           ROS_LOG_DIR=home)
        process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True, env=environment,
                                   start_new_session=True)
        try:
            out, err = process.communicate(timeout=TIMEOUT_S)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            out, err = process.communicate()
            return None, out, err
    return process.returncode, out, err


def node_help():
    status, out, err = run([os.path.join(BIN_DIR, 'deformable_sim_node'), '--help'])
    assert status == 0, 'deformable_sim_node --help: exit status %s\n%s' % (status, err)
    return out


def readme_names():
    """{`~name` or `/name`} in the first column of README.md's topic, service and parameter
    tables."""
    names = set()
    header = re.compile(r'^\|\s*(topic|service|parameter|topic / service)\s*\|')
    in_table = False
    with open(os.path.join(SOURCE, 'README.md')) as readme:
        for row in readme:
            if header.match(row):
                in_table = True
            elif not row.startswith('|'):
                in_table = False
            elif in_table:
                first = row.split('|')[1]
                names.update(re.findall(r'`([~/][^`\s]*)`', first))
    return names


def help_names(text):
    """The `~name` and `/name` words of a usage text (not the `/` inside `1/rate`)."""
    return set(re.findall(r'(?<![\w.)])[~/][\w/<>]+', text))


def problem(command):
    """What is wrong with the command's answer to --help, or None."""
    status, out, err = run(command)
    shown = ' '.join(os.path.basename(c) if c.startswith('/') else c for c in command)
    if status is None:
        return '%s: still running after %g s (waits for ROS, or does its work?)\n%s%s' % (
            shown, TIMEOUT_S, out, err)
    if status != 0:
        return '%s: exit status %d\n%s%s' % (shown, status, out, err)
    if 'usage' not in out.lower():
        return '%s: no usage on stdout\n%s%s' % (shown, out, err)
    return None


class EveryProgramAnswersHelp(unittest.TestCase):
    def expect_help(self, commands):
        problems = [p for p in (problem(c) for c in commands) if p]
        if problems:
            self.fail('\n'.join(problems))

    def test_executables(self):
        names = executables()
        self.assertIn('deformable_sim_node', names)
        self.expect_help([[os.path.join(BIN_DIR, name), flag]
                          for name in names for flag in ('--help', '-h')])

    def test_scripts(self):
        self.assertIn('print_stats', [os.path.basename(p) for p in scripts()])
        self.expect_help([[path, flag] for path in scripts() for flag in ('--help', '-h')])

    def test_remapping_arguments_are_left_to_ros(self):
        ros_programs = [p for p in scripts() if uses_ros(p)]
        self.assertGreaterEqual(len(ros_programs), 3)
        ros_programs.append(os.path.join(BIN_DIR, 'deformable_sim_node'))
        self.expect_help([[path, '__name:=renamed', '_rate:=5', 'x:=y', '--help']
                          for path in ros_programs])


class NodeHelpMatchesReadme(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.help = node_help()
        cls.help_names = help_names(cls.help)
        cls.readme_names = readme_names()

    def test_readme_tables_were_found(self):
        for name in ('~wrench', '~stats', '~reset', '~scene', '/tf'):
            self.assertIn(name, self.readme_names)

    def test_help_names_every_readme_topic_service_and_parameter(self):
        missing = sorted(self.readme_names - self.help_names)
        self.assertEqual(missing, [], 'in README.md, not in deformable_sim_node --help:\n'
                         + self.help)

    def test_readme_lists_everything_help_names(self):
        missing = sorted(self.help_names - self.readme_names)
        self.assertEqual(missing, [], 'in deformable_sim_node --help, not in README.md')

    def test_help_names_every_parameter_the_node_reads(self):
        with open(os.path.join(SOURCE, 'src', 'ros', 'node_parameters.cpp')) as code:
            read = set('~' + p for p in re.findall(r'\bparam\(node, "(\w+)"', code.read()))
        self.assertIn('~scene', read)
        self.assertEqual(sorted(read - self.help_names), [])


def main():
    global BIN_DIR
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--bin-dir', required=True, help='where the C++ executables are')
    arguments, rest = parser.parse_known_args()
    BIN_DIR = arguments.bin_dir
    rosunit.unitrun('deformable_sim', 'test_command_line', __name__, sysargs=[sys.argv[0]] + rest)


if __name__ == '__main__':
    main()
