#!/usr/bin/python3
"""Records the reference session (test/data/reference/session.bag) from a running
deformable_sim_node on test/data/reference/session.yaml; test/data/reference/record.launch starts
both. After a reset the bodies fall onto the slab and the table; a moving gripper frame grasps
the cube, lifts it and lets it go; a wrench pushes the rigid brick against it (not hard enough to
move both); the slab's edge is fixed and dragged over the table; a live tuning softens the
bodies; all is let go. Only the node's ~scene, ~applied and ~state are kept, compressed: what
deformable_sim_replay needs.

  roslaunch test/data/reference/record.launch     # from the package's folder
"""
import math
import os
import time

import dynamic_reconfigure.client
import rospy
import tf2_ros
from geometry_msgs.msg import Point, TransformStamped, WrenchStamped

from deformable_sim.msg import FixedNodes, Grasp
from sim_client import SimClient, connected, start_recording, stop_recording

NODE = '/deformable_sim'
TOPICS = [NODE + '/scene', NODE + '/applied', NODE + '/state']
BAG = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'data',
                   'reference', 'session.bag')
# (seconds after the reset, event); the node steps in real time at the scene's dt.
EVENTS = [(0.5, 'grasp'), (1.4, 'release'), (1.6, 'push'), (2.0, 'fix'), (2.4, 'drag'),
          (2.8, 'tune'), (3.2, 'stop pushing'), (3.6, 'let go'), (4.2, 'end')]
GRASP_AT = 0.5


def gripper_frame(t):
    """The gripper over the cube's top centre, lifted and turned a little once it holds."""
    s = max(0.0, t - GRASP_AT - 0.2)
    frame = TransformStamped()
    frame.header.stamp = rospy.Time.now()
    frame.header.frame_id = 'world'
    frame.child_frame_id = 'gripper'
    frame.transform.translation.x = -0.08 + 0.01 * math.sin(2.0 * s)
    frame.transform.translation.z = 0.12 + 0.02 * (1.0 - math.cos(2.0 * s))
    frame.transform.rotation.z = math.sin(0.2 * s)
    frame.transform.rotation.w = math.cos(0.2 * s)
    return frame


def main():
    rospy.init_node('record_session')
    sim = SimClient()
    wrench = rospy.Publisher(NODE + '/wrench', WrenchStamped, queue_size=10)
    fixed = rospy.Publisher(NODE + '/fixed_nodes', FixedNodes, queue_size=10)
    grasp = rospy.Publisher(NODE + '/grasp', Grasp, queue_size=10)
    tuner = dynamic_reconfigure.client.Client(NODE, timeout=10.0)
    broadcaster = tf2_ros.TransformBroadcaster()
    start = [time.time()]
    rospy.Timer(rospy.Duration(0.02),
                lambda _: broadcaster.sendTransform(gripper_frame(time.time() - start[0])))
    if os.path.exists(BAG):
        os.remove(BAG)
    recorder = start_recording(BAG, TOPICS, NODE, options=['--bz2'])
    connected(wrench, fixed, grasp)
    time.sleep(0.5)  # the gripper frame in the node's tf
    sim.reset()  # the session starts here: the bag holds all of it
    start[0] = time.time()
    for at, event in EVENTS:
        while time.time() - start[0] < at:
            time.sleep(0.01)
        if event == 'push':
            m = WrenchStamped()
            m.header.frame_id = 'brick'
            m.wrench.force.x, m.wrench.torque.z = -1.2, 0.002
            wrench.publish(m)
        elif event == 'fix':
            fixed.publish(FixedNodes(body='slab', action=FixedNodes.FIX, group='edge'))
        elif event == 'drag':
            fixed.publish(FixedNodes(body='slab', action=FixedNodes.FIX, group='edge',
                                     translation=Point(0.03, 0.0, 0.0)))
        elif event == 'tune':
            tuner.update_configuration({'youngs_modulus': 5.0e5, 'damping_mass': 2.0})
        elif event == 'grasp':
            m = Grasp(name='hand', body='cube', action=Grasp.ATTACH,
                      region=Grasp.REGION_SPHERE, sphere_radius=0.045)
            m.header.frame_id = 'gripper'
            grasp.publish(m)
        elif event == 'release':
            grasp.publish(Grasp(name='hand', action=Grasp.RELEASE))
        elif event == 'stop pushing':
            wrench.publish(WrenchStamped(header=rospy.Header(frame_id='brick')))
        elif event == 'let go':
            fixed.publish(FixedNodes(body='slab', action=FixedNodes.RELEASE, group='edge'))
    stop_recording(recorder, BAG)
    print('wrote %s (%d bytes)' % (BAG, os.path.getsize(BAG)))


if __name__ == '__main__':
    main()
