#!/usr/bin/python3
"""A flood of hostile messages on every command topic, at more than 1 kHz for 30 s, while the
node steps a sagging beam with a soft block resting on it (contact between bodies) in real time
and a few good commands arrive among them.

What must hold (the promise of the README's Security section):
(a) the node stays up and answers: ~stats never stops for a second, and hostile calls of the
    ~grasp service and of live tuning (dynamic_reconfigure), five a second each during the flood,
    are answered within a second and refused;
(b) it keeps stepping at >= 90 % of its nominal rate (100 Hz), measured from ~stats' step counter
    over the flood;
(c) every hostile message is refused and counted: ~stats' dropped_messages grows by exactly the
    number sent. ROS itself drops the oldest message when a subscriber's queue (100 per topic in the
    node) is full, and nothing would count that. So the flood never has more messages in flight
    (sent but not yet counted on ~stats) than 4 x 90, spread round-robin over 4 topics: no topic's
    queue can ever hold more than about 90, ROS can drop none, and the count must be exact. The
    flood is paced at 1.25 kHz; if the node ever fell that far behind (or accepted a hostile
    message, which then never counts), the window would slow the flood and its rate check fails.
    Service calls are synchronous: each is counted once answered;
(d) the flood changes nothing: the node's ~applied log of the session (recorded with rosbag from a
    reset) holds the reset and exactly the good commands, in order, and deformable_sim_replay,
    which re-runs that log on the same scene in another process with no flood at all, reproduces
    every recorded ~state (one per step) bit for bit. A hostile message that took effect would
    appear in the log; one that changed the state any other way would make the replay differ.
Warnings stay throttled: at most one a second per topic.
"""
import math
import os
import re
import shutil
import subprocess
import tempfile
import threading
import time
import unittest

import dynamic_reconfigure.client
import rosbag
import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Point, TransformStamped, Vector3, WrenchStamped
from rosgraph_msgs.msg import Log

from deformable_sim.msg import Applied, ContactPair, Contacts, FixedNodes, Grasp, NodeWrench, Stats
from deformable_sim.srv import SetGrasp
from sim_client import (SimClient, connected, node_wrench, start_recording, stop_recording,
                        wrench_stamped)

NODE = '/deformable_sim'
TOPICS = [NODE + '/scene', NODE + '/applied', NODE + '/state']
NAN = float('nan')
INF = float('inf')
FLOOD_S = 30.0
TARGET_HZ = 1250.0
NOMINAL_HZ = 100.0    # the scene's dt of 0.01 s, one step a tick
MIN_STEP_RATE = 0.9   # of NOMINAL_HZ: the README's promise
QUEUE = 100           # the node's subscriber queue on every command topic
WINDOW = 4 * 90       # messages in flight at most: < QUEUE on each of the 4 topics
GRIPPER = 'flood_gripper'  # a tf frame near the beam's tip, so that grasps get past the frame check



def fixed(frame='', **fields):
    m = FixedNodes(**fields)
    m.header.frame_id = frame
    return m


def grasp(frame=GRIPPER, **fields):
    m = Grasp(**fields)
    m.header.frame_id = frame
    return m


