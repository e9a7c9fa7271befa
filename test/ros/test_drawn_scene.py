#!/usr/bin/python3
"""What a user sees of a scene in rviz: the obstacles on the latched ~obstacles (shapes as shapes,
a mesh as its file, in grey), each body's surface on ~mesh in its own colour, and a mesh, not a
DELETEALL, as the first message a new ~mesh subscriber gets."""
import math
import os
import threading
import time
import unittest

import rospy
import rostest
from visualization_msgs.msg import Marker, MarkerArray

from sim_client import SimClient

NODE = '/deformable_sim'
GREY = (0.6, 0.6, 0.6)
RIGHT_COLOUR = (0.1, 0.8, 0.3)  # drawn_scene.yaml, bodies[1].colour
STL = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                    '..', 'data', 'meshes', 'cube_binary.stl'))


def rgb(colour):
    return (colour.r, colour.g, colour.b)


def close(a, b, tolerance=1e-6):
    return all(abs(x - y) <= tolerance for x, y in zip(a, b))


def first_message(topic, kind, timeout=10.0):
    """The very first message a subscription made now receives."""
    got = []
    done = threading.Event()

    def keep(message):
        if not done.is_set():
            got.append(message)
            done.set()

    subscriber = rospy.Subscriber(topic, kind, keep, queue_size=100)
    assert done.wait(timeout), 'nothing on %s within %.0f s' % (topic, timeout)
    subscriber.unregister()
    return got[0]


class DrawnScene(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_drawn_scene')
        cls.sim = SimClient()
        time.sleep(1.0)  # the node is up and has drawn its obstacles before anyone asks
        # The first subscriber of ~mesh there is: the one an earlier node greeted with a DELETEALL.
        cls.first_mesh = first_message(NODE + '/mesh', Marker)

    def test_obstacles_are_latched_shapes_in_grey(self):
        array = first_message(NODE + '/obstacles', MarkerArray)
        self.assertEqual(array.markers[0].action, Marker.DELETEALL)
        markers = {m.id: m for m in array.markers[1:]}
        self.assertEqual(sorted(markers), [0, 1, 2, 3])
        for m in markers.values():
            self.assertEqual(m.ns, 'obstacles')
            self.assertEqual(m.header.frame_id, 'world')
            self.assertTrue(close(rgb(m.color), GREY) and m.color.a == 1.0, m.color)
        floor, ball, post, ramp = (markers[k] for k in range(4))
        self.assertEqual(floor.type, Marker.CUBE)
        self.assertTrue(close((floor.scale.x, floor.scale.y, floor.scale.z), (2.0, 1.0, 0.1)))
        self.assertTrue(close((floor.pose.position.z, floor.pose.orientation.w), (-0.05, 1.0)))
        self.assertEqual(ball.type, Marker.SPHERE)
        self.assertTrue(close((ball.scale.x, ball.scale.y, ball.scale.z), (0.2, 0.2, 0.2)))
        self.assertTrue(close((ball.pose.position.x, ball.pose.position.y), (0.5, 0.3)))
        self.assertEqual(post.type, Marker.CYLINDER)
        self.assertTrue(close((post.scale.x, post.scale.y, post.scale.z), (0.1, 0.1, 0.4)))
        q = post.pose.orientation  # yaw 0.3 rad
        self.assertTrue(close((q.x, q.y, q.z, q.w), (0, 0, math.sin(0.15), math.cos(0.15))), q)
        self.assertEqual(ramp.type, Marker.MESH_RESOURCE)
        self.assertTrue(ramp.mesh_resource.startswith('file://'), ramp.mesh_resource)
        self.assertEqual(os.path.realpath(ramp.mesh_resource[len('file://'):]),
                         os.path.realpath(STL))
        self.assertTrue(close((ramp.scale.x, ramp.scale.y, ramp.scale.z), (0.3, 0.2, 0.05)))
        q = ramp.pose.orientation  # roll 0.2 rad
        self.assertTrue(close((q.x, q.y, q.z, q.w), (math.sin(0.1), 0, 0, math.cos(0.1))), q)

    def test_first_mesh_message_is_a_mesh(self):
        marker = self.first_mesh
        self.assertEqual(marker.action, Marker.ADD)
        self.assertEqual(marker.type, Marker.TRIANGLE_LIST)
        self.assertGreater(len(marker.points), 0)

    def test_bodies_have_their_own_colours(self):
        colours = {}
        got = threading.Event()

        def keep(marker):
            if marker.action == Marker.ADD:
                colours[marker.ns] = rgb(marker.color)
            if len(colours) == 2:
                got.set()

        subscriber = rospy.Subscriber(NODE + '/mesh', Marker, keep, queue_size=100)
        self.assertTrue(got.wait(10.0), colours)
        subscriber.unregister()
        self.assertFalse(close(colours['left'], colours['right'], 0.05), colours)
        self.assertTrue(close(colours['right'], RIGHT_COLOUR), colours)


if __name__ == '__main__':
    rostest.rosrun('deformable_sim', 'test_drawn_scene', DrawnScene)
