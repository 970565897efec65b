#!/usr/bin/python3
"""rostest: fr1_xyz_37 played slowly into both nodes; mapping_node is killed a third of the way in
and started again a few frames later. The restarted mapper must notice what it missed, get the
tracker's whole map and trajectory back, save a whole trajectory (every frame, ATE as offline) and
a map that holds the keyframes it never received itself, and say its dense maps are partial.
With ~apart (the mapping side in mapping_node) the restarted node asks the tracker to hand over
its copy of the map, maps the later keyframes on from it (the tracker follows its updates) and
writes the map file itself, which must load again."""
import shutil
import subprocess
import sys
import time
import unittest

import rospy
import rostest

import checked_run
import ros_test_support as support

MAPPER = "/ply_slam/mapping_node"


class MapperRestart(unittest.TestCase):
    def test_restarted_mapper_gets_the_map_back(self):
        sequence = support.shared_path(rospy.get_param("~sequence"))
        apart = rospy.get_param("~apart", False)
        work = support.work_dir()
        self.addCleanup(shutil.rmtree, work, True)
        frames, offline_ate, stats, player = support.slow_replay(sequence, work)
        self.addCleanup(player.process.kill)
        self.assertTrue(stats.wait_until(lambda s: s.get("keyframes") >= 3, 60))
        player.pause()  # the mapper goes down at a known point, whatever the nodes' speed
        checked_run.run(["rosnode", "kill", MAPPER])
        down_at = stats.get("keyframes")
        player.resume()
        self.assertTrue(stats.wait_until(lambda s: s.get("keyframes") >= down_at + 2, 60),
                        "no keyframe while the mapper was down")
        player.pause()  # keyframes are left for the restarted mapper to map
        followed_at_restart = stats.get("updates_followed")
        mapper = subprocess.Popen([support.tool("mapping_node"), "__name:=mapping_node",
                                   "__ns:=/ply_slam"])
        self.addCleanup(mapper.terminate)
        rospy.wait_for_service(support.SAVE_TRAJECTORY, timeout=120)
        player.resume()
        self.assertEqual(player.wait(timeout=120), 0)
        stats.wait_until(lambda s: s.get("tracked") + s.get("lost") >= frames, 60)
        if apart:  # the restarted mapping side maps the later keyframes; the tracker follows
            self.assertTrue(stats.wait_while_progressing(
                lambda s: s.get("updates_followed") > followed_at_restart,
                lambda s: (s.get("keyframes"), s.get("updates_followed")), stall_s=60),
                "no map update followed after the restart")
        time.sleep(2)  # the last messages reach the mapper

        message, ate, saved, ids, folder = support.saved_trajectory_and_map(sequence, work)
        print("stats %s; trajectory: %s, ATE %.6f m (offline %.6f); map: %s" % (
            stats.values, message, ate["rmse"], offline_ate, saved.message))
        self.assertEqual(stats.get("tracked"), frames)
        self.assertEqual(ate["pairs"], frames, "poses lost while the mapper was down")
        self.assertLessEqual(ate["rmse"], 1.5 * offline_ate)
        self.assertIn(0, ids, "the first keyframe (sent before the restart) is not in the map")
        self.assertFalse(saved.success, "the dense maps miss keyframes but save_map said success")
        self.assertIn("dense maps lack", saved.message)
        if apart:  # the new mapping side mapped on, the tracker followed, the file loads
            self.assertGreater(stats.get("updates_followed"), followed_at_restart)
            loaded = support.load_saved_map(sequence, folder, work)
            print("the map mapping_node wrote: %s" % loaded)
            self.assertEqual(loaded["first_tracked_frame"], 0)
            self.assertEqual(loaded["keyframes_loaded"], len(ids))


if __name__ == "__main__":
    rospy.init_node("mapper_restart_test")
    rostest.rosrun("ply_slam", "mapper_restart_test", MapperRestart, sys.argv)
