#!/usr/bin/python3
"""The soak's meter (scripts/soak.sh): every PERIOD seconds one CSV row with the resident memory
of both nodes (VmRSS of /proc/PID/status) and the map as they publish it: frames done, keyframes
made (tracking_node ~stats), keyframes kept and map points (mapping_node ~keyframes,
~map_points), dense cloud points and octree voxels (~dense_cloud, ~octomap_cloud: subscribed as
rviz would be, read without deserialising the points). Runs until the tracker's process ends or
STOP_FILE appears.

usage: soak_monitor.py OUT.csv TRACKER_PID MAPPER_PID [--period S] [--stop-file F]
"""
import argparse
import csv
import os
import struct
import time

import rospy
from geometry_msgs.msg import PoseArray
from std_msgs.msg import String

NS = "/ply_slam/"
FIELDS = ["seconds", "frames", "tracked", "lost", "skipped_bad", "keyframes_made",
          "keyframes", "map_points", "dense_points", "octree_voxels", "tracker_rss_mb",
          "mapper_rss_mb"]


def rss_mb(pid):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return None  # the process is gone


def cloud_width(raw):
    """Points of a serialised PointCloud2: header (seq, stamp, frame_id), height, width."""
    (frame_len,) = struct.unpack_from("<I", raw, 12)
    height, width = struct.unpack_from("<II", raw, 16 + frame_len)
    return height * width


class Map:
    def __init__(self):
        self.values = {}
        rospy.Subscriber(NS + "tracking_node/stats", String, self.on_stats)
        rospy.Subscriber(NS + "mapping_node/keyframes", PoseArray,
                         lambda m: self.values.update(keyframes=len(m.poses)))
        for topic, key in (("map_points", "map_points"), ("dense_cloud", "dense_points"),
                           ("octomap_cloud", "octree_voxels")):
            rospy.Subscriber(NS + "mapping_node/" + topic, rospy.AnyMsg,
                             lambda m, key=key: self.values.update({key: cloud_width(m._buff)}))

    def on_stats(self, msg):
        stats = {k: float(v) for k, _, v in (f.partition("=") for f in msg.data.split())}
        self.values.update(frames=int(stats.get("tracked", 0) + stats.get("lost", 0)),
                           tracked=int(stats.get("tracked", 0)), lost=int(stats.get("lost", 0)),
                           skipped_bad=int(stats.get("skipped_bad", 0)),
                           keyframes_made=int(stats.get("keyframes", 0)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("tracker_pid", type=int)
    parser.add_argument("mapper_pid", type=int)
    parser.add_argument("--period", type=float, default=5.0)
    parser.add_argument("--stop-file", default="")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("soak_monitor", disable_signals=True)
    state = Map()
    start = time.time()
    with open(args.out, "w", newline="") as f:
        out = csv.DictWriter(f, FIELDS)
        out.writeheader()
        while not (args.stop_file and os.path.exists(args.stop_file)):
            tracker, mapper = rss_mb(args.tracker_pid), rss_mb(args.mapper_pid)
            if tracker is None:
                break
            row = {k: state.values.get(k, 0) for k in FIELDS}
            row.update(seconds="%.1f" % (time.time() - start), tracker_rss_mb="%.1f" % tracker,
                       mapper_rss_mb="" if mapper is None else "%.1f" % mapper)
            out.writerow(row)
            f.flush()
            time.sleep(args.period)


if __name__ == "__main__":
    main()