FIX, SPHERE = FixedNodes.FIX, Grasp.REGION_SPHERE
# Every one of these must be refused: NaN, infinite and huge values, unknown node ids, frames,
# bodies, groups and grasps, regions that hold no node, nothing selected at all, bad constants.
HOSTILE = {
    'wrench': [
        wrench_stamped('beam/tip', force=(0, 0, NAN)),
        wrench_stamped('beam', torque=(INF, 0, 0)),
        wrench_stamped('beam/tip', force=(0, 0, -1e12)),
        wrench_stamped('beam', force=(-INF, NAN, 1e308)),
        wrench_stamped('intruder_frame', force=(0, 0, -1)),
        wrench_stamped('beam/nope', force=(0, 0, -1)),
        wrench_stamped('sponge', force=(0, 1, 0)),
        wrench_stamped('', force=(1, 0, 0)),
        wrench_stamped('intruder_frame'),  # zero wrenches that clear nothing name their target too
        wrench_stamped('beam/nope'),
    ],
    'node_wrench': [
        node_wrench(nodes=[123456, -7], force=(0, 0, -1)),
        node_wrench(body='sponge', group='tip', force=(0, 0, -1)),
        node_wrench(group='nope', force=(0, 0, -1)),
        node_wrench(force=(0, 0, -1)),
        node_wrench(group='tip', torque=(0, NAN, 0)),
        node_wrench(group='tip', force=(1e300, 0, 0)),
        node_wrench(group='tip', force=(0, 0, -1), frame='intruder_frame'),
        node_wrench(nodes=[123456]),
        node_wrench(body='sponge', group='tip'),
        node_wrench(),
    ],
    'fixed_nodes': [
        fixed(body='beam', action=FIX, nodes=[9], targets=[Point(0.5, NAN, 0)]),
        fixed(body='beam', action=FIX, group='tip', translation=Vector3(INF, 0, 0)),
        fixed(body='beam', action=FIX, nodes=[9], targets=[Point(1e300, 0, 0)]),
        fixed(body='beam', action=FIX, nodes=[123456]),
        fixed(body='beam', action=FixedNodes.RELEASE, nodes=[-3]),
        fixed(body='nobody', action=FIX, group='tip'),
        fixed(body='beam', action=FIX),
        fixed(body='beam', action=FIX, group='nope'),
        fixed(body='beam', action=FIX, region=FixedNodes.REGION_BOX, box_min=Point(5, 5, 5),
              box_max=Point(6, 6, 6)),
        fixed(body='beam', action=FIX, region=FixedNodes.REGION_SPHERE,
              sphere_center=Point(NAN, 0, 0), sphere_radius=0.1),
        fixed(body='beam', action=FIX, region=FixedNodes.REGION_SPHERE, sphere_radius=-1.0),
        fixed(body='beam', action=7, group='tip'),
        fixed(body='beam', action=FIX, group='tip', region=5),
        fixed(frame='intruder_frame', body='beam', action=FIX, group='tip'),
    ],
    'grasp': [
        grasp(name='intruder', body='nobody', action=Grasp.ATTACH, region=SPHERE,
              sphere_radius=0.12),
        grasp(frame='intruder_frame', name='intruder', action=Grasp.ATTACH, region=SPHERE,
              sphere_radius=0.12),
        grasp(frame='', name='intruder', action=Grasp.ATTACH, region=SPHERE, sphere_radius=0.12),
        grasp(frame='beam', name='intruder', action=Grasp.ATTACH, region=SPHERE,
              sphere_radius=0.12),
        grasp(name='intruder', action=Grasp.ATTACH, region=SPHERE, sphere_radius=NAN),
        grasp(name='intruder', action=Grasp.ATTACH, region=Grasp.REGION_BOX,
              box_min=Point(3, 3, 3), box_max=Point(4, 4, 4)),
        grasp(name='intruder', action=Grasp.ATTACH, region=Grasp.REGION_LINK, link='no_link'),
        grasp(name='intruder', action=Grasp.ATTACH, region=9),
        grasp(name='intruder', action=5),
        grasp(name='no_such_grasp', action=Grasp.RELEASE),
    ],
}

# The good commands, at seconds into the flood, on the same topics, and the ~applied kind each
# must produce.
GOOD = [
    (2.0, 'wrench', wrench_stamped('beam/tip', force=(0, 0.4, 0)), Applied.WRENCH),
    (6.0, 'node_wrench', node_wrench(group='tip', force=(0, 0, 0.2)), Applied.WRENCH),
    (10.0, 'wrench', wrench_stamped('beam/tip'), Applied.CLEAR_WRENCH),  # zero: clears the first
    (13.0, 'fixed_nodes', fixed(body='beam', action=FIX, group='tip',
                                translation=Vector3(0, 0, 0.02)), Applied.FIX),
    (17.0, 'fixed_nodes', fixed(body='beam', action=FixedNodes.RELEASE, group='tip'),
     Applied.RELEASE),
    (20.0, 'grasp', grasp(name='hand', action=Grasp.ATTACH, region=SPHERE, sphere_radius=0.12),
     Applied.GRASP),
    (25.0, 'grasp', grasp(name='hand', action=Grasp.RELEASE), Applied.RELEASE_GRASP),
    (27.0, 'node_wrench', node_wrench(group='tip'), Applied.WRENCH),  # zero: clears the second
]


