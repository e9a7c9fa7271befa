#!/usr/bin/python3
"""rviz, with the shipped config, draws the node's mesh: a screenshot of rviz under Xvfb has the
mesh's orange pixels. The screenshot is kept (~screenshot) for the README."""
import os
import shutil
import subprocess
import tempfile
import time
import unittest

import rospkg
import rospy
import rostest

CONFIG = os.path.join(rospkg.RosPack().get_path('deformable_sim'), 'config', 'deformable_sim.rviz')


def mesh_pixels(png):
    """Pixels of the mesh's orange (1.0, 0.55, 0.1), lit or in shade; not the red fixed nodes."""
    raw = subprocess.run(['/usr/bin/convert', png, '-depth', '8', 'rgb:-'], capture_output=True,
                         check=True).stdout
    count = 0
    for k in range(0, len(raw), 3):
        r, g, b = raw[k], raw[k + 1], raw[k + 2]
        if r > 80 and 0.35 * r < g < 0.75 * r and b < 0.3 * r:
            count += 1
    return count


class RvizScreenshot(unittest.TestCase):
    def setUp(self):
        for tool in ('Xvfb', 'rviz', '/usr/bin/import', '/usr/bin/convert'):
            self.assertIsNotNone(shutil.which(tool), tool + ' is not installed (.ci/run installs it)')
        self.folder = tempfile.mkdtemp()
        read_end, write_end = os.pipe()
        self.xvfb = subprocess.Popen(['Xvfb', '-displayfd', str(write_end), '-screen', '0',
                                      '1024x768x24', '+extension', 'GLX', '+render', '-noreset'],
                                     pass_fds=[write_end], stderr=subprocess.DEVNULL)
        os.close(write_end)
        with os.fdopen(read_end) as display:
            self.display = ':' + display.readline().strip()
        environment = dict(os.environ, DISPLAY=self.display)
        self.rviz = subprocess.Popen(['rviz', '-d', CONFIG], env=environment,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def tearDown(self):
        for process in (self.rviz, self.xvfb):  # rviz first: it aborts if the display goes
            process.terminate()
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                process.kill()

    def test_the_mesh_shows(self):
        shot = os.path.join(self.folder, 'rviz.png')
        pixels = 0
        deadline = time.time() + 60.0
        while time.time() < deadline and pixels < 5000:
            time.sleep(2.0)
            subprocess.run(['/usr/bin/import', '-display', self.display, '-window', 'root', shot],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            if os.path.exists(shot):
                pixels = mesh_pixels(shot)
        keep = rospy.get_param('~screenshot', '')
        if keep and os.path.exists(shot):
            shutil.copy(shot, keep)
        # The beam seen from the default view covers some 20 000 pixels of 1024 x 768.
        self.assertGreater(pixels, 5000, 'the mesh does not show in rviz (%d pixels)' % pixels)


if __name__ == '__main__':
    rospy.init_node('test_rviz_screenshot')
    rostest.rosrun('deformable_sim', 'rviz_screenshot', RvizScreenshot)
