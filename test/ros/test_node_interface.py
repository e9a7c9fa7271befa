#!/usr/bin/python3
"""deformable_sim_node on its built-in default scene, driven as a user would: markers, tf, state,
pause / step / resume / reset, fixing and releasing nodes by topic."""
import math
import unittest

import dynamic_reconfigure.client
import rospy
import rostest
import tf2_ros
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from geometry_msgs.msg import Point, TransformStamped, Vector3, WrenchStamped
from visualization_msgs.msg import Marker

from deformable_sim.msg import FixedNodes
from sim_client import SimClient, all_finite, connected, positions, surface_marker

# The default scene: a 0.5 x 0.1 x 0.1 m box in 16 x 4 x 4 cells, six tetrahedra a cell.
CELLS = (16, 4, 4)
NODES = (CELLS[0] + 1) * (CELLS[1] + 1) * (CELLS[2] + 1)
SURFACE_TRIANGLES = 4 * (CELLS[0] * CELLS[1] + CELLS[0] * CELLS[2] + CELLS[1] * CELLS[2])
TIP_NODES = (CELLS[1] + 1) * (CELLS[2] + 1)
CLAMPED_NODES = TIP_NODES


class NodeInterface(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_node_interface')
        cls.sim = SimClient()
        cls.fixed_pub = rospy.Publisher('/deformable_sim/fixed_nodes', FixedNodes, queue_size=10)
        connected(cls.fixed_pub)

    def setUp(self):
        self.sim.resume()

    def test_mesh_marker_is_the_surface(self):
        marker = surface_marker('/deformable_sim/mesh')
        self.assertEqual(marker.type, Marker.TRIANGLE_LIST)
        self.assertEqual(marker.header.frame_id, 'world')
        self.assertGreater(marker.header.stamp.to_sec(), 0.0)
        self.assertEqual(marker.ns, 'beam')
        self.assertEqual(len(marker.points), 3 * SURFACE_TRIANGLES)
        self.assertTrue(all_finite([(p.x, p.y, p.z) for p in marker.points]))
        # Outward normals: the signed volume enclosed by the surface is the box's.
        volume = 0.0
        for k in range(0, len(marker.points), 3):
            a, b, c = marker.points[k:k + 3]
            volume += (a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) +
                       a.z * (b.x * c.y - b.y * c.x)) / 6.0
        self.assertAlmostEqual(volume, 0.5 * 0.1 * 0.1, delta=0.005 * 0.005)

    def test_body_frame_in_tf_is_its_centroid(self):
        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        t = buffer.lookup_transform('world', 'beam', rospy.Time(0), rospy.Duration(10.0))
        # The clamped beam sags a little under gravity; its centroid stays near (0.25, 0, 0).
        self.assertAlmostEqual(t.transform.translation.x, 0.25, delta=0.01)
        self.assertAlmostEqual(t.transform.translation.y, 0.0, delta=1e-5)  # a symmetric mesh
        self.assertLess(t.transform.translation.z, 0.0)
        self.assertGreater(t.transform.translation.z, -0.1)
        tip = buffer.lookup_transform('world', 'beam/tip', rospy.Time(0), rospy.Duration(10.0))
        self.assertAlmostEqual(tip.transform.translation.x, 0.5, delta=0.02)

    def test_state_has_every_node(self):
        state = self.sim.wait('state')
        self.assertEqual(state.body, 'beam')
        self.assertEqual(state.header.frame_id, 'world')
        self.assertEqual(len(state.node_ids), NODES)
        self.assertEqual(sorted(state.node_ids), list(range(1, NODES + 1)))
        self.assertEqual(len(state.positions), NODES)
        self.assertEqual(len(state.velocities), NODES)
        self.assertTrue(all_finite(positions(state)))

    def test_pause_step_resume_reset_count_steps_exactly(self):
        self.assertTrue(self.sim.pause().success)
        paused = self.sim.wait('stats', lambda m: m.paused)
        start = self.sim.step(0).step
        self.assertEqual(paused.step, start)
        rospy.sleep(0.3)  # the timer keeps ticking but takes no step
        self.assertEqual(self.sim.wait('state').step, start)
        answer = self.sim.step(7)
        self.assertTrue(answer.success, answer.message)
        self.assertEqual(answer.step, start + 7)
        self.assertEqual(self.sim.state_at(start + 7).step, start + 7)
        self.assertEqual(self.sim.step(25).step, start + 32)
        self.assertTrue(self.sim.resume().success)
        self.sim.wait('state', lambda m: m.step > start + 40)
        refused = self.sim.step(3)
        self.assertFalse(refused.success)
        self.assertIn('pause', refused.message)
        self.assertTrue(self.sim.pause().success)
        self.assertTrue(self.sim.reset().success)
        self.assertEqual(self.sim.step(0).step, 0)
        state = self.sim.state_at(0)
        # Back at the rest shape: the box, undeformed.
        xs = [p.x for p in state.positions]
        zs = [p.z for p in state.positions]
        self.assertAlmostEqual(min(xs), 0.0, places=12)
        self.assertAlmostEqual(max(xs), 0.5, places=12)
        self.assertAlmostEqual(min(zs), -0.05, places=12)
        self.assertAlmostEqual(max(zs), 0.05, places=12)
        self.assertEqual(max(abs(v.x) + abs(v.y) + abs(v.z) for v in state.velocities), 0.0)

    def test_fix_drag_and_release_by_topic(self):
        self.sim.pause()
        self.sim.reset()
        rest = positions(self.sim.state_at(0))
        message = FixedNodes(body='beam', action=FixedNodes.FIX, group='tip',
                             translation=Vector3(0.0, 0.0, 0.04))
        self.fixed_pub.publish(message)
        stats = self.sim.wait('stats', lambda m: m.bodies[0].fixed_nodes == CLAMPED_NODES + TIP_NODES)
        self.assertEqual(stats.dropped_messages, 0, stats.last_refusal)
        self.sim.step(1)
        state = self.sim.state_at(1)
        tip = [k for k, p in enumerate(rest) if abs(p[0] - 0.5) < 1e-9]
        self.assertEqual(len(tip), TIP_NODES)
        for k in tip:  # dragged up by exactly 4 cm in one step
            moved = [a - b for a, b in zip(positions(state)[k], rest[k])]
            self.assertAlmostEqual(moved[0], 0.0, places=12)
            self.assertAlmostEqual(moved[2], 0.04, places=12)
        self.fixed_pub.publish(FixedNodes(body='beam', action=FixedNodes.RELEASE, group='tip'))
        self.sim.wait('stats', lambda m: m.bodies[0].fixed_nodes == CLAMPED_NODES)
        # Fix a region (a sphere around the middle of the beam) in place.
        region = FixedNodes(body='beam', action=FixedNodes.FIX, region=FixedNodes.REGION_SPHERE,
                            sphere_center=Point(0.25, 0.0, 0.02), sphere_radius=0.06)
        self.fixed_pub.publish(region)
        stats = self.sim.wait('stats', lambda m: m.bodies[0].fixed_nodes > CLAMPED_NODES)
        held = stats.bodies[0].fixed_nodes - CLAMPED_NODES
        self.assertGreater(held, 0)
        before = positions(self.sim.state_at(1))
        self.sim.step(5)
        after = positions(self.sim.state_at(6))
        still = sum(1 for a, b in zip(before, after) if a == b)
        self.assertEqual(still, CLAMPED_NODES + held)
        region.action = FixedNodes.RELEASE
        self.fixed_pub.publish(region)
        self.sim.wait('stats', lambda m: m.bodies[0].fixed_nodes == CLAMPED_NODES)
        self.sim.reset()

    def test_wrench_in_another_tf_frame_acts_on_the_nodes_near_its_origin(self):
        # A "finger" frame 1 cm beyond the free end, turned 90 degrees about x.
        broadcaster = tf2_ros.StaticTransformBroadcaster()
        finger = TransformStamped()
        finger.header.stamp = rospy.Time.now()
        finger.header.frame_id = 'world'
        finger.child_frame_id = 'finger'
        finger.transform.translation.x = 0.51
        finger.transform.rotation.x = math.sqrt(0.5)
        finger.transform.rotation.w = math.sqrt(0.5)
        broadcaster.sendTransform(finger)
        publisher = rospy.Publisher('/deformable_sim/wrench', WrenchStamped, queue_size=10)
        connected(publisher)
        def tip_height_after_20_steps():
            self.sim.step(20)
            return max(p.z for p in self.sim.state_at(20).positions if p.x > 0.45)

        self.sim.pause()
        self.sim.reset()
        sagging = tip_height_after_20_steps()
        self.sim.reset()
        rospy.sleep(0.5)  # the static transform reaches the node's tf buffer
        push = WrenchStamped()
        push.header.frame_id = 'finger'
        push.wrench.force.y = 1.0  # the finger's y is the world's z
        publisher.publish(push)
        stats = self.sim.wait('stats', lambda m: m.bodies[0].applied_wrenches == 1)
        self.assertEqual(stats.dropped_messages, 0, stats.last_refusal)
        # Pushed up against gravity: the end sags less (by about 2.5 cm after 0.2 s).
        self.assertGreater(tip_height_after_20_steps(), sagging + 0.01)
        push.wrench.force.y = 0.0
        publisher.publish(push)
        self.sim.wait('stats', lambda m: m.bodies[0].applied_wrenches == 0)
        self.sim.reset()

    def test_diagnostics_report_the_simulation(self):
        deadline = rospy.Time.now() + rospy.Duration(10.0)
        while rospy.Time.now() < deadline:
            array = rospy.wait_for_message('/diagnostics', DiagnosticArray, timeout=10.0)
            ours = [s for s in array.status if s.name.endswith('simulation')]
            if ours:
                break
        self.assertTrue(ours)
        values = {v.key: v.value for v in ours[0].values}
        self.assertIn(ours[0].level, (DiagnosticStatus.OK, DiagnosticStatus.WARN))
        self.assertIn('real-time factor', values)
        self.assertIn('dropped messages', values)
        self.assertEqual(ours[0].hardware_id, 'deformable_sim')

    def test_live_tuning_stiffens_the_beam_between_steps(self):
        def sag_after(steps):
            self.sim.pause()
            self.sim.reset()
            self.sim.step(steps)
            return min(p.z for p in self.sim.state_at(steps).positions) + 0.05

        soft = sag_after(30)
        client = dynamic_reconfigure.client.Client('/deformable_sim', timeout=10.0)
        config = client.get_configuration(timeout=10.0)
        self.assertEqual(config['youngs_modulus'], 1.0e5)  # the scene's value
        self.assertEqual(config['density'], 100.0)
        client.update_configuration({'youngs_modulus': 1.0e7})
        stiff = sag_after(30)  # a reset keeps what was tuned
        self.assertLess(soft, -0.01)
        self.assertLess(abs(stiff), 0.1 * abs(soft))
        client.update_configuration({'youngs_modulus': 1.0e5})
        self.assertAlmostEqual(sag_after(30), soft, places=9)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'node_interface', NodeInterface)
