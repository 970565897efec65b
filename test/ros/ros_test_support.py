"""Shared pieces of the rostest integration tests: where the shared data is, offline reference
runs, bag conversion, the tracking node's statistics and the mapper's save service."""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time
import unittest

import checked_run
import rospkg
import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from roslib.packages import find_node
from std_msgs.msg import String

PACKAGE_DIR = rospkg.RosPack().get_path("ply_slam")
STATS_TOPIC = "/ply_slam/tracking_node/stats"
SAVE_TRAJECTORY = "/ply_slam/mapping_node/save_trajectory"
SAVE_MAP = "/ply_slam/mapping_node/save_map"
GRID_TOPIC = "/ply_slam/mapping_node/grid_map"
PATH_TOPIC = "/ply_slam/tracking_node/path"
POSE_TOPIC = "/ply_slam/tracking_node/pose"


def shared_path(relative):
    """$PLY_SLAM_SHARED/relative, else ../shared beside the repository. Missing: the test fails
    under CI=true and is skipped otherwise (as test/shared_data.h does for the gtests)."""
    root = os.environ.get("PLY_SLAM_SHARED") or os.path.join(
        os.path.dirname(os.path.realpath(PACKAGE_DIR)), "shared")
    path = os.path.join(root, relative)
    if not os.path.exists(path):
        if os.environ.get("CI") == "true":
            raise AssertionError("CI=true but shared data is missing: " + path)
        raise unittest.SkipTest("shared data missing: %s (set PLY_SLAM_SHARED)" % path)
    return path


def tool(name):
    found = find_node("ply_slam", name)
    if not found:
        raise AssertionError("cannot find the %s executable (build the package first)" % name)
    return found[0]


def work_dir():
    return tempfile.mkdtemp(prefix="ply_slam_rostest_")


def tum_to_bag(sequence, bag, d435i=False, extra=()):
    command = ["/usr/bin/python3", os.path.join(PACKAGE_DIR, "scripts", "tum_to_bag.py"),
               sequence, bag] + (["--d435i"] if d435i else []) + list(extra)
    subprocess.run(command, check=True)


def ate_rmse(sequence, trajectory):
    out = checked_run.run([tool("ply_slam_eval"), "ate",
                           os.path.join(sequence, "groundtruth.txt"), trajectory, "--json"])
    return json.loads(out.stdout)


def loop_gap(sequence, trajectory):
    """How far the trajectory's last pose is from where its first pose and the ground truth put
    it (m): the drift a loop closure takes out, on a sequence that ends where it began."""
    with open(trajectory) as f:
        poses = sum(1 for line in f if line.strip() and not line.startswith("#"))
    out = checked_run.run([tool("ply_slam_eval"), "rpe",
                           os.path.join(sequence, "groundtruth.txt"), trajectory, "--delta",
                           str(poses - 1), "--json"])
    result = json.loads(out.stdout)
    assert result["pairs"] == 1, out.stdout
    return result["trans_max"]


def offline_run(sequence, out_dir):
    """ply_slam_tum on the same frames with the same config: the reference the nodes must meet.
    Returns (frames tracked, ATE RMSE)."""
    config = os.path.join(PACKAGE_DIR, "config", "tum_fr1.yaml")
    checked_run.run([tool("ply_slam_tum"), "--sequence", sequence, "--config", config, "--out",
                     out_dir])
    ate = ate_rmse(sequence, os.path.join(out_dir, "CameraTrajectory.txt"))
    return ate["pairs"], ate["rmse"]


class StatsListener:
    """The tracking node's latched ~stats ("key=value ..."), newest first."""

    def __init__(self):
        self.values = {}
        self.sub = rospy.Subscriber(STATS_TOPIC, String, self._on_stats)

    def _on_stats(self, msg):
        values = {}
        for field in msg.data.split():
            key, _, value = field.partition("=")
            values[key] = float(value)
        self.values = values

    def get(self, key):
        return self.values.get(key, 0)

    def wait_until(self, condition, timeout):
        deadline = time.time() + timeout
        while time.time() < deadline and not rospy.is_shutdown():
            if condition(self):
                return True
            time.sleep(0.1)
        return condition(self)

    def wait_while_progressing(self, condition, progress, stall_s=30.0, limit_s=600.0):
        """Waits until condition holds, as long as progress(self) keeps changing: a mapping side
        slower than the camera (sanitized, or on a loaded machine) is waited for; one that has
        stopped fails after stall_s without progress. True when the condition held."""
        limit = time.time() + limit_s
        last, stall = progress(self), time.time() + stall_s
        while time.time() < min(stall, limit) and not rospy.is_shutdown():
            if condition(self):
                return True
            time.sleep(0.1)
            if progress(self) != last:
                last, stall = progress(self), time.time() + stall_s
        return condition(self)


