#!/usr/bin/python3
"""rostest: fr1_xyz_37 played slowly into both nodes with the mapping side in mapping_node
(tracking_node ~mapping_apart, mapping_node ~map_keyframes); tracking_node is killed a third of the
way in and started again a few frames later. The restarted tracker must take over mapping_node's
map (~map_for_tracker), relocalise in it at its first frame and extend it: the map mapping_node
saves holds the first tracker's first keyframe and the new tracker's keyframes (ids after the
first tracker's, none given twice), loads again, and every pose it received is in one world (ATE
as offline)."""
import shutil
import subprocess
import sys
import time
import unittest

import rospy
import rostest

import checked_run
import ros_test_support as support

TRACKER = "/ply_slam/tracking_node"


class TrackerRestart(unittest.TestCase):
    def test_restarted_tracker_goes_on_in_the_mappers_map(self):
        sequence = support.shared_path(rospy.get_param("~sequence"))
        work = support.work_dir()
        self.addCleanup(shutil.rmtree, work, True)
        frames, offline_ate, stats, player = support.slow_replay(sequence, work)
        self.assertTrue(stats.wait_until(lambda s: s.get("keyframes") >= 3, 60))
        first_keyframes = stats.get("keyframes")
        first_tracked = stats.get("tracked")
        checked_run.run(["rosnode", "kill", TRACKER])
        time.sleep(2)  # frames go by untracked
        stats.values = {}
        tracker = subprocess.Popen([support.tool("tracking_node"), "__name:=tracking_node",
                                    "__ns:=/ply_slam"])
        self.addCleanup(tracker.terminate)
        self.assertEqual(player.wait(timeout=120), 0)
        time.sleep(3)  # the last frames are tracked, their keyframes mapped
        self.assertTrue(stats.wait_until(lambda s: s.get("tracked") > 0, 30),
                        "the restarted tracker tracked nothing: %s" % stats.values)
        later = stats.values.copy()

        message, ate, saved, ids, folder = support.saved_trajectory_and_map(sequence, work)
        print("first tracker: %d tracked, %d keyframes; restarted: %s; trajectory: %s, ATE %.6f m "
              "over %d (offline %.6f); map: %s, keyframe ids %s" % (
                  first_tracked, first_keyframes, later, message, ate["rmse"], ate["pairs"],
                  offline_ate, saved.message, ids))
        self.assertEqual(later.get("lost", 0), 0, "the restarted tracker did not relocalise at once")
        self.assertGreater(later.get("keyframes", 0), 0, "the restarted tracker made no keyframe")
        self.assertEqual(ate["pairs"], first_tracked + later["tracked"])
        self.assertLessEqual(ate["rmse"], 1.5 * offline_ate)
        self.assertIn(0, ids, "the first tracker's first keyframe is not in the map")
        self.assertGreaterEqual(max(ids), first_keyframes, "no keyframe of the new tracker")
        self.assertEqual(len(ids), len(set(ids)))
        self.assertEqual(support.load_saved_map(sequence, folder, work)["first_tracked_frame"], 0)


if __name__ == "__main__":
    rospy.init_node("tracker_restart_test")
    rostest.rosrun("ply_slam", "tracker_restart_test", TrackerRestart, sys.argv)
