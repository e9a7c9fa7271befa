#!/usr/bin/python3
"""With /use_sim_time the node follows /clock: nothing moves while the clock stands still, and one
second of clock time is one second of simulated time, however fast the clock runs."""
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import WrenchStamped
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Trigger
from tf2_msgs.msg import TFMessage
from visualization_msgs.msg import Marker

from deformable_sim.msg import BodyState, Stats

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
        # Still stepping with the clock (a lagging node may fold some ticks into one).
        sim.wait('state', lambda m: m.step > start + 20)

    def test_outputs_come_at_their_rates_of_simulated_time(self):
        """~mesh at ~marker_rate (30 Hz) and ~stats at ~stats_rate (10 Hz) per second of the
        clock, on a timer that ticks at 100 Hz: each is due a period after it was last due, not
        a period after the tick that published it (every fourth tick: 25 Hz)."""
        stamps = {'mesh': [], 'stats': []}
        subscribers = [
            rospy.Subscriber('/deformable_sim/mesh', Marker, lambda m: stamps['mesh'].append(
                m.header.stamp.to_sec()) if m.action == Marker.ADD else None, queue_size=1000),
            rospy.Subscriber('/deformable_sim/stats', Stats,
                             lambda m: stamps['stats'].append(m.header.stamp.to_sec()),
                             queue_size=1000)]
        self.run_clock(1.0, 1.0)  # time for the subscriptions to connect
        start = self.now
        self.run_clock(5.0, 1.0)
        for subscriber in subscribers:
            subscriber.unregister()
        for topic, rate in (('mesh', 30.0), ('stats', 10.0)):
            counted = [t for t in stamps[topic] if start < t <= start + 5.0]
            self.assertAlmostEqual(len(counted) / 5.0, rate, delta=0.03 * rate, msg=topic)

    def test_outputs_are_stamped_at_the_simulated_instant_they_show(self):
        """~state, tf, ~reactions and ~stats are stamped with the episode's start plus the
        simulated time, to the nanosecond (dt 10 ms), not with the time the tick ran; a reset
        starts an episode at the clock's time. The clock's ticks come up to 4 ms after the
        steps' instants, as a timer's callbacks do."""
        seen = {'state': [], 'tf': [], 'reaction': [], 'stats': []}
        subscribers = [
            rospy.Subscriber('/deformable_sim/state', BodyState, lambda m: seen['state'].append(
                (m.episode, m.step, m.header.stamp.to_nsec())), queue_size=1000),
            rospy.Subscriber('/tf', TFMessage, lambda m: seen['tf'].extend(
                t.header.stamp.to_nsec() for t in m.transforms if t.child_frame_id == 'beam'),
                queue_size=1000),
            rospy.Subscriber('/deformable_sim/reactions/beam', WrenchStamped,
                             lambda m: seen['reaction'].append(m.header.stamp.to_nsec()),
                             queue_size=1000),
            rospy.Subscriber('/deformable_sim/stats', Stats, lambda m: seen['stats'].append(
                (m.sim_time, m.header.stamp.to_nsec())), queue_size=1000)]
        def run_late_clock(seconds):
            start = self.now
            for k in range(1, int(round(seconds / 0.01)) + 1):
                self.tick(start + 0.01 * k + 0.001 * (k % 5) - self.now)  # 0 to 4 ms late
                time.sleep(0.01)
            time.sleep(0.3)

        run_late_clock(1.5)
        rospy.wait_for_service('/deformable_sim/reset')
        reset_at = self.now
        self.assertTrue(rospy.ServiceProxy('/deformable_sim/reset', Trigger)().success)
        run_late_clock(1.0)
        for subscriber in subscribers:
            subscriber.unregister()

        episodes = sorted({e for e, _, _ in seen['state']})
        self.assertGreaterEqual(len(episodes), 2)
        starts = {}
        for episode in episodes:
            states = [(step, stamp) for e, step, stamp in seen['state'] if e == episode]
            self.assertGreater(len(states), 50)
            start = {stamp - step * 10**7 for step, stamp in states}
            self.assertEqual(len(start), 1, 'episode %d: stamps off the instants by %s ns' % (
                episode, sorted(s - min(start) for s in start)[:10]))
            starts[episode] = start.pop()
        # The reset's episode started at the clock's time then.
        self.assertAlmostEqual(starts[episodes[-1]] * 1e-9, reset_at, delta=0.011)
        instants = {stamp for _, _, stamp in seen['state']}
        self.assertGreater(len(seen['tf']), 100)
        self.assertLessEqual(set(seen['tf']), instants, 'tf stamped off the states\' instants')
        self.assertGreater(len(seen['reaction']), 100)
        self.assertLessEqual(set(seen['reaction']), instants, '~reactions off the instants')
        self.assertGreater(len(seen['stats']), 10)
        for sim_time, stamp in seen['stats']:
            self.assertIn(stamp - round(sim_time * 1e9), starts.values())


if __name__ == '__main__':
    rospy.init_node('test_sim_time')
    rostest.rosrun('deformable_sim', 'sim_time', SimTime)
