#!/usr/bin/python3
"""rostest: the synthetic ring (a corridor walked once round a block, back to the start) rendered
at test time, written as a D435i-style bag and played into tracking_node + mapping_node. The
tracker closes the loop and publishes the correction (MapUpdate); mapping_node applies it, so the
trajectory it saves has the loop closed. Checks: every frame tracked, a loop closed, the mapper
applied it, the saved trajectory is within a bound measured offline and, in line, its end meets its
start (the ring ends where it began) and it is more accurate than the poses as they were streamed
(before the correction). With ~apart the mapping side runs in mapping_node (tracking.launch
mapping_apart, mapping.launch map_keyframes): the tracker sends its keyframes as jobs, mapping_node
closes the loop and sends the updates back, and the tracker's copy of the map follows every one;
the map file mapping_node then writes itself loads again and relocalises the ring's first frames.
How long either node holds the other up (the longest follow, the longest mapper callback) is a
speed figure: printed here, measured by scripts/live_benchmark.sh."""
import glob
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

import numpy as np
import rospy
import rostest
from geometry_msgs.msg import PoseStamped

import checked_run
import ros_test_support as support

POSE_TOPIC = "/ply_slam/tracking_node/pose"


class StreamedPoses:
    """The tracker's ~pose as it came: what a user without the mapper's correction has."""

    def __init__(self):
        self.lines = []
        self.sub = rospy.Subscriber(POSE_TOPIC, PoseStamped, self._on_pose, queue_size=100000)

    def _on_pose(self, msg):
        p, q = msg.pose.position, msg.pose.orientation
        self.lines.append("%.6f %.9f %.9f %.9f %.9f %.9f %.9f %.9f" % (
            msg.header.stamp.to_sec(), p.x, p.y, p.z, q.x, q.y, q.z, q.w))

    def write(self, path):
        with open(path, "w") as f:
            f.write("\n".join(self.lines) + "\n")


def keep_head(sequence, frames):
    """The first `frames` frames of `sequence` as a sequence of their own beside it."""
    head = sequence + "_head"
    for folder in ("rgb", "depth"):
        os.makedirs(os.path.join(head, folder))
    for name in ("camera.yaml", "groundtruth.txt"):
        shutil.copy(os.path.join(sequence, name), head)
    with open(os.path.join(sequence, "associations.txt")) as f:
        lines = [line for line in f if line.strip() and not line.startswith("#")][:frames]
    with open(os.path.join(head, "associations.txt"), "w") as f:
        f.writelines(lines)
    for name, columns in (("rgb.txt", slice(0, 2)), ("depth.txt", slice(2, 4))):
        with open(os.path.join(head, name), "w") as f:
            f.writelines(" ".join(line.split()[columns]) + "\n" for line in lines)
    for line in lines:
        _, rgb, _, depth = line.split()
        for path in (rgb, depth):
            shutil.copy(os.path.join(sequence, path), os.path.join(head, path))
    return head


def remove_stale_rings(keep, max_age_s=2 * 3600):
    """Each build of the renderer makes a new ring (1.3 GB): those of other builds go once no
    test has used them for longer than a test run lasts (each use touches its folder)."""
    now = time.time()
    for old in glob.glob(os.path.join(tempfile.gettempdir(), "ply_slam_ring_*")):
        try:
            stale = old != keep and now - os.path.getmtime(old) > max_age_s
        except OSError:
            continue  # removed meanwhile
        if stale:
            shutil.rmtree(old, True)


def ring_bag(frames, config):
    """The ring rendered and written as a bag (its folder, the bag, its first 3 frames as a
    sequence), once for both loop rostests (rostests run one at a time): kept in the temporary
    folder under a name that changes with the renderer's build, the frames and the config."""
    synth = support.tool("ply_slam_synth")
    with open(config) as f:
        key = "%s %f %d %s" % (synth, os.path.getmtime(synth), frames, f.read())
    cache = os.path.join(tempfile.gettempdir(),
                         "ply_slam_ring_" + hashlib.sha1(key.encode()).hexdigest()[:12])
    ring, bag = os.path.join(cache, "ring"), os.path.join(cache, "ring.bag")
    done = os.path.join(cache, "done")
    if not os.path.isfile(done):
        remove_stale_rings(cache)
        shutil.rmtree(cache, True)
        checked_run.run([synth, "--out", ring, "--scene", "ring", "--frames", str(frames),
                         "--loop", "--noise"])
        support.tum_to_bag(ring, bag, d435i=True, extra=["--config", config, "--lz4"])
        keep_head(ring, 3)
        shutil.rmtree(os.path.join(ring, "rgb"))  # the bag has them now
        shutil.rmtree(os.path.join(ring, "depth"))
        open(done, "w").close()
    os.utime(cache)  # in use: not stale for the other builds' tests
    return ring, bag, ring + "_head"


