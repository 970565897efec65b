#!/usr/bin/python3
"""rostest: a map saved by ply_slam_tum from the first frames of a sequence, loaded by
tracking_node through tum_bag.launch map:=DIR, the rest of the sequence played as a bag. Checks:
every frame tracked (relocalised at once, as offline), the ATE in the saved map's frame (aligned
as the run that made the map) within the allowed factor of ply_slam_tum --map on the same
frames, and the map file that mapping_node's save_map gets from the tracker loads again. With
odometry (an odom frame from which this test's static transform says the camera never moved):
map -> odom in the saved map's frame (its world_in_map.txt, written here as a robot would have),
and save_map writes that placement again. With ~apart the mapping side runs in mapping_node
(tum_bag.launch mapping_apart:=true): both nodes load the map, the tracker extends it
(localisation_only false, offline too), mapping_node maps the new keyframes and its save_map
writes the map file itself, which must hold more keyframes than the one loaded."""
import math
import json
import os
import shutil
import signal
import subprocess
import sys
import unittest

import numpy as np
import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import PoseStamped, TransformStamped

import checked_run
import ros_test_support as support


def run_tum(*args):
    config = os.path.join(support.PACKAGE_DIR, "config", "tum_fr1.yaml")
    checked_run.run([support.tool("ply_slam_tum"), "--config", config] + list(args))


def ate_in_map(sequence, trajectory, mapping_trajectory):
    out = checked_run.run([support.tool("ply_slam_eval"), "ate",
                           os.path.join(sequence, "groundtruth.txt"), trajectory, "--align-with",
                           mapping_trajectory, "--json"])
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


# Where a robot's mapping run put the SLAM world in its map frame: 1 m, 2 m, 0.5 m, 0.5 rad yaw.
SAVED_PLACE = (1.0, 2.0, 0.5, 0.0, 0.0, math.sin(0.25), math.cos(0.25))
CAMERA_FRAME = "openni_rgb_optical_frame"  # tum_bag.launch's for TUM bags


def matrix(translation, quaternion):
    x, y, z, w = quaternion
    T = np.eye(4)
    T[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    T[:3, 3] = translation
    return T


def write_world_in_map(folder):
    with open(os.path.join(folder, "world_in_map.txt"), "w") as f:
        f.write("# the SLAM world in the map frame: x y z qx qy qz qw\n")
        f.write(" ".join("%.17g" % v for v in SAVED_PLACE) + "\n")


def read_world_in_map(folder):
    with open(os.path.join(folder, "world_in_map.txt")) as f:
        rows = [line for line in f if line.strip() and not line.startswith("#")]
    return [float(v) for v in rows[0].split()]


def odometry_that_never_moves():
    """odom -> camera fixed: the map -> odom the mapper sends then carries the camera's motion."""
    broadcaster = tf2_ros.StaticTransformBroadcaster()
    t = TransformStamped()
    t.header.stamp = rospy.Time.now()
    t.header.frame_id = "odom"
    t.child_frame_id = CAMERA_FRAME
    t.transform.rotation.w = 1.0
    broadcaster.sendTransform(t)
    return broadcaster


class MapReplay(unittest.TestCase):
    def test_localises_in_a_saved_map(self):
        sequence = support.shared_path(rospy.get_param("~sequence"))
        mapped = rospy.get_param("~mapped_frames")
        factor = rospy.get_param("~ate_factor", 1.5)
        apart = rospy.get_param("~apart", False)
        extend = ["--localisation-only", "false"] if apart else []
        work = support.work_dir()
        self.addCleanup(shutil.rmtree, work, True)
        part = os.path.join(work, "part2")
        frames = later_part(sequence, mapped, part)
        saved = os.path.join(work, "map")
        run_tum("--sequence", sequence, "--out", os.path.join(work, "mapped"), "--max-frames",
                str(mapped), "--save-map", saved)
        mapping = os.path.join(work, "mapped", "CameraTrajectory.txt")
        run_tum("--sequence", part, "--out", os.path.join(work, "offline"), "--map", saved,
                *extend)
        offline = ate_in_map(sequence, os.path.join(work, "offline", "CameraTrajectory.txt"),
                             mapping)
        write_world_in_map(saved)
        bag = os.path.join(work, "part2.bag")
        support.tum_to_bag(part, bag, extra=["--config", os.path.join(support.PACKAGE_DIR,
                                                                       "config", "tum_fr1.yaml")])

        stats = support.StatsListener()
        odometry = odometry_that_never_moves()  # noqa: F841 (kept alive: it latches)
        poses = []
        rospy.Subscriber("/ply_slam/tracking_node/pose", PoseStamped, poses.append)
        tf_buffer = tf2_ros.Buffer(rospy.Duration(120))
        tf2_ros.TransformListener(tf_buffer)
        nodes = subprocess.Popen(["roslaunch", "ply_slam", "tum_bag.launch", "bag:=" + bag,
                                  "map:=" + saved, "odom_frame:=odom", "rviz:=false",
                                  "output:=log", "delay:=5", "frame_max_age:=0"] +
                                 (["mapping_apart:=true", "localisation_only:=false"] if apart
                                  else ["mapping_apart:=false"]))
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

        # map -> odom in the saved map's frame: the saved placement times the camera's pose.
        last = poses[-1]
        sent = tf_buffer.lookup_transform("map", "odom", last.header.stamp, rospy.Duration(5))
        p, q = last.pose.position, last.pose.orientation
        expected = matrix(SAVED_PLACE[:3], SAVED_PLACE[3:]) @ matrix((p.x, p.y, p.z),
                                                                     (q.x, q.y, q.z, q.w))
        tr, rot = sent.transform.translation, sent.transform.rotation
        got = matrix((tr.x, tr.y, tr.z), (rot.x, rot.y, rot.z, rot.w))
        print("map -> odom at the last pose: %s, expected %s" % (got[:3, 3], expected[:3, 3]))
        self.assertLess(np.abs(got[:3, 3] - expected[:3, 3]).max(), 1e-3)
        self.assertLess(np.abs(got[:3, :3] - expected[:3, :3]).max(), 1e-3)

        # The loaded keyframes have no images: the dense maps are partial, the map file whole.
        folder = os.path.join(work, "saved_again")
        success, message = support.save_map(folder)
        self.assertTrue(os.path.isfile(os.path.join(folder, "map.plymap")), message)
        np.testing.assert_allclose(read_world_in_map(folder), SAVED_PLACE, atol=1e-9)
        run_tum("--sequence", part, "--out", os.path.join(work, "again"), "--max-frames", "3",
                "--map", folder)
        with open(os.path.join(work, "again", "summary.json")) as f:
            again = json.load(f)["map"]
        self.assertEqual(again["first_tracked_frame"], 0)
        if apart:  # mapping_node mapped the tracker's new keyframes into the map it loaded
            with open(os.path.join(work, "offline", "summary.json")) as f:
                loaded = json.load(f)["map"]["keyframes_loaded"]
            print("keyframes: %d loaded, %d in the map mapping_node saved" % (
                loaded, again["keyframes_loaded"]))
            self.assertGreater(again["keyframes_loaded"], loaded)


if __name__ == "__main__":
    rospy.init_node("map_replay_test")
    rostest.rosrun("ply_slam", "map_replay_test", MapReplay, sys.argv)
