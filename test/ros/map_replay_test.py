#!/usr/bin/python3
"""rostest (issue #20): a map saved by ply_slam_tum from the first frames of a sequence, loaded by
tracking_node through tum_bag.launch map:=DIR, the rest of the sequence played as a bag. Checks:
every frame tracked (relocalised at once, as offline), the ATE in the saved map's frame (aligned
as the run that made the map) within the allowed factor of ply_slam_tum --map on the same
frames, and the map file that mapping_node's save_map gets from the tracker loads again."""
import json
import os
import shutil
import signal
import subprocess
import sys
import unittest

import rospy
import rostest

import ros_test_support as support


def run_tum(*args):
    config = os.path.join(support.PACKAGE_DIR, "config", "tum_fr1.yaml")
    subprocess.run([support.tool("ply_slam_tum"), "--config", config] + list(args), check=True,
                   capture_output=True)


def ate_in_map(sequence, trajectory, mapping_trajectory):
    out = subprocess.run([support.tool("ply_slam_eval"), "ate",
                          os.path.join(sequence, "groundtruth.txt"), trajectory, "--align-with",
                          mapping_trajectory, "--json"], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def later_part(sequence, first, folder):
    """The sequence's frames from `first` on, as a TUM folder (links to its images)."""
    os.makedirs(folder)
    for name in ("rgb", "depth", "rgb.txt", "depth.txt", "groundtruth.txt"):
        os.symlink(os.path.join(sequence, name), os.path.join(folder, name))
    with open(os.path.join(sequence, "associations.txt")) as f:
        rows = [line for line in f if line.strip() and not line.startswith("#")]
    with open(os.path.join(folder, "associations.txt"), "w") as f:
        f.writelines(rows[first:])
    return len(rows) - first


class MapReplay(unittest.TestCase):
    def test_localises_in_a_saved_map(self):
        sequence = support.shared_path(rospy.get_param("~sequence"))
        mapped = rospy.get_param("~mapped_frames")
        factor = rospy.get_param("~ate_factor", 1.5)
        work = support.work_dir()
        self.addCleanup(shutil.rmtree, work, True)
        part = os.path.join(work, "part2")
        frames = later_part(sequence, mapped, part)
        saved = os.path.join(work, "map")
        run_tum("--sequence", sequence, "--out", os.path.join(work, "mapped"), "--max-frames",
                str(mapped), "--save-map", saved)
        mapping = os.path.join(work, "mapped", "CameraTrajectory.txt")
        run_tum("--sequence", part, "--out", os.path.join(work, "offline"), "--map", saved)
        offline = ate_in_map(sequence, os.path.join(work, "offline", "CameraTrajectory.txt"),
                             mapping)
        bag = os.path.join(work, "part2.bag")
        support.tum_to_bag(part, bag, extra=["--config", os.path.join(support.PACKAGE_DIR,
                                                                       "config", "tum_fr1.yaml")])

        stats = support.StatsListener()
        nodes = subprocess.Popen(["roslaunch", "ply_slam", "tum_bag.launch", "bag:=" + bag,
                                  "map:=" + saved, "rviz:=false", "output:=log", "delay:=5"])
        self.addCleanup(lambda: (nodes.send_signal(signal.SIGINT), nodes.wait(30)))
        support.wait_for_nodes()
        self.assertTrue(stats.wait_until(lambda s: s.get("tracked") + s.get("lost") >= frames, 90),
                        "not every frame arrived: %s" % stats.values)
        trajectory = os.path.join(work, "ros_trajectory.txt")
        support.save_trajectory(trajectory)
        ate = ate_in_map(sequence, trajectory, mapping)
        print("offline in the map: ATE %.6f m over %d; ROS: %s, ATE %.6f m over %d" % (
            offline["rmse"], offline["pairs"], stats.values, ate["rmse"], ate["pairs"]))
        self.assertEqual(stats.get("tracked"), offline["pairs"])
        self.assertEqual(ate["pairs"], offline["pairs"])
        self.assertLessEqual(ate["rmse"], factor * offline["rmse"])

        # The loaded keyframes have no images: the dense maps are partial, the map file whole.
        folder = os.path.join(work, "saved_again")
        success, message = support.save_map(folder)
        self.assertTrue(os.path.isfile(os.path.join(folder, "map.plymap")), message)
        run_tum("--sequence", part, "--out", os.path.join(work, "again"), "--max-frames", "3",
                "--map", folder)
        with open(os.path.join(work, "again", "summary.json")) as f:
            self.assertEqual(json.load(f)["map"]["first_tracked_frame"], 0)


if __name__ == "__main__":
    rospy.init_node("map_replay_test")
    rostest.rosrun("ply_slam", "map_replay_test", MapReplay, sys.argv)
