#!/usr/bin/python3
"""A session the node itself recorded, measured by its own outputs with a lab's noise put on them
(the tip's frame as a tracked marker, 1 mm; the clamp's reaction as a force/torque sensor,
0.02 N and 0.002 N m; both at the stamps the node gave them) and driven by abrupt commands (a
wrench step on the tip, the tip held by fixed nodes and jumped 2 cm, their release) and a smooth
one (a swaying wrench on the middle). The node stamps each output at the simulated instant it
shows, so at the true material the re-simulation meets every sample to its noise, the impacts
included; fitted from E and damping 2.5 times off, it finds them again."""
import math
import os
import random
import re
import shutil
import subprocess
import tempfile
import time
import unittest

import rosbag
import rospy
import rostest
from geometry_msgs.msg import TransformStamped, Vector3, Wrench, WrenchStamped
from tf2_msgs.msg import TFMessage

from deformable_sim.msg import FixedNodes, NodeWrench
from sim_client import SimClient, connected, start_recording, stop_recording

NODE = '/deformable_sim'
TOPICS = [NODE + '/scene', NODE + '/applied', NODE + '/state']
MARKER_NOISE, FORCE_NOISE, TORQUE_NOISE = 0.001, 0.02, 0.002  # m, N, N m
TRUE_E, TRUE_MASS_DAMPING, TRUE_STIFFNESS_DAMPING = 2.0e5, 1.0, 0.005  # identify_beam.yaml
SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'data', 'scenes',
                     'identify_beam.yaml')


def upward(force):
    """A wrench of `force` N up."""
    return Wrench(force=Vector3(0.0, 0.0, force))


def identify(fit_file):
    return subprocess.run(['rosrun', 'deformable_sim', 'deformable_sim_identify', fit_file,
                           '--threads', '2'], capture_output=True, text=True, timeout=240)