class PausablePlayer:
    """rosbag play that the test pauses and resumes (its ~pause_playback service), so that what
    the nodes get in between does not depend on how fast they are."""

    def __init__(self, bag, rate):
        from std_srvs.srv import SetBool
        before = set(rosservice_list())
        self.process = subprocess.Popen(["rosbag", "play", "--quiet", "--delay=1",
                                         "--rate=%g" % rate, bag])
        deadline = time.time() + 30
        while time.time() < deadline:
            found = [s for s in set(rosservice_list()) - before if s.endswith("/pause_playback")]
            if found:
                self.pause_service = rospy.ServiceProxy(found[0], SetBool)
                return
            time.sleep(0.2)
        self.process.kill()
        raise AssertionError("rosbag play did not offer pause_playback within 30 s")

    def pause(self, paused=True):
        self.pause_service(paused)

    def resume(self):
        self.pause(False)

    def wait(self, timeout):
        return self.process.wait(timeout=timeout)


def rosservice_list():
    return checked_run.run(["rosservice", "list"]).stdout.split()


class PathListener:
    """The tracking node's ~path messages (wall time received, the poses' stamps) and its ~pose
    messages."""

    def __init__(self):
        self.paths = []
        self.poses = []
        self.path_sub = rospy.Subscriber(PATH_TOPIC, Path, self._on_path)
        self.pose_sub = rospy.Subscriber(POSE_TOPIC, PoseStamped, self._on_pose)

    def _on_path(self, msg):
        self.paths.append((time.time(), [p.header.stamp.to_sec() for p in msg.poses]))

    def _on_pose(self, msg):
        self.poses.append(msg)

    def expected_stamps(self, start):
        """The poses the path keeps from the pose at `start` on (one it kept): each 1 cm or
        1 degree from the last kept."""
        kept, last = [], None
        for msg in self.poses:
            if msg.header.stamp.to_sec() < start:
                continue
            p, q = msg.pose.position, msg.pose.orientation
            if last is not None:
                (lp, lq) = last
                moved = math.dist((p.x, p.y, p.z), (lp.x, lp.y, lp.z))
                dot = abs(q.x * lq.x + q.y * lq.y + q.z * lq.z + q.w * lq.w)
                turned = 2.0 * math.degrees(math.acos(min(1.0, dot)))
                if moved <= 0.01 and turned <= 1.0:
                    continue
            kept.append(msg.header.stamp.to_sec())
            last = (p, q)
        return kept

    def newest_path_tail(self):
        """The newest path's stamps from the first pose this listener also received on, and the
        poses the path should keep from there (the first ~pose messages may come before the
        subscription does)."""
        received = {msg.header.stamp.to_sec() for msg in self.poses}
        stamps = self.paths[-1][1] if self.paths else []
        tail = [t for t in stamps if t >= min(received | {math.inf})]
        return tail, self.expected_stamps(tail[0]) if tail else [None]

    def check(self, test, period, timeout=5.0):
        """~path messages at least `period` apart (less 0.1 s of delivery jitter), and within
        `timeout` of the stream's end one holding every pose the path keeps (none held back)."""
        deadline = time.time() + timeout
        while time.time() < deadline and (lambda t: t[0] != t[1])(self.newest_path_tail()):
            time.sleep(0.1)
        tail, expected = self.newest_path_tail()
        print("~path messages (poses, s after the first): %s; poses received %d, kept %d" % (
            [(len(stamps), round(t - self.paths[0][0], 2)) for t, stamps in self.paths],
            len(self.poses), len(expected)))
        test.assertTrue(self.paths, "no ~path message")
        test.assertGreater(len(tail), 10, "too few poses to judge the path")
        test.assertEqual(tail, expected)
        gaps = [b[0] - a[0] for a, b in zip(self.paths, self.paths[1:])]
        test.assertTrue(all(g >= period - 0.1 for g in gaps), "~path gaps %s s" % gaps)


def import_service_type():
    """ply_slam.srv.SaveToPath. catkin caches the environment of a fresh workspace before the
    generated Python messages exist, so under ctest PYTHONPATH can lack them: add the devel
    space's dist-packages, found beside our executables."""
    devel = os.path.dirname(os.path.dirname(os.path.dirname(tool("ply_slam_tum"))))
    packages = os.path.join(devel, "lib", "python3", "dist-packages")
    if os.path.isdir(packages) and packages not in sys.path:
        sys.path.insert(0, packages)
    from ply_slam.srv import SaveToPath
    return SaveToPath


