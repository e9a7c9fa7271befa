#!/usr/bin/python3
"""The node refuses to start on a scene with an error: it exits non-zero and the message names the
key; likewise for a bad parameter."""
import os
import signal
import subprocess
import threading
import unittest

import rospkg
import rospy
import rostest

from deformable_sim.msg import Scene

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

    def test_a_rate_left_on_the_parameter_server_is_named_with_the_dt_it_sets(self):
        """A ~rate an earlier node's live tuning left behind changes the next node's dt: the
        node says so at its start, naming the parameter and both steps."""
        rospy.set_param('/rate_left/rate', 50.0)
        node = subprocess.Popen(['rosrun', 'deformable_sim', 'deformable_sim_node',
                                 '__name:=rate_left'], stdout=subprocess.DEVNULL,
                                stderr=subprocess.PIPE, text=True, start_new_session=True)
        stop = threading.Timer(30.0, lambda: os.killpg(node.pid, signal.SIGINT))
        stop.start()
        warning = ''
        try:
            for line in node.stderr:  # warnings come on stderr, unbuffered
                if '~rate' in line:
                    warning = line
                    break
            scene = rospy.wait_for_message('/rate_left/scene', Scene, timeout=20.0)
        finally:
            stop.cancel()
            os.killpg(node.pid, signal.SIGINT)
            node.wait(timeout=30)
            rospy.delete_param('/rate_left/rate')
        self.assertIn("~rate 50 Hz on the parameter server (/rate_left/rate) sets dt 0.02 s, not "
                      "the scene's 0.01 s; a rate set by an earlier node or its live tuning stays "
                      "there until `rosparam delete /rate_left/rate`", warning)
        self.assertAlmostEqual(scene.dt, 0.02)

    def test_bad_rate(self):
        run = start_node('_rate:=-5.0', '__name:=bad_rate')
        self.assertEqual(run.returncode, 1)
        self.assertIn('~rate: must be finite and > 0 Hz', run.stderr)


if __name__ == '__main__':
    rospy.init_node('test_bad_scene')
    rostest.rosrun('deformable_sim', 'bad_scene', BadScene)
