#!/usr/bin/python3
"""Bodies made straight from surface meshes (config/scenes/soft_objects.yaml) in the node: ~mesh
draws the user's own triangles, in the file's order, where the scene put them (not the grid the
body is simulated on); they follow the grid when the sponge is squeezed, in rviz too (the
screenshot, kept by ~screenshot, is the README's); and a recorded session re-simulates bit for bit
with the surface still drawn."""
import os
import re
import shutil
import struct
import subprocess
import tempfile
import time
import unittest

import rosbag
import rospkg
import rospy
import rostest
from visualization_msgs.msg import Marker

from deformable_sim.msg import FixedNodes
from rviz_xvfb import RvizUnderXvfb, count_pixels, is_mesh_orange
from sim_client import SimClient, connected, start_recording, stop_recording

NODE = '/deformable_sim'
CONFIG = os.path.join(rospkg.RosPack().get_path('deformable_sim'), 'config')
MESHES = os.path.join(CONFIG, 'meshes')
# The scene's placement of each surface (a pure translation for these two).
OFFSETS = {'sponge': (0.0, 0.0, 0.015), 'ball': (0.15, 0.0, 0.04)}


def stl_triangles(path):
    """The triangles of a binary STL, as three (x, y, z) corners each."""
    with open(path, 'rb') as f:
        data = f.read()
    count = struct.unpack_from('<I', data, 80)[0]
    return [[struct.unpack_from('<3f', data, 84 + 50 * t + 12 * (k + 1)) for k in range(3)]
            for t in range(count)]


class Markers:
    """The latest ~mesh marker of each body."""

    def __init__(self):
        self.latest = {}
        self.subscriber = rospy.Subscriber(NODE + '/mesh', Marker, self._on_marker, queue_size=10)

    def _on_marker(self, m):
        if m.action == Marker.ADD:
            self.latest[m.ns] = m

    def wait(self, body, predicate=lambda m: True, timeout=20.0):
        deadline = time.time() + timeout
        while time.time() < deadline:
            m = self.latest.get(body)
            if m is not None and predicate(m):
                return m
            time.sleep(0.05)
        raise AssertionError('no ~mesh marker of %s as expected within %.0f s' % (body, timeout))


def top(marker):
    return max(p.z for p in marker.points)


class SurfaceBodies(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_surface_bodies')
        cls.sim = SimClient()
        cls.fix_pub = rospy.Publisher(NODE + '/fixed_nodes', FixedNodes, queue_size=10)
        connected(cls.fix_pub)
        cls.folder = tempfile.mkdtemp()
        cls.markers = Markers()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder, ignore_errors=True)

    def test_1_mesh_carries_the_users_triangles(self):
        for body, offset in OFFSETS.items():
            triangles = stl_triangles(os.path.join(MESHES, body + '.stl'))
            marker = self.markers.wait(body)
            self.assertEqual(marker.type, Marker.TRIANGLE_LIST)
            self.assertEqual(len(marker.points), 3 * len(triangles))
            # Resting on the floor, each corner is within a millimetre of where the file and the
            # scene put it; the grid's nodes lie on a 1 cm lattice and would be far off.
            worst = 0.0
            for t, corners in enumerate(triangles):
                for k, c in enumerate(corners):
                    p = marker.points[3 * t + k]
                    worst = max(worst, abs(p.x - c[0] - offset[0]), abs(p.y - c[1] - offset[1]),
                                abs(p.z - c[2] - offset[2]))
            self.assertLess(worst, 1e-3, '%s: a vertex is %.4f m from the file\'s' % (body, worst))

    def test_2_squeezed_sponge_surface_follows_the_grid_and_replays(self):
        bag = os.path.join(self.folder, 'squeeze.bag')
        recorder = start_recording(bag, [NODE + '/scene', NODE + '/applied', NODE + '/state'])
        self.sim.reset()  # the recorded session starts here
        rest = top(self.markers.wait('sponge'))
        squeeze = FixedNodes(body='sponge', action=FixedNodes.FIX, group='top')
        squeeze.translation.z = -0.012  # 40 % of the sponge's 3 cm
        self.fix_pub.publish(squeeze)
        pressed = self.markers.wait('sponge', lambda m: top(m) < rest - 0.010)
        self.assertEqual(len(pressed.points), 3 * len(stl_triangles(os.path.join(MESHES,
                                                                                 'sponge.stl'))))
        self.check_rviz_shows_the_squeeze()
        time.sleep(1.0)
        stop_recording(recorder, bag)
        out = os.path.join(self.folder, 'resimulated.bag')
        result = subprocess.run(['rosrun', 'deformable_sim', 'deformable_sim_replay', '--quiet',
                                 bag, '--out', out], capture_output=True, text=True, timeout=120)
        self.assertEqual(result.returncode, 0, result.stderr)
        match = re.search(r'largest difference (\S+) m in position', result.stdout)
        self.assertIsNotNone(match, result.stdout)
        self.assertEqual(float(match.group(1)), 0.0, result.stdout)
        with rosbag.Bag(out) as resimulated:
            sponge = [m for _, m, _ in resimulated.read_messages(topics=[NODE + '/mesh'])
                      if m.ns == 'sponge' and m.action == Marker.ADD]
        self.assertTrue(sponge, 'the re-simulated bag has no sponge marker')
        self.assertEqual(len(sponge[-1].points), len(pressed.points))
        self.assertLess(top(sponge[-1]), rest - 0.010)

    def check_rviz_shows_the_squeeze(self):
        rviz = RvizUnderXvfb(os.path.join(CONFIG, 'soft_objects.rviz'))
        try:
            shot, pixels = None, 0
            deadline = time.time() + 60.0
            while time.time() < deadline and pixels < 5000:
                time.sleep(2.0)
                shot = rviz.screenshot()
                if shot:
                    pixels = count_pixels(shot, is_mesh_orange)
            keep = rospy.get_param('~screenshot', '')
            if keep and shot:
                shutil.copy(shot, keep)
        finally:
            rviz.close()
        self.assertGreater(pixels, 5000, 'the objects do not show in rviz (%d pixels)' % pixels)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'surface_bodies', SurfaceBodies)
