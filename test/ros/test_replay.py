#!/usr/bin/python3
"""Record a session with rosbag (wrenches, fixed-node changes, a grasp of a moving tf frame, live
tuning) and re-simulate it with deformable_sim_replay: recorded and re-simulated states are
identical bit for bit. Other solver settings give another result; truncated, foreign and non-bag
files give a clear error, not a crash. The session is recorded a while after the node started, as
a user would: the re-simulated bag must still start where its states do."""
import math
import os
import re
import shutil
import signal
import subprocess
import tempfile
import time
import unittest
import xmlrpc.client

import dynamic_reconfigure.client
import rosbag
import rosgraph
import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Point, TransformStamped, WrenchStamped
from std_msgs.msg import String

from deformable_sim.msg import Applied, FixedNodes, Grasp
from sim_client import SimClient, connected

NODE = '/deformable_sim'
# How long after the node's start the recording begins: the node stamps its latched ~scene when
# it starts, so a bag written at that stamp would start this long before its first state.
NODE_AGE_AT_RECORDING = 4.0
TOPICS = [NODE + '/scene', NODE + '/applied', NODE + '/state']


def replay(*arguments, quiet=True):
    return subprocess.run(['rosrun', 'deformable_sim', 'deformable_sim_replay'] +
                          (['--quiet'] if quiet else []) + list(arguments),
                          capture_output=True, text=True, timeout=120)


