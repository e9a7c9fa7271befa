#!/usr/bin/python3
"""A scene with a mesh obstacle (an STL table, tilted): the node accepts it, the block dropped on it
comes to rest on its top with no node inside, and the recorded session holds the table's triangles
once (in ~scene), names them by id in every OBSTACLES command, and re-simulates bit for bit
without the STL file."""
import os
import re
import shutil
import signal
import subprocess
import tempfile
import time
import unittest
import xmlrpc.client

import numpy as np
import rosbag
import rosgraph
import rospy
import rostest

from deformable_sim.msg import Applied, Obstacle
from sim_client import SimClient, positions

NODE = '/deformable_sim'
TOPICS = [NODE + '/scene', NODE + '/applied', NODE + '/state']
SURFACE_TOLERANCE = 1e-9  # m: README, "Obstacles"
TILT = 0.2  # rad about x, as in block_on_mesh_table.yaml


class MeshObstacles(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_mesh_obstacles')
        cls.folder = tempfile.mkdtemp()
        cls.bag = os.path.join(cls.folder, 'session.bag')
        cls.sim = SimClient()
        recorder = subprocess.Popen(['rosbag', 'record', '-O', cls.bag] + TOPICS,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                    start_new_session=True)
        node = xmlrpc.client.ServerProxy(rosgraph.Master('/test_mesh_obstacles').lookupNode(NODE))
        deadline = time.time() + 20.0
        while time.time() < deadline:
            connections = node.getBusInfo('/test_mesh_obstacles')[2]
            if all(t in {c[4] for c in connections if c[2] == 'o' and 'record' in c[1]}
                   for t in TOPICS):
                break
            time.sleep(0.1)
        cls.sim.reset()
        cls.states = []
        for _ in range(20):  # 2 s in steps of 0.1 s
            answer = cls.sim.step(10)
            assert answer.success, answer.message
            cls.states.append(cls.sim.state_at(answer.step))
        cls.stats = cls.sim.wait('stats')
        time.sleep(1.0)  # the last messages reach the recorder
        os.killpg(recorder.pid, signal.SIGINT)  # rosbag and its recorder: the bag is closed
        recorder.wait(timeout=30)
        deadline = time.time() + 10.0  # the recorder renames session.bag.active when it is done
        while not os.path.exists(cls.bag) and time.time() < deadline:
            time.sleep(0.1)
        assert os.path.exists(cls.bag), 'rosbag record wrote no bag'

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder, ignore_errors=True)

    def heights(self, state):
        """Each node's height above the table's top face (negative: inside)."""
        normal = np.array([0.0, -np.sin(TILT), np.cos(TILT)])
        top = np.array([0.0, 0.0, -0.05]) + 0.05 * normal
        return (np.array(positions(state)) - top) @ normal

    def test_the_block_comes_to_rest_on_the_mesh_table(self):
        for state in self.states:
            h = self.heights(state)
            self.assertGreater(h.min(), -SURFACE_TOLERANCE, 'a node is %.3g m inside' % -h.min())
        last = self.states[-1]
        self.assertLess(self.heights(last).min(), 1e-6, 'the block never reached the table')
        self.assertLess(max(abs(c) for v in last.velocities for c in (v.x, v.y, v.z)), 1e-2)
        self.assertGreaterEqual(self.stats.bodies[0].contacts, 9)

    def test_the_bag_holds_the_triangles_once_and_re_simulates_bit_for_bit(self):
        obstacle_commands = 0
        with rosbag.Bag(self.bag) as bag:
            scenes = [m for _, m, _ in bag.read_messages(topics=[NODE + '/scene'])]
            for _, m, _ in bag.read_messages(topics=[NODE + '/applied']):
                self.assertEqual(len(m.meshes), 0, 'a command repeats triangles of ~scene')
                if m.kind == Applied.OBSTACLES:
                    obstacle_commands += 1
                    self.assertEqual([(o.shape, o.mesh_id) for o in m.obstacles],
                                     [(Obstacle.MESH, 'obstacles[0]')])
        self.assertGreaterEqual(obstacle_commands, 1)
        self.assertEqual(len(scenes), 1)
        meshes = scenes[0].obstacle_meshes
        self.assertEqual([m.id for m in meshes], ['obstacles[0]'])
        self.assertEqual((len(meshes[0].vertices), len(meshes[0].triangles)), (8 * 3, 12 * 3))
        # The replay takes the table's triangles from the bag, not from the STL file.
        result = subprocess.run(['rosrun', 'deformable_sim', 'deformable_sim_replay', '--quiet',
                                 self.bag], capture_output=True, text=True, timeout=120,
                                cwd=self.folder)
        self.assertEqual(result.returncode, 0, result.stderr)
        match = re.search(r'compared (\d+) recorded states: largest difference (\S+) m in position, '
                          r'(\S+) m/s in velocity \(bit-exact\)', result.stdout)
        self.assertIsNotNone(match, result.stdout)
        self.assertGreaterEqual(int(match.group(1)), 20)
        self.assertEqual(float(match.group(2)), 0.0)
        self.assertEqual(float(match.group(3)), 0.0)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'mesh_obstacles', MeshObstacles)