def call_save(service, path):
    """Calls one of the mapper's SaveToPath services; raises when it reports a failure."""
    SaveToPath = import_service_type()
    rospy.wait_for_service(service, timeout=30)
    response = rospy.ServiceProxy(service, SaveToPath)(path)
    if not response.success:
        raise AssertionError(service + " failed: " + response.message)
    return response.message


def save_trajectory(path):
    return call_save(SAVE_TRAJECTORY, path)


def check_grid(test, folder):
    """The latched ~grid_map arrives and is consistent; save_map wrote map.yaml with
    map_server's documented fields and a map.pgm of the message's size and values."""
    from nav_msgs.msg import OccupancyGrid
    grid = rospy.wait_for_message(GRID_TOPIC, OccupancyGrid, timeout=10)
    test.assertEqual(len(grid.data), grid.info.width * grid.info.height)
    test.assertTrue(set(grid.data) <= {-1, 0, 100})
    test.assertIn(grid.header.frame_id, ("map", "ply_slam_world"))
    call_save(SAVE_MAP, folder)
    fields = {}
    with open(os.path.join(folder, "map.yaml")) as f:
        for line in f:
            key, _, value = line.partition(":")
            fields[key.strip()] = value.strip()
    test.assertEqual(fields["image"], "map.pgm")
    test.assertAlmostEqual(float(fields["resolution"]), grid.info.resolution, places=6)
    test.assertEqual(len(fields["origin"].strip("[]").split(",")), 3)
    test.assertEqual(fields["negate"], "0")
    test.assertGreater(float(fields["occupied_thresh"]), float(fields["free_thresh"]))
    with open(os.path.join(folder, "map.pgm"), "rb") as f:
        test.assertEqual(f.readline().strip(), b"P5")
        line = f.readline()
        while line.startswith(b"#"):
            line = f.readline()
        width, height = (int(v) for v in line.split())
        f.readline()  # maxval
        pixels = set(f.read())
    test.assertGreater(width * height, 0)
    test.assertTrue(pixels <= {0, 205, 254})


def save_map(path):
    """(success, message) of the mapper's save_map."""
    SaveToPath = import_service_type()
    rospy.wait_for_service(SAVE_MAP, timeout=30)
    response = rospy.ServiceProxy(SAVE_MAP, SaveToPath)(path)
    return response.success, response.message


def wait_for_nodes(timeout=30):
    """Both nodes are up: the mapper's service exists and the tracker's subscribers are there."""
    rospy.wait_for_service(SAVE_TRAJECTORY, timeout=timeout)
    deadline = time.time() + timeout
    while time.time() < deadline:
        nodes = subprocess.run(["rosnode", "list"], capture_output=True, text=True).stdout
        if "/ply_slam/tracking_node" in nodes:
            return
        time.sleep(0.2)
    raise AssertionError("tracking_node did not come up")


def slow_replay(sequence, work):
    """The sequence as a bag played at rate 0.1 (37 frames: about 12 s) into nodes that are up,
    with its offline run: (frames, offline ATE, the tracker's stats, the PausablePlayer)."""
    bag = os.path.join(work, "sequence.bag")
    tum_to_bag(sequence, bag)
    frames, offline_ate = offline_run(sequence, os.path.join(work, "offline"))
    stats = StatsListener()
    wait_for_nodes()
    return frames, offline_ate, stats, PausablePlayer(bag, 0.1)


def saved_trajectory_and_map(sequence, work):
    """mapping_node's trajectory and map saved into `work`: (save_trajectory's message, its ATE
    (ate_rmse), save_map's response, the ids in its keyframes.csv, the folder)."""
    trajectory = os.path.join(work, "trajectory.txt")
    message = save_trajectory(trajectory)  # fails the test when not whole
    ate = ate_rmse(sequence, trajectory)
    folder = os.path.join(work, "map")
    SaveToPath = import_service_type()
    service = "/ply_slam/mapping_node/save_map"
    rospy.wait_for_service(service, timeout=30)
    saved = rospy.ServiceProxy(service, SaveToPath)(folder)
    with open(os.path.join(folder, "keyframes.csv")) as f:
        ids = [int(row["id"]) for row in csv.DictReader(f)]
    return message, ate, saved, ids, folder


def load_saved_map(sequence, folder, work):
    """ply_slam_tum on the sequence's first 3 frames in the map saved in `folder`: the "map"
    part of its summary.json (keyframes_loaded, first_tracked_frame, ...)."""
    out = os.path.join(work, "again")
    checked_run.run([tool("ply_slam_tum"), "--sequence", sequence, "--config",
                     os.path.join(PACKAGE_DIR, "config", "tum_fr1.yaml"), "--out", out,
                     "--max-frames", "3", "--map", folder])
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)["map"]