class LoopReplay(unittest.TestCase):
    def test_saved_trajectory_has_the_loop_closed(self):
        frames = rospy.get_param("~frames", 900)
        rate = rospy.get_param("~rate", 0.5)
        apart = rospy.get_param("~apart", False)
        work = support.work_dir()
        self.addCleanup(shutil.rmtree, work, True)
        config = os.path.join(support.PACKAGE_DIR, "test", "ros", "ring_loop.yaml")
        ring, bag, head = ring_bag(frames, config)

        stats = support.StatsListener()
        streamed = StreamedPoses()
        support.wait_for_nodes()
        subprocess.run(["rosbag", "play", "--quiet", "--delay=1", "--rate=%g" % rate, bag],
                       check=True)
        stats.wait_until(lambda s: s.get("tracked") + s.get("lost") >= frames, 300)
        # The mapping side runs on its own thread (tracking_node's default, or mapping_node's
        # apart): the last keyframes, and a loop they close, come after the last frame. Apart,
        # each keyframe's job comes back as one update at least.
        # Either may be slower than the camera (sanitized, a loaded machine): waited for while
        # it maps on.
        self.assertTrue(stats.wait_while_progressing(lambda s: s.get("mapping_backlog") == 0,
                                                     lambda s: s.get("mapping_backlog")),
                        "the mapping thread stopped with keyframes left: %s" % stats.values)
        if apart:
            self.assertTrue(stats.wait_while_progressing(
                lambda s: s.get("updates_followed") >= s.get("keyframes"),
                lambda s: s.get("updates_followed")),
                "mapping_node stopped mapping keyframes before the last: %s" % stats.values)
        time.sleep(1.0)  # the updates it sent last, to mapping_node

        saved = os.path.join(work, "saved.txt")
        message = support.save_trajectory(saved)
        raw = os.path.join(work, "streamed.txt")
        streamed.write(raw)
        saved_ate = support.ate_rmse(ring, saved)
        streamed_ate = support.ate_rmse(ring, raw)
        print("ROS: %s; mapper: %s; ATE saved %.6f m, as streamed %.6f m" % (
            stats.values, message, saved_ate["rmse"], streamed_ate["rmse"]))
        self.assertEqual(stats.get("tracked"), frames)
        self.assertEqual(stats.get("skipped_bad"), 0)
        self.assertIn("map updates applied", message)
        applied_loops = int(message.split(" after a loop closure")[0].split(", ")[-1])
        if apart:
            loops = int(message.split(" loops closed here")[0].split(", ")[-1])
            self.assertGreaterEqual(loops, 1, "no loop closed")
            self.assertEqual(stats.get("loops"), 0)  # the tracker maps nothing itself
            # Every update the mapping side sent, the tracker's copy followed.
            self.assertGreaterEqual(stats.get("updates_followed"), stats.get("keyframes"))
            self.assertGreaterEqual(applied_loops, loops)
        else:
            self.assertGreaterEqual(stats.get("loops"), 1, "no loop closed")
            self.assertEqual(applied_loops, stats.get("loops"),
                             "the mapper missed a loop's update")
        self.assertEqual(saved_ate["pairs"], frames)
        # ply_slam_tum on the same 900 frames (docs/RESULTS.md, session 44): ATE 0.0082 m with the
        # loop closed, 0.0118 m without; the last pose 0.0019 m from where the first puts it (the
        # ring ends where it began), 0.051 m without.
        self.assertLessEqual(saved_ate["rmse"], 0.014)
        gap = support.loop_gap(ring, saved)
        print("saved trajectory's end %.4f m from its start" % gap)
        if not apart:
            self.assertLess(gap, 0.025)  # 0.006 m measured
            self.assertLess(saved_ate["rmse"], 0.8 * streamed_ate["rmse"])
            return
        # Apart, how far the tracker drifts, and how well the map closes, varies with how late
        # the tracker follows the updates (streamed 0.0087-0.031 m in ten runs, saved
        # 0.0083-0.0133 m; the ends 0.016-0.036 m apart in three): a comparison with the streamed
        # poses or the gap would test the scheduler ("saved < streamed" failed once in three
        # runs). test_loop_closure closes the loop apart, updates a keyframe late, without a clock.
        self.check_saved_map_relocalises(work, head, config)

    def check_saved_map_relocalises(self, work, head, config):
        """Apart, mapping_node owns the map and writes the map file itself: it loads, and the
        ring's first frames relocalise in it at the start of the world (the first camera's)."""
        folder = os.path.join(work, "saved_map")
        success, message = support.save_map(folder)
        print("save_map: %s %s" % (success, message))
        self.assertTrue(os.path.isfile(os.path.join(folder, "map.plymap")), message)
        out = os.path.join(work, "relocalised")
        run = subprocess.run([support.tool("ply_slam_tum"), "--config", config, "--sequence", head,
                              "--out", out, "--map", folder], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        with open(os.path.join(out, "summary.json")) as f:
            self.assertEqual(json.load(f)["map"]["first_tracked_frame"], 0)
        first = np.loadtxt(os.path.join(out, "CameraTrajectory.txt"), ndmin=2)[0]
        print("first frame relocalised at %s" % first[1:4])
        self.assertLess(np.linalg.norm(first[1:4]), 0.05)


if __name__ == "__main__":
    rospy.init_node("loop_replay_test")
    rostest.rosrun("ply_slam", "loop_replay_test", LoopReplay, sys.argv)
