#!/usr/bin/python3
"""rostest: converts a shared TUM sequence to a bag at test time (TUM or D435i topics), plays it
at rate 1 into the running tracking_node + mapping_node, saves the trajectory through the
mapper's service and checks: every frame synchronised and tracked, ATE within the allowed factor
of the offline ply_slam_tum run on the same frames; the occupancy grid is published and saved in
map_server's format; ~path comes at most once per ~path_period and its last poses are not held
back when the stream ends. Apart (~apart, the default), mapping_node mapped every keyframe: the
tracker followed an update for each."""
import os
import shutil
import subprocess
import sys
import unittest

import rospy
import rostest

import ros_test_support as support


class BagReplay(unittest.TestCase):
    def test_replay_matches_offline(self):
        sequence = support.shared_path(rospy.get_param("~sequence"))
        d435i = rospy.get_param("~d435i", False)
        factor = rospy.get_param("~ate_factor", 1.5)
        work = support.work_dir()
        self.addCleanup(shutil.rmtree, work, True)  # bags are tens of MB
        bag = os.path.join(work, "sequence.bag")
        support.tum_to_bag(sequence, bag, d435i)
        offline_frames, offline_ate = support.offline_run(sequence, os.path.join(work, "offline"))

        stats = support.StatsListener()
        path = support.PathListener()
        support.wait_for_nodes()
        subprocess.run(["rosbag", "play", "--quiet", "--delay=1", "--rate=1", bag], check=True)
        stats.wait_until(lambda s: s.get("tracked") + s.get("lost") >= offline_frames, 30)
        apart = rospy.get_param("~apart", True)
        if apart:  # mapping_node may be slower than the camera: waited for while it maps on
            self.assertTrue(stats.wait_while_progressing(
                lambda s: s.get("updates_followed") >= s.get("keyframes"),
                lambda s: s.get("updates_followed")),
                "mapping_node stopped mapping keyframes before the last (see its log): %s" %
                stats.values)

        trajectory = os.path.join(work, "ros_trajectory.txt")
        support.save_trajectory(trajectory)
        ate = support.ate_rmse(sequence, trajectory)
        print("offline: %d frames, ATE %.6f m; ROS: %s, ATE %.6f m over %d" % (
            offline_frames, offline_ate, stats.values, ate["rmse"], ate["pairs"]))
        self.assertEqual(stats.get("rgb_received"), offline_frames)
        self.assertEqual(stats.get("synchronised"), offline_frames, "synchroniser dropped frames")
        self.assertEqual(stats.get("skipped_bad"), 0)
        self.assertEqual(stats.get("tracked"), offline_frames)
        self.assertEqual(ate["pairs"], offline_frames)
        self.assertLessEqual(ate["rmse"], factor * offline_ate)
        if apart:
            self.assertGreater(stats.get("keyframes"), 0)
        support.check_grid(self, os.path.join(work, "saved_map"))
        path.check(self, rospy.get_param("~path_period", 1.0))


if __name__ == "__main__":
    rospy.init_node("bag_replay_test")
    rostest.rosrun("ply_slam", "bag_replay_test", BagReplay, sys.argv)
