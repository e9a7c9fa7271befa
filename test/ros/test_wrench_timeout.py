#!/usr/bin/python3
"""With ~wrench_timeout set, a wrench that is not renewed stops acting after that time."""
import unittest

import rospy
import rostest
from geometry_msgs.msg import WrenchStamped

from sim_client import SimClient, connected


class WrenchTimeout(unittest.TestCase):
    def test_an_old_wrench_expires(self):
        sim = SimClient()
        publisher = rospy.Publisher('/deformable_sim/wrench', WrenchStamped, queue_size=10)
        connected(publisher)
        timeout = rospy.get_param('/deformable_sim/wrench_timeout')
        message = WrenchStamped()
        message.header.frame_id = 'beam/tip'
        message.wrench.force.z = -0.5
        publisher.publish(message)
        applied = sim.wait('stats', lambda m: m.bodies[0].applied_wrenches == 1).header.stamp
        # Renewed in time, it stays.
        for _ in range(4):
            rospy.sleep(0.5 * timeout)
            publisher.publish(message)
        self.assertEqual(sim.wait('stats').bodies[0].applied_wrenches, 1)
        expired = sim.wait('stats', lambda m: m.bodies[0].applied_wrenches == 0).header.stamp
        self.assertGreater((expired - applied).to_sec(), 2.0 * timeout)


if __name__ == '__main__':
    rospy.init_node('test_wrench_timeout')
    rostest.rosrun('deformable_sim', 'wrench_timeout', WrenchTimeout)
