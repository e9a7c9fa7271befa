#!/usr/bin/python3
"""With /use_sim_time the node follows /clock: nothing moves while the clock stands still, and one
second of clock time is one second of simulated time, however fast the clock runs."""
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage

from sim_client import SimClient, connected


class SimTime(unittest.TestCase):
    def setUp(self):
        self.clock = rospy.Publisher('/clock', Clock, queue_size=100)
        self.now = 1000.0
        self.tick(0.0)
        connected(self.clock)

    def tick(self, seconds):
        self.now += seconds
        self.clock.publish(Clock(clock=rospy.Time.from_sec(self.now)))

    def run_clock(self, seconds, speed):
        """Advances the clock by `seconds` in 10 ms ticks at `speed` times the wall clock."""
        for _ in range(int(round(seconds / 0.01))):
            self.tick(0.01)
            time.sleep(0.01 / speed)
        time.sleep(0.3)  # let the last ticks arrive

    def test_steps_follow_the_clock(self):
        sim = SimClient()
        self.run_clock(0.5, 1.0)
        start = sim.wait('state').step
        time.sleep(1.0)  # the clock stands still: no step
        self.assertEqual(sim.wait('state').step, start)
        self.run_clock(1.0, 1.0)
        after_one = sim.wait('state').step
        self.assertAlmostEqual(after_one - start, 100, delta=3)  # dt = 10 ms
        self.run_clock(1.0, 3.0)  # three times faster than the wall clock
        self.assertAlmostEqual(sim.wait('state').step - after_one, 100, delta=3)
        # The state is stamped with the clock's time.
        self.assertAlmostEqual(sim.wait('state').header.stamp.to_sec(), self.now, delta=0.02)

    def test_a_clock_that_jumps_repeats_no_transform(self):
        """A clock coarser than the timer (rosbag play --clock -r 2) fires the timer several
        times at one time; each stamp is sent once, else tf warns TF_REPEATED_DATA."""
        sent = []
        tf = rospy.Subscriber('/tf', TFMessage, lambda m: sent.extend(
            (t.child_frame_id, t.header.stamp.to_nsec()) for t in m.transforms), queue_size=1000)
        sim = SimClient()
        self.run_clock(1.0, 1.0)  # time for the subscriptions to connect
        start = sim.wait('state').step
        for _ in range(40):  # 50 ms ticks: five timer periods each
            self.tick(0.05)
            time.sleep(0.02)
        time.sleep(0.5)
        tf.unregister()
        beam = [s for s in sent if s[0] == 'beam']
        self.assertGreater(len(beam), 20)
        self.assertEqual(len(beam), len(set(beam)), 'a transform was sent twice with one stamp')
        self.assertGreater(sim.wait('state').step, start + 40)  # a step a tick at least


if __name__ == '__main__':
    rospy.init_node('test_sim_time')
    rostest.rosrun('deformable_sim', 'sim_time', SimTime)