class IdentifyRecorded(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_identify_recorded')
        cls.folder = tempfile.mkdtemp()
        cls.bag = os.path.join(cls.folder, 'session.bag')
        cls.tip, cls.reaction = [], []
        rospy.Subscriber('/tf', TFMessage, cls.on_tf, queue_size=1000)
        rospy.Subscriber(NODE + '/reactions/beam', WrenchStamped, cls.on_reaction,
                         queue_size=1000)
        cls.sim = SimClient()
        cls.record_session()
        cls.add_measurements()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder, ignore_errors=True)

    @classmethod
    def on_tf(cls, message):
        cls.tip.extend(t for t in message.transforms if t.child_frame_id == 'beam/tip')

    @classmethod
    def on_reaction(cls, message):
        cls.reaction.append(message)

    @classmethod
    def record_session(cls):
        recorder = start_recording(cls.bag, TOPICS)
        wrench = rospy.Publisher(NODE + '/node_wrench', NodeWrench, queue_size=100)
        fixed = rospy.Publisher(NODE + '/fixed_nodes', FixedNodes, queue_size=10)
        connected(wrench, fixed)
        cls.sim.reset()  # the session starts here
        start = time.time()
        events = [(0.5, 'push'), (1.5, 'let go'), (2.5, 'hold'), (3.0, 'jump'), (3.8, 'release'),
                  (4.5, 'sway'), (6.0, 'end')]
        for at, event in events:
            while time.time() - start < at:
                time.sleep(0.005)
            if event == 'push':  # a step of 0.5 N up on the tip
                wrench.publish(NodeWrench(body='beam', group='tip', wrench=upward(0.5)))
            elif event == 'let go':
                wrench.publish(NodeWrench(body='beam', group='tip'))
            elif event == 'hold':
                fixed.publish(FixedNodes(body='beam', action=FixedNodes.FIX, group='tip'))
            elif event == 'jump':  # the held tip 2 cm up in one step
                fixed.publish(FixedNodes(body='beam', action=FixedNodes.FIX, group='tip',
                                         translation=Vector3(0.0, 0.0, 0.02)))
            elif event == 'release':
                fixed.publish(FixedNodes(body='beam', action=FixedNodes.RELEASE, group='tip'))
            elif event == 'sway':  # 1.5 Hz on the middle, sent at 50 Hz
                while time.time() - start < 5.5:
                    t = time.time() - start
                    force = 0.2 * math.sin(2.0 * math.pi * 1.5 * (t - 4.5))
                    wrench.publish(NodeWrench(body='beam', group='middle', wrench=upward(force)))
                    time.sleep(0.02)
                wrench.publish(NodeWrench(body='beam', group='middle'))
        stop_recording(recorder, cls.bag)

    @classmethod
    def add_measurements(cls):
        """The lab's measurements, with noise, at the stamps the node gave the outputs."""
        noise = random.Random(3)
        with rosbag.Bag(cls.bag, 'a') as bag:
            for t in cls.tip:
                marker = TransformStamped()
                marker.header = t.header
                marker.child_frame_id = 'marker_tip'
                marker.transform.rotation.w = 1.0
                p = t.transform.translation
                marker.transform.translation = Vector3(
                    p.x + noise.gauss(0, MARKER_NOISE), p.y + noise.gauss(0, MARKER_NOISE),
                    p.z + noise.gauss(0, MARKER_NOISE))
                bag.write('/tf', TFMessage([marker]), t.header.stamp)
            for r in cls.reaction:
                measured = WrenchStamped(header=r.header)
                for part, sigma in (('force', FORCE_NOISE), ('torque', TORQUE_NOISE)):
                    value = getattr(r.wrench, part)
                    setattr(measured.wrench, part, Vector3(
                        value.x + noise.gauss(0, sigma), value.y + noise.gauss(0, sigma),
                        value.z + noise.gauss(0, sigma)))
                bag.write('/ft_sensor/wrench', measured, r.header.stamp)

    def fit_file(self, name, scale):
        """A fit of E and both dampings from the scene with them `scale` times their truth."""
        with open(SCENE) as f:
            scene = f.read()
        scene = scene.replace('youngs_modulus: 2.0e5', 'youngs_modulus: %g' % (TRUE_E * scale))
        scene = scene.replace('damping: {mass: 1.0, stiffness: 0.005}',
                              'damping: {mass: %g, stiffness: %g}' % (
                                  TRUE_MASS_DAMPING * scale, TRUE_STIFFNESS_DAMPING * scale))
        scene_file = os.path.join(self.folder, name + '_scene.yaml')
        with open(scene_file, 'w') as f:
            f.write(scene)
        fit = os.path.join(self.folder, name + '.yaml')
        with open(fit, 'w') as f:
            f.write('''bag: session.bag
scene: %s
fit:
  - {body: beam, parameter: youngs_modulus, min: 1.0e4, max: 1.0e7}
  - {body: beam, parameter: damping_mass, min: 0.0, max: 10.0}
  - {body: beam, parameter: damping_stiffness, min: 0.0, max: 0.05}
observations:
  - {tf: marker_tip, body: beam, at: [0.4, 0.0, 0.0], sigma: %g}
  - {wrench: /ft_sensor/wrench, reactions: beam, sigma: [%g, %g]}
out: %s_fitted.yaml
''' % (scene_file, MARKER_NOISE, FORCE_NOISE, TORQUE_NOISE, name))
        return fit

    def test_the_session_was_driven_as_planned(self):
        self.assertGreater(len(self.tip), 500)
        self.assertGreater(len(self.reaction), 500)

    def test_at_the_true_material_every_observation_is_met_to_its_noise(self):
        result = identify(self.fit_file('truth', 1.0))
        marker = re.search(r'RMS residual observations\[0\] \(tf marker_tip\): (\S+) m before',
                           result.stdout)
        sensor = re.search(r'RMS residual observations\[1\] \(wrench /ft_sensor/wrench\): (\S+) N '
                           r'(\S+) N m before', result.stdout)
        self.assertIsNotNone(marker, result.stdout + result.stderr)
        self.assertIsNotNone(sensor, result.stdout + result.stderr)
        # The test heard the node before the reset the session starts at: those samples are
        # outside it, counted and left out.
        self.assertRegex(result.stdout, r'observations\[0\] \(marker_tip\): [0-9]+ samples '
                         r'outside the recorded session left out')
        for measured, noise in ((marker.group(1), MARKER_NOISE), (sensor.group(1), FORCE_NOISE),
                                (sensor.group(2), TORQUE_NOISE)):
            self.assertAlmostEqual(float(measured), noise, delta=0.1 * noise, msg=result.stdout)

    def test_from_two_and_a_half_times_off_the_fit_finds_the_material(self):
        result = identify(self.fit_file('off', 2.5))
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        fitted = {name: (float(value), float(sigma)) for name, value, sigma in
                  re.findall(r'fitted beam (\S+) (\S+) ± (\S+)', result.stdout)}
        for name, truth, within in (('youngs_modulus', TRUE_E, 0.01),
                                    ('damping_stiffness', TRUE_STIFFNESS_DAMPING, 0.1),
                                    ('damping_mass', TRUE_MASS_DAMPING, 0.2)):
            value, sigma = fitted[name]
            self.assertAlmostEqual(value / truth, 1.0, delta=within, msg=result.stdout)
            # A session driven in real time differs run to run: one value in 20 misses 2 sigma
            # by chance (the coverage test counts that on fixed draws); 3 sigma here.
            self.assertLessEqual(abs(value - truth), 3.0 * sigma, msg=result.stdout)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'identify_recorded', IdentifyRecorded)
