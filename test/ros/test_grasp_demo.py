#!/usr/bin/python3
"""launch/grasp_demo.launch runs its whole script headless: the block stays finite, is lifted by the
two finger grasps, swung and put back on the table, never sinking into it; the fingers feed back
what they push with. rviz under Xvfb shows gripper, block and reaction wrench while it is held (the
screenshot, kept by ~screenshot, is the README's)."""
import os
import shutil
import threading
import time
import unittest

import numpy as np
import rospkg
import rospy
import rostest
from geometry_msgs.msg import WrenchStamped

from deformable_sim.msg import BodyState
from rviz_xvfb import (RvizUnderXvfb, count_pixels, is_gripper_grey, is_reaction_cyan,
                       is_strain_coloured, is_table_wood)

CONFIG = os.path.join(rospkg.RosPack().get_path('deformable_sim'), 'config', 'grasp_demo.rviz')
MASS = 150.0 * 0.06 ** 3  # kg: the block of config/scenes/grasp_demo.yaml
TABLE_TOP = 0.0           # m: config/urdf/gripper_demo.urdf


class GraspDemo(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.states = []
        self.forces = {'left': [], 'right': []}
        rospy.Subscriber('/deformable_sim/state', BodyState, self.on_state, queue_size=100)
        for side in self.forces:
            rospy.Subscriber('/deformable_sim/grasps/%s/wrench' % side, WrenchStamped,
                             lambda m, side=side: self.on_wrench(side, m), queue_size=100)
        self.rviz = RvizUnderXvfb(CONFIG)

    def tearDown(self):
        self.rviz.close()

    def on_state(self, message):
        points = np.array([(p.x, p.y, p.z) for p in message.positions])
        with self.lock:
            self.states.append((time.time(), points))

    def on_wrench(self, side, message):
        f = message.wrench.force
        with self.lock:
            self.forces[side].append((time.time(), np.array([f.x, f.y, f.z])))

    def cycles(self):
        return rospy.get_param('/grasp_demo_motion/cycles', 0)

    def wait_for_cycle(self, count, deadline):
        """Waits until the script has run `count` times; returns the wall time it saw that."""
        while self.cycles() < count and time.time() < deadline:
            time.sleep(0.05)
            self.take_screenshot_when_held()
        self.assertGreaterEqual(self.cycles(), count, 'the script did not finish its run %d in '
                                'time' % count)
        return time.time()

    def take_screenshot_when_held(self):
        with self.lock:
            latest = self.states[-1][1] if self.states else None
        if self.shot is not None or latest is None or latest[:, 2].mean() <= 0.2:
            return
        candidate = self.rviz.screenshot()
        if not candidate:
            return
        pixels = tuple(count_pixels(candidate, f) for f in
                       (is_strain_coloured, is_reaction_cyan, is_gripper_grey, is_table_wood))
        # The table under it covers a third of the view (about 150 000 pixels).
        if min(pixels[:3]) > 50 and pixels[3] > 20000:
            self.shot, self.shot_pixels = candidate, pixels
            keep = rospy.get_param('~screenshot', '')
            if keep:
                shutil.copy(candidate, keep)

    def test_the_demo_picks_up_swings_and_puts_down_the_block(self):
        # The script loops and the launch starts it with this test, so its first run may be half
        # over before we subscribed: judge one whole run, from the end of the one in progress to
        # the end of the next. The screenshot is taken the first time the block is held high.
        self.shot, self.shot_pixels = None, (0, 0, 0, 0)
        deadline = time.time() + 110.0
        while not rospy.has_param('/grasp_demo_motion/cycles') and time.time() < deadline:
            time.sleep(0.1)
        run = self.cycles() + 1
        begin = self.wait_for_cycle(run, deadline)
        end = self.wait_for_cycle(run + 1, deadline)
        while self.shot is None and time.time() < deadline and self.cycles() < run + 2:
            time.sleep(0.5)
            self.take_screenshot_when_held()
        with self.lock:
            states = [(t, p) for t, p in self.states if begin <= t <= end]
            forces = {side: [(t, f) for t, f in f_side if begin <= t <= end]
                      for side, f_side in self.forces.items()}

        self.assertGreater(len(states), 1000)
        for _, points in states:
            self.assertTrue(np.all(np.isfinite(points)))
            self.assertGreater(points[:, 2].min(), TABLE_TOP - 1e-9, 'a node sank into the table')
        heights = [points[:, 2].mean() for _, points in states]
        self.assertGreater(max(heights), 0.2, 'the block was never lifted')
        # Put down and let go: it rests on the table again, about where it started.
        self.assertLess(abs(heights[-1] - 0.03), 0.005, 'mean height %.4f m after the run' %
                        heights[-1])
        self.assertLess(heights[0], 0.04, 'mean height %.4f m when the run began' % heights[0])
        # While held, the fingers carry the block's weight (and its swing).
        for side in forces:
            self.assertTrue(forces[side], 'no reaction wrench from the %s finger' % side)
            self.assertTrue(all(np.all(np.isfinite(f)) for _, f in forces[side]))
        lifted = [f for side in forces for _, f in forces[side]]
        self.assertGreater(max(f[2] for f in lifted), 0.25 * MASS * 9.81)
        self.assertIsNotNone(self.shot, 'rviz never showed block, reaction wrench, gripper and '
                             'table together')
        rospy.loginfo('screenshot pixels (block, wrench, gripper, table): %s', self.shot_pixels)


if __name__ == '__main__':
    rospy.init_node('test_grasp_demo')
    rostest.rosrun('deformable_sim', 'grasp_demo', GraspDemo)
