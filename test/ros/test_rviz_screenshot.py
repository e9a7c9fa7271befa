#!/usr/bin/python3
"""rviz, with a shipped config (~config, by default config/deformable_sim.rviz), draws the node's
mesh: a screenshot of rviz under Xvfb has the mesh's orange pixels. The screenshot is kept
(~screenshot) for the README."""
import os
import shutil
import time
import unittest

import rospkg
import rospy
import rostest

from rviz_xvfb import RvizUnderXvfb, count_pixels, is_mesh_orange

CONFIG = os.path.join(rospkg.RosPack().get_path('deformable_sim'), 'config', 'deformable_sim.rviz')


class RvizScreenshot(unittest.TestCase):
    def setUp(self):
        self.rviz = RvizUnderXvfb(rospy.get_param('~config', CONFIG))

    def tearDown(self):
        self.rviz.close()

    def test_the_mesh_shows(self):
        shot, pixels = None, 0
        deadline = time.time() + 60.0
        while time.time() < deadline and pixels < 5000:
            time.sleep(2.0)
            shot = self.rviz.screenshot()
            if shot:
                pixels = count_pixels(shot, is_mesh_orange)
        keep = rospy.get_param('~screenshot', '')
        if keep and shot:
            shutil.copy(shot, keep)
        # The default scene's beam covers some 20 000 pixels of 1024 x 768; the pile's first
        # sponge, the orange body, tens of thousands.
        self.assertGreater(pixels, 5000, 'the mesh does not show in rviz (%d pixels)' % pixels)


if __name__ == '__main__':
    rospy.init_node('test_rviz_screenshot')
    rostest.rosrun('deformable_sim', 'rviz_screenshot', RvizScreenshot)