class Replay(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_replay')
        cls.folder = tempfile.mkdtemp()
        cls.bag = os.path.join(cls.folder, 'session.bag')
        cls.sim = SimClient()
        time.sleep(NODE_AGE_AT_RECORDING)
        cls.record_session()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder, ignore_errors=True)

    @classmethod
    def record_session(cls):
        recorder = subprocess.Popen(['rosbag', 'record', '-O', cls.bag] + TOPICS,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                    start_new_session=True)
        broadcaster = tf2_ros.TransformBroadcaster()

        def gripper(event):
            t = time.time() - cls.start if cls.start else 0.0
            frame = TransformStamped()
            frame.header.stamp = rospy.Time.now()
            frame.header.frame_id = 'world'
            frame.child_frame_id = 'gripper'
            s = max(0.0, t - 0.5)  # still while it is grasped, then lifted and turned
            frame.transform.translation.x = 0.05 + 0.03 * math.sin(2.0 * s)
            frame.transform.translation.y = 0.05
            frame.transform.translation.z = 0.1 + 0.03 * (1.0 - math.cos(2.0 * s))
            frame.transform.rotation.z = math.sin(0.2 * s)
            frame.transform.rotation.w = math.cos(0.2 * s)
            broadcaster.sendTransform(frame)

        cls.start = None
        rospy.Timer(rospy.Duration(0.02), gripper)  # the node must know the frame first
        # Wait until the node itself has a connection to the recorder on every topic.
        node = xmlrpc.client.ServerProxy(rosgraph.Master('/test_replay').lookupNode(NODE))
        deadline = time.time() + 20.0
        while time.time() < deadline:
            connections = node.getBusInfo('/test_replay')[2]
            out = {c[4] for c in connections if c[2] == 'o' and 'record' in c[1]}
            if all(t in out for t in TOPICS):
                break
            time.sleep(0.1)
        wrench = rospy.Publisher(NODE + '/wrench', WrenchStamped, queue_size=10)
        fixed = rospy.Publisher(NODE + '/fixed_nodes', FixedNodes, queue_size=10)
        grasp = rospy.Publisher(NODE + '/grasp', Grasp, queue_size=10)
        connected(wrench, fixed, grasp)
        tuner = dynamic_reconfigure.client.Client(NODE, timeout=10.0)
        # The session starts at the reset: the bag holds all of it.
        cls.sim.reset()
        start = cls.start = time.time()
        events = [(0.05, 'grasp'), (0.3, 'push'), (1.5, 'fix'), (2.0, 'tune'), (2.5, 'drag'),
                  (3.5, 'release'), (4.0, 'let go'), (5.0, 'end')]
        for at, event in events:
            while time.time() - start < at:
                time.sleep(0.01)
            if event == 'push':
                m = WrenchStamped()
                m.header.frame_id = 'block'
                m.wrench.force.x, m.wrench.torque.z = 0.3, 0.01
                wrench.publish(m)
            elif event == 'grasp':
                m = Grasp(name='hand', body='block', action=Grasp.ATTACH,
                          region=Grasp.REGION_SPHERE, sphere_radius=0.03)
                m.header.frame_id = 'gripper'
                grasp.publish(m)
            elif event == 'fix':
                fixed.publish(FixedNodes(body='block', action=FixedNodes.FIX, nodes=[1, 2]))
            elif event == 'tune':
                tuner.update_configuration({'youngs_modulus': 8.0e4, 'damping_mass': 5.0})
            elif event == 'drag':
                fixed.publish(FixedNodes(body='block', action=FixedNodes.FIX, nodes=[1, 2],
                                         translation=Point(0.0, 0.0, 0.02)))
            elif event == 'release':
                grasp.publish(Grasp(name='hand', action=Grasp.RELEASE))
                wrench.publish(WrenchStamped(header=rospy.Header(frame_id='block')))
            elif event == 'let go':
                fixed.publish(FixedNodes(body='block', action=FixedNodes.RELEASE, nodes=[1, 2]))
        os.killpg(recorder.pid, signal.SIGINT)  # rosbag and its recorder: the bag is closed
        recorder.wait(timeout=30)
        deadline = time.time() + 10.0
        while not os.path.exists(cls.bag) and time.time() < deadline:
            time.sleep(0.1)
        assert os.path.exists(cls.bag), 'rosbag record wrote no bag'

    def test_the_recorded_session_is_re_simulated_bit_for_bit(self):
        kinds = set()
        states = 0
        with rosbag.Bag(self.bag) as bag:
            for topic, message, _ in bag.read_messages(topics=TOPICS):
                if topic.endswith('/applied'):
                    kinds.add(message.kind)
                elif topic.endswith('/state'):
                    states += 1

        for kind in (Applied.RESET, Applied.WRENCH, Applied.CLEAR_WRENCH, Applied.FIX,
                     Applied.RELEASE, Applied.GRASP, Applied.MOVE_GRASP, Applied.RELEASE_GRASP,
                     Applied.TUNE):
            self.assertIn(kind, kinds, 'the log has no command of kind %d' % kind)
        out = os.path.join(self.folder, 'resimulated.bag')
        result = replay(self.bag, '--out', out)
        self.assertEqual(result.returncode, 0, result.stderr)
        match = re.search(r'compared (\d+) recorded states: largest difference (\S+) m in position, '
                          r'(\S+) m/s in velocity \(bit-exact\)', result.stdout)
        self.assertIsNotNone(match, result.stdout)
        self.assertGreater(int(match.group(1)), 300)
        self.assertEqual(float(match.group(2)), 0.0)
        self.assertEqual(float(match.group(3)), 0.0)
        self.assertIn('real time', result.stdout)
        # The new bag plays back like the recorded one: state, mesh and tf.
        with rosbag.Bag(out) as bag:
            topics = bag.get_type_and_topic_info().topics
        self.assertEqual(topics[NODE + '/state'].message_count, int(match.group(1)))
        self.assertGreater(topics[NODE + '/mesh'].message_count, 10)
        self.assertGreater(topics['/tf'].message_count, 10)
        self.check_the_bag_starts_with_its_states(out)

    def check_the_bag_starts_with_its_states(self, path):
        with rosbag.Bag(path) as bag:
            scene_times = [t.to_sec() for _, _, t in bag.read_messages(topics=[NODE + '/scene'])]
            state_times = [t.to_sec() for _, _, t in bag.read_messages(topics=[NODE + '/state'])]
            start = bag.get_start_time()
        self.assertEqual(len(scene_times), 1)
        first_state = min(state_times)
        # The scene comes with the first state, not when the node started: no empty lead-in.
        self.assertGreater(scene_times[0], first_state - 0.1,
                           'the scene is %.1f s before the first state' %
                           (first_state - scene_times[0]))
        self.assertGreater(start, first_state - 0.1)

    def test_states_and_frames_are_stamped_at_their_instants_live_and_replayed(self):
        """Live, each state is stamped at the episode's start plus its simulated time, to the
        nanosecond, except where the node fell more than 0.25 s behind the clock and its
        reckoning started again there; the replay stamps its states and frames alike."""
        with rosbag.Bag(self.bag) as bag:
            dt = next(bag.read_messages(topics=[NODE + '/scene'])).message.dt
            live = [(m.episode, m.step, m.header.stamp.to_nsec())
                    for _, m, _ in bag.read_messages(topics=[NODE + '/state'])]
        episode = live[-1][0]  # the recorded session starts at a reset
        states = [(step, stamp) for e, step, stamp in live if e == episode]
        self.assertGreater(len(states), 300)
        exact = 0
        for (step0, stamp0), (step1, stamp1) in zip(states, states[1:]):
            apart = stamp1 - stamp0 - (round(step1 * dt * 1e9) - round(step0 * dt * 1e9))
            if apart == 0:
                exact += 1
            else:  # the clock ran on past the steps: the reckoning starts again there
                self.assertGreater(abs(apart), 0.25e9, 'steps %d, %d' % (step0, step1))
        self.assertGreater(exact, 0.9 * (len(states) - 1))
        out = os.path.join(self.folder, 'stamped.bag')
        result = replay(self.bag, '--out', out)
        self.assertEqual(result.returncode, 0, result.stderr)
        with rosbag.Bag(out) as bag:
            replayed = [(m.episode, m.step, m.header.stamp.to_nsec())
                        for _, m, _ in bag.read_messages(topics=[NODE + '/state'])]
            frames = [t.header.stamp.to_nsec() for _, m, _ in bag.read_messages(topics=['/tf'])
                      for t in m.transforms]
        self.assertEqual(replayed, [(episode, step, stamp) for step, stamp in states])
        self.assertGreater(len(frames), 10)
        self.assertLessEqual(set(frames), {stamp for _, stamp in states})

    def test_more_threads_re_simulate_the_same_bits(self):
        # The node ran on one thread; two sum everything in the same order.
        result = replay(self.bag, '--threads', '2')
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn('on 2 threads', result.stdout)
        self.assertIn('(bit-exact)', result.stdout)

    def test_other_solver_settings_give_another_result(self):
        result = replay(self.bag, '--tolerance', '1e-2', '--max-iterations', '5')
        self.assertEqual(result.returncode, 0, result.stderr)
        match = re.search(r'largest difference (\S+) m in position', result.stdout)
        self.assertGreater(float(match.group(1)), 0.0)
        self.assertNotIn('bit-exact', result.stdout)

    def test_help_prints_the_usage_and_succeeds(self):
        for flag in ('--help', '-h'):
            result = replay(flag, quiet=False)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertIn('usage: deformable_sim_replay IN.bag', result.stdout)
            self.assertEqual(result.stderr, '')
        result = replay(self.bag, '--no-such-option', quiet=False)
        self.assertEqual(result.returncode, 2)
        self.assertIn("bad argument '--no-such-option'", result.stderr)
        self.assertIn('usage: deformable_sim_replay IN.bag', result.stderr)
        self.assertEqual(result.stdout, '')

    def test_truncated_foreign_and_non_bags_are_refused_clearly(self):
        truncated = os.path.join(self.folder, 'truncated.bag')
        with open(self.bag, 'rb') as whole, open(truncated, 'wb') as half:
            half.write(whole.read(os.path.getsize(self.bag) // 2))
        result = replay(truncated)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn('truncated.bag', result.stderr)
        self.assertRegex(result.stderr, 'truncated|cannot read')

        foreign = os.path.join(self.folder, 'foreign.bag')
        with rosbag.Bag(foreign, 'w') as bag:
            bag.write('/chatter', String(data='hello'), rospy.Time(1))
        result = replay(foreign)
        self.assertEqual(result.returncode, 1)
        self.assertIn('no deformable_sim/Scene message', result.stderr)

        text = os.path.join(self.folder, 'notes.bag')
        with open(text, 'w') as f:
            f.write('not a bag\n')
        result = replay(text)
        self.assertEqual(result.returncode, 1)
        self.assertIn('cannot read the bag', result.stderr)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'replay', Replay)
