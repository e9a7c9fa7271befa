#!/usr/bin/python3
"""The node refuses to start on a scene with an error: it exits non-zero and the message names the
key; likewise for a bad parameter."""
import os
import subprocess
import unittest

import rospkg
import rostest

SCENES = os.path.join(rospkg.RosPack().get_path('deformable_sim'), 'test', 'data', 'scenes')


def start_node(*arguments):
    return subprocess.run(['rosrun', 'deformable_sim', 'deformable_sim_node', *arguments],
                          capture_output=True, text=True, timeout=60)


class BadScene(unittest.TestCase):
    def test_bad_material_names_the_key(self):
        run = start_node('_scene:=' + os.path.join(SCENES, 'bad_material.yaml'), '__name:=bad_material')
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn('bad_material.yaml:5: bodies[0].material.poisson_ratio: must be in (-1, 0.5)',
                      run.stderr)

    def test_missing_mesh_file_names_the_scene_line_and_key(self):
        run = start_node('_scene:=' + os.path.join(SCENES, 'missing_mesh.yaml'), '__name:=missing_mesh')
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn('missing_mesh.yaml:4: bodies[0].mesh: cannot open mesh file', run.stderr)

    def test_group_that_selects_nothing_names_the_scene_line_and_key(self):
        run = start_node('_scene:=' + os.path.join(SCENES, 'empty_group.yaml'), '__name:=empty_group')
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn('empty_group.yaml:8: bodies[0].groups.nowhere: selects no node', run.stderr)

    def test_bodies_started_inside_each_other_are_refused_with_both_names_and_the_depth(self):
        run = start_node('_scene:=' + os.path.join(SCENES, 'tubes_inside_each_other.yaml'),
                         '__name:=tubes_inside')
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertRegex(run.stderr, r"tubes_inside_each_other.yaml:[0-9]+: bodies\[1\]: body "
                         r"'tube_b' starts [0-9.]+ mm inside body 'tube_a'; bodies may start at "
                         r"most 1.3 mm into each other")

    def test_missing_scene_file(self):
        run = start_node('_scene:=/nonexistent/scene.yaml', '__name:=missing_scene')
        self.assertEqual(run.returncode, 1)
        self.assertIn('/nonexistent/scene.yaml: cannot open the scene file', run.stderr)

    def test_bad_rate(self):
        run = start_node('_rate:=-5.0', '__name:=bad_rate')
        self.assertEqual(run.returncode, 1)
        self.assertIn('~rate: must be finite and > 0 Hz', run.stderr)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'bad_scene', BadScene)
