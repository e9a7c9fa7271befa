"""A small client of deformable_sim_node for the rostests: latest messages, services, waits."""
import math
import os
import signal
import subprocess
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
import tf2_ros
from geometry_msgs.msg import WrenchStamped
from std_srvs.srv import Trigger
from visualization_msgs.msg import Marker

from deformable_sim.msg import BodyState, NodeWrench, Stats
from deformable_sim.srv import Step


class SimClient:
    def __init__(self, node='/deformable_sim'):
        self.node = node
        self._lock = threading.Lock()
        # Each newest message with the clock time it came: a message is stamped with the
        # simulated instant it shows, which may be a little before the tick that sent it.
        self._state = None
        self._states = {}  # the newest state of each body (a scene's bodies publish in turn)
        self._stats = None
        rospy.Subscriber(node + '/state', BodyState, self._on_state, queue_size=10)
        rospy.Subscriber(node + '/stats', Stats, self._on_stats, queue_size=10)
        for name in ('pause', 'resume', 'reset', 'step'):
            rospy.wait_for_service(node + '/' + name, timeout=30.0)
        self.pause = rospy.ServiceProxy(node + '/pause', Trigger)
        self.resume = rospy.ServiceProxy(node + '/resume', Trigger)
        self.reset = rospy.ServiceProxy(node + '/reset', Trigger)
        self.step = rospy.ServiceProxy(node + '/step', Step)

    def _on_state(self, message):
        with self._lock:
            self._state = (message, rospy.Time.now())
            self._states[message.body] = self._state

    def _on_stats(self, message):
        with self._lock:
            self._stats = (message, rospy.Time.now())

    def wait(self, what, predicate=lambda m: True, timeout=10.0, body=None):
        """The newest state (of `body`, if given) or stats message published after this call
        for which predicate holds."""
        since = rospy.Time.now()
        deadline = time.time() + timeout
        while time.time() < deadline and not rospy.is_shutdown():
            with self._lock:
                if what == 'state':
                    newest = self._state if body is None else self._states.get(body)
                else:
                    newest = self._stats
            if newest is not None and newest[1] >= since and predicate(newest[0]):
                return newest[0]
            time.sleep(0.02)
        raise AssertionError('no %s message of the expected kind within %.0f s' % (what, timeout))

    def state_at(self, step, timeout=10.0):
        return self.wait('state', lambda m: m.step == step, timeout)



def surface_marker(topic, timeout=10.0):
    """The first TRIANGLE_LIST on a node's ~mesh (skipping the DELETEALL of one that stops)."""
    deadline = time.time() + timeout
    while True:
        marker = rospy.wait_for_message(topic, Marker, timeout=max(deadline - time.time(), 0.1))
        if marker.action != Marker.DELETEALL:
            return marker


class FrameBroadcaster:
    """Broadcasts one tf frame at 50 Hz, as a robot would; set `transform` to move it."""

    def __init__(self):
        self.transform = None
        self._broadcaster = tf2_ros.TransformBroadcaster()
        self._timer = rospy.Timer(rospy.Duration(0.02), self._send)

    def _send(self, event):
        transform = self.transform
        if transform is not None:
            transform.header.stamp = rospy.Time.now()
            self._broadcaster.sendTransform(transform)


def node_wrench(body='beam', nodes=(), group='', force=(0, 0, 0), torque=(0, 0, 0), frame=''):
    m = NodeWrench(body=body, nodes=list(nodes), group=group)
    m.header.frame_id = frame
    m.wrench.force.x, m.wrench.force.y, m.wrench.force.z = force
    m.wrench.torque.x, m.wrench.torque.y, m.wrench.torque.z = torque
    return m


def wrench_stamped(frame, force=(0, 0, 0), torque=(0, 0, 0)):
    m = WrenchStamped()
    m.header.frame_id = frame
    m.wrench.force.x, m.wrench.force.y, m.wrench.force.z = force
    m.wrench.torque.x, m.wrench.torque.y, m.wrench.torque.z = torque
    return m


def grasp_when_in_tf(grasp, request, timeout=10.0):
    """Calls the ~grasp service, again while the node's tf listener has not yet heard of the
    request's frame (it hears of a new frame some time after the test's own buffer does)."""
    deadline = rospy.Time.now() + rospy.Duration(timeout)
    answer = grasp(request)
    while not answer.success and 'not in tf' in answer.message and rospy.Time.now() < deadline:
        rospy.sleep(0.1)
        answer = grasp(request)
    return answer


def connected(*publishers, timeout=10.0):
    """Waits until every publisher has a subscriber (else the first messages are lost)."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        if all(p.get_num_connections() > 0 for p in publishers):
            return
        time.sleep(0.02)
    raise AssertionError('the node did not subscribe to %s' % [p.name for p in publishers])


def start_recording(bag, topics, node='/deformable_sim', timeout=20.0, options=()):
    """Starts rosbag record of topics into bag (with rosbag record's options, e.g. --bz2);
    returns once the node publishes every topic to it (else the first messages are missing from
    the bag)."""
    recorder = subprocess.Popen(['rosbag', 'record'] + list(options) + ['-O', bag] + list(topics),
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                start_new_session=True)
    caller = rospy.get_name()
    server = xmlrpc.client.ServerProxy(rosgraph.Master(caller).lookupNode(node))
    deadline = time.time() + timeout
    while time.time() < deadline:
        connections = server.getBusInfo(caller)[2]
        out = {c[4] for c in connections if c[2] == 'o' and 'record' in c[1]}
        if all(t in out for t in topics):
            return recorder
        time.sleep(0.1)
    raise AssertionError('rosbag record did not subscribe to %s' % list(topics))


def stop_recording(recorder, bag):
    """Stops rosbag record (SIGINT to it and its recorder: the bag is closed) and waits for the
    bag."""
    os.killpg(recorder.pid, signal.SIGINT)
    recorder.wait(timeout=30)
    deadline = time.time() + 10.0
    while not os.path.exists(bag) and time.time() < deadline:
        time.sleep(0.1)
    assert os.path.exists(bag), 'rosbag record wrote no bag'


def positions(state):
    return [(p.x, p.y, p.z) for p in state.positions]


def all_finite(points):
    return all(math.isfinite(c) for p in points for c in p)