def interleaved(hostile):
    """One cycle of (topic, message), round-robin over the topics."""
    longest = max(len(messages) for messages in hostile.values())
    return [(topic, messages[k % len(messages)]) for k in range(longest)
            for topic, messages in hostile.items()]


class Flood(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_flood')
        cls.folder = tempfile.mkdtemp()
        cls.bag = os.path.join(cls.folder, 'flood.bag')
        cls.lock = threading.Lock()
        cls.stats = []      # (stamp, step, dropped_messages) of every ~stats message
        cls.warnings = []   # (stamp, text) of the node's warnings
        rospy.Subscriber(NODE + '/stats', Stats, cls.on_stats, queue_size=100)
        cls.resting = []    # per ~contacts message: the beam's push up on the block, N, or None
        rospy.Subscriber(NODE + '/contacts', Contacts, cls.on_contacts, queue_size=100)
        rospy.Subscriber('/rosout', Log, cls.on_log, queue_size=1000)
        cls.sim = SimClient()
        cls.publishers = {
            'wrench': rospy.Publisher(NODE + '/wrench', WrenchStamped, queue_size=1000),
            'node_wrench': rospy.Publisher(NODE + '/node_wrench', NodeWrench, queue_size=1000),
            'fixed_nodes': rospy.Publisher(NODE + '/fixed_nodes', FixedNodes, queue_size=1000),
            'grasp': rospy.Publisher(NODE + '/grasp', Grasp, queue_size=1000),
        }
        connected(*cls.publishers.values())
        cls.grasp_service = rospy.ServiceProxy(NODE + '/grasp', SetGrasp)
        cls.tuner = dynamic_reconfigure.client.Client(NODE, timeout=10.0)
        cls.place_gripper()
        recorder = start_recording(cls.bag, TOPICS)
        try:
            cls.sim.reset()  # the recorded session starts here
            cls.flood()
        finally:
            stop_recording(recorder, cls.bag)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder, ignore_errors=True)

    @classmethod
    def on_stats(cls, message):
        with cls.lock:
            cls.stats.append((message.header.stamp.to_sec(), message.step,
                              message.dropped_messages))

    @classmethod
    def on_contacts(cls, message):
        push = [p.force.z for p in message.pairs
                if (p.body, p.other, p.kind) == ('block', 'beam', ContactPair.BODY)]
        with cls.lock:
            cls.resting.append(push[0] if push else None)

    @classmethod
    def on_log(cls, log):
        if log.level == Log.WARN and log.name == NODE:
            with cls.lock:
                cls.warnings.append((log.header.stamp.to_sec(), log.msg))

    @classmethod
    def refused(cls):
        with cls.lock:
            return cls.stats[-1][2] if cls.stats else None

    @classmethod
    def place_gripper(cls):
        """A static tf frame at the beam's tip; waits until the node has it in its tf buffer."""
        cls.static_tf = tf2_ros.StaticTransformBroadcaster()
        t = TransformStamped()
        t.header.stamp = rospy.Time.now()
        t.header.frame_id = 'world'
        t.child_frame_id = GRIPPER
        t.transform.translation.x = 0.5
        t.transform.rotation.w = 1.0
        cls.static_tf.sendTransform(t)
        probe = grasp(name='probe', body='nobody', action=Grasp.ATTACH, region=SPHERE,
                      sphere_radius=0.12)
        deadline = time.time() + 10.0
        while time.time() < deadline:
            if "unknown body 'nobody'" in cls.grasp_service(probe).message:
                return
            time.sleep(0.1)
        raise AssertionError('the node never saw the tf frame ' + GRIPPER)

    @classmethod
    def probe_services(cls, stop):
        """Five times a second, calls the ~grasp service and live tuning with hostile requests."""
        probe = grasp(name='probe', body='nobody', action=Grasp.ATTACH, region=SPHERE,
                      sphere_radius=0.12)
        tunes = [{'youngs_modulus': NAN}, {'body': 'nobody', 'density': 50.0}]
        while not stop.is_set():
            start = time.monotonic()
            response = cls.grasp_service(probe)
            latency = time.monotonic() - start
            with cls.lock:
                cls.service_calls.append((latency, response.success, response.message))
            start = time.monotonic()
            config = cls.tuner.update_configuration(tunes[len(cls.tune_calls) % len(tunes)])
            latency = time.monotonic() - start
            with cls.lock:
                cls.tune_calls.append((latency, config))
            stop.wait(0.2)

    @classmethod
    def flood(cls):
        cycle = interleaved(HOSTILE)
        good = list(GOOD)
        cls.service_calls = []
        cls.tune_calls = []
        cls.sent = {topic: 0 for topic in HOSTILE}
        cls.window_waits = 0
        # The count before the flood: it includes the probes of place_gripper.
        cls.refused_before = cls.sim.wait('stats', lambda m: m.step > 0).dropped_messages
        stop = threading.Event()
        prober = threading.Thread(target=cls.probe_services, args=(stop,))
        period = 1.0 / TARGET_HZ
        cls.start_stamp = rospy.Time.now().to_sec()
        start = time.monotonic()
        prober.start()
        i = 0
        while True:
            now = time.monotonic()
            if now - start >= FLOOD_S:
                break
            while good and good[0][0] <= now - start:
                _, topic, message, _ = good.pop(0)
                cls.publishers[topic].publish(message)
            with cls.lock:
                answered = len(cls.service_calls) + len(cls.tune_calls)
            while (cls.refused_before + sum(cls.sent.values()) + answered - cls.refused() >
                   WINDOW):
                cls.window_waits += 1
                time.sleep(0.001)
            due = start + i * period
            if due > now:
                time.sleep(due - now)
            topic, message = cycle[i % len(cycle)]
            cls.publishers[topic].publish(message)
            cls.sent[topic] += 1
            i += 1
        cls.flood_s = time.monotonic() - start
        cls.end_stamp = rospy.Time.now().to_sec()
        stop.set()
        prober.join()
        cls.expected = sum(cls.sent.values()) + len(cls.service_calls) + len(cls.tune_calls)
        # Let the node drain its queues, then one more second of states for the bag.
        deadline = time.time() + 10.0
        while cls.refused() < cls.refused_before + cls.expected and time.time() < deadline:
            time.sleep(0.05)
        time.sleep(1.0)
        rospy.loginfo('flood: %d hostile messages in %.1f s (%.0f Hz) %s, %d service calls; '
                      '%d tuning calls; window waits %d', sum(cls.sent.values()), cls.flood_s,
                      sum(cls.sent.values()) / cls.flood_s, cls.sent, len(cls.service_calls),
                      len(cls.tune_calls), cls.window_waits)

    def test_a_the_flood_reached_1_khz(self):
        rate = sum(self.sent.values()) / self.flood_s
        print('flood rate: %.0f Hz, %d messages' % (rate, sum(self.sent.values())))
        self.assertGreaterEqual(rate, 1000.0)
        self.assertGreater(min(self.sent.values()), 0.2 * FLOOD_S * 1000.0)

    def test_b_the_node_kept_answering(self):
        with self.lock:
            stamps = [s for s, _, _ in self.stats if self.start_stamp <= s <= self.end_stamp + 1]
            calls = list(self.service_calls)
            tunes = list(self.tune_calls)
        gaps = [b - a for a, b in zip(stamps, stamps[1:])]
        print('largest gap between ~stats: %.3f s; %d grasp and %d tuning calls, slowest %.3f s' %
              (max(gaps), len(calls), len(tunes), max(c[0] for c in calls + tunes)))
        self.assertGreater(len(stamps), 0.8 * 10 * FLOOD_S)  # ~stats_rate 10 Hz
        self.assertLess(max(gaps), 1.0)
        self.assertGreater(len(calls), 2.0 * FLOOD_S)
        for latency, success, message in calls:
            self.assertLess(latency, 1.0)
            self.assertFalse(success)
            self.assertIn("unknown body 'nobody'", message)
        self.assertEqual(len(tunes), len(calls))
        for latency, config in tunes:
            self.assertLess(latency, 1.0)
            # Refused: the node answers with the values in effect, the scene's.
            self.assertEqual((config['body'], config['youngs_modulus'], config['density']),
                             ('', 1.0e5, 100.0))

    def test_c_the_step_rate_held(self):
        with self.lock:
            inside = [(s, step) for s, step, _ in self.stats
                      if self.start_stamp <= s <= self.end_stamp]
        (t0, s0), (t1, s1) = inside[0], inside[-1]
        rate = (s1 - s0) / (t1 - t0)
        print('step rate during the flood: %.1f Hz of %.0f (%.1f %%)' %
              (rate, NOMINAL_HZ, 100.0 * rate / NOMINAL_HZ))
        self.assertGreater(t1 - t0, 0.9 * FLOOD_S)
        self.assertGreaterEqual(rate, MIN_STEP_RATE * NOMINAL_HZ)

    def test_d_every_hostile_message_was_refused_and_counted(self):
        refused = self.refused() - self.refused_before
        print('refused %d of %d sent (%d on topics, %d grasp and %d tuning calls)' %
              (refused, self.expected, sum(self.sent.values()), len(self.service_calls),
               len(self.tune_calls)))
        self.assertEqual(refused, self.expected)

    def test_e_warnings_stayed_throttled_and_named_the_problem(self):
        with self.lock:
            texts = [m for s, m in self.warnings if self.start_stamp <= s <= self.end_stamp + 1]
        topics = ['~wrench', '~node_wrench', '~fixed_nodes', '~grasp', '~grasp (service)',
                  '~set_parameters']
        for topic in topics:
            mine = [m for m in texts if m.startswith(topic + ':')]
            self.assertGreater(len(mine), 0.5 * FLOOD_S, topic)
            self.assertLessEqual(len(mine), FLOOD_S + 2, topic)
            self.assertTrue(any(re.search(r'\d+ more dropped on ' + re.escape(topic), m)
                                for m in mine), mine[:3])
        print('%d warnings during the flood' % len(texts))
        self.assertLessEqual(len(texts), len(topics) * (FLOOD_S + 2))

    def test_f_the_flood_changed_nothing(self):
        applied = []
        states = 0
        with rosbag.Bag(self.bag) as bag:
            for topic, message, _ in bag.read_messages(topics=TOPICS):
                if topic.endswith('/applied') and (message.episode > 0 or
                                                   message.kind == Applied.RESET):
                    applied.append(message)
                elif topic.endswith('/state') and message.episode > 0:
                    states += 1
                    self.assertTrue(all(math.isfinite(c) for p in message.positions
                                        for c in (p.x, p.y, p.z)))
        # Only the good commands took effect, each once and in order; the grasp's frame is
        # moved every step while it holds.
        kinds = [m.kind for m in applied if m.kind != Applied.MOVE_GRASP]
        self.assertEqual(kinds, [Applied.RESET] + [kind for _, _, _, kind in GOOD])
        self.assertEqual(applied[-1].name, 'node_wrench:beam:group tip')
        moves = [m for m in applied if m.kind == Applied.MOVE_GRASP]
        grasped = next(m.step for m in applied if m.kind == Applied.GRASP)
        released = next(m.step for m in applied if m.kind == Applied.RELEASE_GRASP)
        self.assertTrue(all(m.name == 'hand' and grasped <= m.step <= released for m in moves))
        # The same log re-run without the flood gives the same states, step by step, bit for bit.
        result = subprocess.run(['rosrun', 'deformable_sim', 'deformable_sim_replay', '--quiet',
                                 self.bag], capture_output=True, text=True, timeout=120)
        self.assertEqual(result.returncode, 0, result.stderr)
        match = re.search(r'compared (\d+) recorded states: largest difference (\S+) m in position, '
                          r'(\S+) m/s in velocity \(bit-exact\)', result.stdout)
        self.assertIsNotNone(match, result.stdout)
        print('replay: %s' % result.stdout.strip().replace('\n', '; '))
        self.assertEqual(int(match.group(1)), states)
        self.assertGreater(states, MIN_STEP_RATE * NOMINAL_HZ * FLOOD_S)
        self.assertEqual(float(match.group(2)), 0.0)
        self.assertEqual(float(match.group(3)), 0.0)

    def test_g_the_block_rested_on_the_beam_through_it(self):
        # Contact between bodies ran all along: the beam carried the block's weight.
        weight = 0.06 ** 3 * 100.0 * 9.81
        with self.lock:
            resting = list(self.resting)
        self.assertGreater(len(resting), 10)
        carried = [z for z in resting if z is not None and abs(z - weight) < 0.1 * weight]
        self.assertGreater(len(carried), 0.9 * len(resting))


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'flood', Flood)
