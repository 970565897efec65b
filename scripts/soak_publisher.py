#!/usr/bin/python3
"""The soak's camera (scripts/soak.sh): loops a synthetic TUM folder rendered with --loop into
tracking_node as TUM topics (rgb8, 32FC1 m, camera_info) until FRAMES good frames are out, with
strictly increasing stamps 1/30 s apart, and every 100th slot a malformed message of one kind in
turn (MALFORMED below). Paced by the tracker: a frame goes out when at most WINDOW frames wait
for it (its ~stats), never faster than 30 Hz.

usage: soak_publisher.py SEQUENCE OUT_DIR --frames N

Writes into OUT_DIR: groundtruth.txt (the sequence's poses at the looped stamps), good.txt (the
good frames' stamps), zero_depth.txt (the all-zero-depth frames' stamps), sent.json (what went
out, by kind, and how long the tracker was waited for).
"""
import argparse
import copy
import json
import os
import sys
import time

import cv2
import numpy as np
import rospy
import yaml
from geometry_msgs.msg import PoseStamped
from sensor_msgs.msg import CameraInfo, Image
from std_msgs.msg import String

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
import tum_to_bag as tum  # noqa: E402  (image_msg, camera_info, read_list)

RGB, DEPTH, INFO = "/camera/rgb/image_color", "/camera/depth/image", "/camera/rgb/camera_info"
FRAME = "/openni_rgb_optical_frame"
STATS = "/ply_slam/tracking_node/stats"
# The launch files' default: the mapping side in mapping_node; the tracker sends it jobs and
# follows its map updates.
JOB = "/ply_slam/tracking_node/mapping_job"
POSE = "/ply_slam/tracking_node/pose"
MAP_UPDATE = "/ply_slam/mapping_node/map_update"
PERIOD = 1.0 / 30
WINDOW = 2  # frames waiting for the tracker at most
# One kind every 100th slot, in turn: (name, what the nodes must report: node and ~stats key or
# log kind; None = nothing expected). The camera_info kinds go with the slot's good frame in
# place of its camera_info (the node keeps only the newest); the kinds in BESIDE_A_FRAME go
# before the slot's good frame.
MALFORMED = [
    ("grey colour image", "tracker", "encoding"),
    ("8-bit depth", "tracker", "encoding"),
    ("truncated colour data", "tracker", "size"),
    ("zero-size images", "tracker", "empty"),
    ("depth half the colour size", "tracker", "size"),
    ("camera_info with NaN fx", "tracker", "camera_info"),
    ("camera_info with zero K (uncalibrated)", "tracker", None),
    ("stamp repeated", "tracker", "stamp"),
    ("stamp 1 s back", "tracker", "stamp"),
    ("colour without depth", "tracker", "unpaired"),
    ("all-zero depth", "tracker", None),  # a frame: a pose from the map alone, or lost
    ("mapping job with NaN pose", "mapper", "mapping_job"),  # a job as the tracker sent one
    ("pose with zero quaternion", "mapper", "pose"),
    ("map update with NaN pose", "tracker", "map_update"),
]
BESIDE_A_FRAME = ("mapping job with NaN pose", "pose with zero quaternion",
                  "map update with NaN pose")


class Stats:
    """The tracker's latched ~stats ("key=value ...")."""

    def __init__(self):
        self.values = {}
        rospy.Subscriber(STATS, String, self._on)

    def _on(self, msg):
        self.values = {k: float(v) for k, _, v in (f.partition("=") for f in msg.data.split())}

    def get(self, key):
        return self.values.get(key, 0.0)

    def frames_done(self):  # well-formed pairs the worker finished: a pose or "lost"
        return self.get("tracked") + self.get("lost")


class Sequence:
    """The rendered frames in memory (colour rgb8 bytes, raw 16-bit depth), ground truth."""

    def __init__(self, folder):
        with open(os.path.join(folder, "camera.yaml")) as f:
            self.camera = yaml.safe_load(f)["camera"]
        self.depth_factor = float(self.camera.get("depth_factor", 5000.0))
        pairs = tum.read_list(os.path.join(folder, "associations.txt"), 4)
        gt = {r[0]: r[1:8] for r in tum.read_list(os.path.join(folder, "groundtruth.txt"), 8)}
        # --loop: the last frame is the first again; leave it out so the loop is seamless.
        pairs = pairs[:-1]
        self.rgb, self.depth, self.poses = [], [], []
        for stamp, rgb, _, depth in pairs:
            bgr = cv2.imread(os.path.join(folder, rgb), cv2.IMREAD_COLOR)
            self.rgb.append(np.ascontiguousarray(bgr[:, :, ::-1]))
            self.depth.append(cv2.imread(os.path.join(folder, depth), cv2.IMREAD_UNCHANGED))
            self.poses.append(gt[stamp])
        self.t0 = float(pairs[0][0])

    def images(self, index, stamp):
        k = index % len(self.rgb)
        metres = self.depth[k].astype(np.float32) / self.depth_factor
        metres[self.depth[k] == 0] = np.nan
        return (tum.image_msg(self.rgb[k], "rgb8", stamp, FRAME),
                tum.image_msg(metres, "32FC1", stamp, FRAME))

    def info(self, stamp):
        return tum.camera_info(self.camera, stamp, FRAME)


def with_fields(image, stamp=None, **fields):
    out = copy.copy(image)
    out.header = copy.copy(image.header)
    if stamp is not None:
        out.header.stamp = stamp
    for key, value in fields.items():
        setattr(out, key, value)
    return out


def nan_transform(transform):
    """A copy of a RigidTransformMsg with its first entry NaN."""
    out = copy.copy(transform)
    out.matrix = [float("nan")] + list(transform.matrix[1:])
    return out


class Soak:
    def __init__(self, sequence, out, frames):
        self.seq, self.out, self.frames = sequence, out, frames
        self.stats = Stats()
        self.pub = {t: rospy.Publisher(t, k, queue_size=10)
                    for t, k in ((RGB, Image), (DEPTH, Image), (INFO, CameraInfo))}
        # The two nodes' inputs from each other, as something else on the network could
        # publish them. The message types are generated by the package's build (devel space on
        # PYTHONPATH).
        from ply_slam.msg import KeyFramePoseMsg, MappingJobMsg, MapUpdateMsg, RigidTransformMsg
        self.MapUpdateMsg, self.KeyFramePoseMsg, self.RigidTransformMsg = (
            MapUpdateMsg, KeyFramePoseMsg, RigidTransformMsg)
        self.pub[JOB] = rospy.Publisher(JOB, MappingJobMsg, queue_size=2)
        self.pub[POSE] = rospy.Publisher(POSE, PoseStamped, queue_size=2)
        self.pub[MAP_UPDATE] = rospy.Publisher(MAP_UPDATE, MapUpdateMsg, queue_size=2)
        # The tracker's first job, kept to be sent again spoilt (then no more: each is MBs).
        self.first_job = None
        self.job_sub = rospy.Subscriber(JOB, MappingJobMsg, self._on_job, queue_size=1)
        self.sent = {name: 0 for name, _, _ in MALFORMED}
        self.good_stamps, self.frames_sent = [], 0  # frames: good ones and all-zero depth
        self.zero_depth_stamps = []
        self.waited_s, self.stalls = 0.0, []

    def _on_job(self, msg):
        if self.first_job is None:
            self.first_job = msg
            self.job_sub.unregister()

    def wait_for_subscribers(self):
        deadline = time.time() + 60
        while any(self.pub[t].get_num_connections() == 0 for t in (RGB, DEPTH, INFO)):
            if time.time() > deadline:
                sys.exit("soak_publisher: tracking_node did not subscribe within 60 s")
            time.sleep(0.2)

    def pace(self, last_send):
        """Waits until the tracker has at most WINDOW frames left and 1/30 s went by."""
        start = time.time()
        deadline = start + 20
        while self.stats.frames_done() < self.frames_sent - WINDOW and not rospy.is_shutdown():
            if time.time() > deadline:  # noted, not hidden: the report shows each
                self.stalls.append((len(self.good_stamps), self.stats.values.copy()))
                break
            time.sleep(0.002)
        self.waited_s += time.time() - start
        time.sleep(max(0.0, last_send + PERIOD - time.time()))

    def send_pair(self, rgb, depth, frame=False):
        self.pub[RGB].publish(rgb)
        self.pub[DEPTH].publish(depth)
        self.frames_sent += frame

    def send_malformed(self, kind, image, stamp, previous_stamp):
        """One malformed message (or pair) of `kind` in the slot at `stamp`. Returns the
        camera_info to send with the slot's good frame, or None when the slot is used up."""
        name = MALFORMED[kind][0]
        self.sent[name] += 1
        rgb, depth = self.seq.images(image, stamp)
        info = self.seq.info(stamp)
        half = dict(width=depth.width // 2, height=depth.height // 2, step=depth.step // 2,
                    data=depth.data[:len(depth.data) // 4])
        if name == "grey colour image":
            self.send_pair(with_fields(rgb, encoding="mono8", step=rgb.width,
                                       data=rgb.data[:rgb.width * rgb.height]), depth)
        elif name == "8-bit depth":
            self.send_pair(rgb, with_fields(depth, encoding="8UC1", step=depth.width,
                                            data=depth.data[:depth.width * depth.height]))
        elif name == "truncated colour data":
            self.send_pair(with_fields(rgb, data=rgb.data[:-1000]), depth)
        elif name == "zero-size images":
            empty = dict(width=0, height=0, step=0, data=b"")
            self.send_pair(with_fields(rgb, **empty), with_fields(depth, **empty))
        elif name == "depth half the colour size":
            self.send_pair(rgb, with_fields(depth, **half))
        elif name == "camera_info with NaN fx":
            info.K = [float("nan")] + list(info.K[1:])
            return info
        elif name == "camera_info with zero K (uncalibrated)":
            info.K, info.P, info.D = [0.0] * 9, [0.0] * 12, [0.0] * 5
            return info
        elif name == "stamp repeated":
            self.send_pair(with_fields(rgb, previous_stamp), with_fields(depth, previous_stamp))
        elif name == "stamp 1 s back":
            back = stamp - rospy.Duration(1.0)
            self.send_pair(with_fields(rgb, back), with_fields(depth, back))
        elif name == "colour without depth":
            self.pub[RGB].publish(rgb)
        elif name == "all-zero depth":
            zero = np.zeros((depth.height, depth.width), np.float32)
            self.send_pair(rgb, with_fields(depth, data=zero.tobytes()), frame=True)
            self.zero_depth_stamps.append(stamp.to_sec())
            self.gt.write(self.gt_line(stamp, image))
        elif name == "mapping job with NaN pose":
            if self.first_job is None:
                sys.exit("soak_publisher: no mapping job seen from tracking_node by slot %d" %
                         len(self.good_stamps))
            msg = copy.copy(self.first_job)
            msg.T_cw = nan_transform(msg.T_cw)
            self.pub[JOB].publish(msg)
        elif name == "pose with zero quaternion":
            msg = PoseStamped()
            msg.header.stamp = stamp
            self.pub[POSE].publish(msg)
        elif name == "map update with NaN pose":
            msg = self.MapUpdateMsg()
            msg.header.stamp = stamp
            identity = self.RigidTransformMsg(matrix=[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0])
            msg.keyframes = [self.KeyFramePoseMsg(id=0, T_cw=nan_transform(identity))]
            self.pub[MAP_UPDATE].publish(msg)
        if name in BESIDE_A_FRAME:
            return self.seq.info(stamp)
        return None

    def gt_line(self, stamp, image):
        return "%.6f %s\n" % (stamp.to_sec(), " ".join(self.seq.poses[image % len(self.seq.poses)]))

    def run(self):
        self.wait_for_subscribers()
        stamp = rospy.Time.from_sec(self.seq.t0)
        previous = stamp
        slot, image, malformed = 0, 0, 0
        last_send = 0.0
        started = time.time()
        with open(os.path.join(self.out, "groundtruth.txt"), "w") as self.gt:
            self.gt.write("# timestamp tx ty tz qx qy qz qw (the sequence looped)\n")
            while len(self.good_stamps) < self.frames and not rospy.is_shutdown():
                self.pace(last_send)
                last_send = time.time()
                info = self.seq.info(stamp)
                if slot % 100 == 50:  # 1 % of the slots
                    kind = malformed % len(MALFORMED)
                    malformed += 1
                    info = self.send_malformed(kind, image, stamp, previous)
                    if info is None:
                        slot += 1
                        stamp += rospy.Duration(PERIOD)
                        continue
                rgb, depth = self.seq.images(image, stamp)
                self.pub[INFO].publish(info)
                self.send_pair(rgb, depth, frame=True)
                self.gt.write(self.gt_line(stamp, image))
                self.good_stamps.append(stamp.to_sec())
                previous = stamp
                image += 1
                slot += 1
                stamp += rospy.Duration(PERIOD)
                if len(self.good_stamps) % 1000 == 0:
                    print("soak_publisher: %d good frames, %d malformed, %.0f s; stats %s" % (
                        len(self.good_stamps), malformed, time.time() - started,
                        self.stats.values), flush=True)
        # The last pairs: the tracker flushes the final one after 0.5 s of quiet.
        deadline = time.time() + 60
        while self.stats.frames_done() < self.frames_sent and time.time() < deadline:
            time.sleep(0.1)
        time.sleep(2.0)
        self.write(time.time() - started)

    def write(self, seconds):
        with open(os.path.join(self.out, "good.txt"), "w") as f:
            f.writelines("%.6f\n" % s for s in self.good_stamps)
        with open(os.path.join(self.out, "zero_depth.txt"), "w") as f:
            f.writelines("%.6f\n" % s for s in self.zero_depth_stamps)
        report = {"good_frames": len(self.good_stamps), "malformed": self.sent,
                  "expected": {name: [node, kind] for name, node, kind in MALFORMED},
                  "frames_sent": self.frames_sent, "seconds": seconds,
                  "waited_for_tracker_s": self.waited_s,
                  "stalls": [{"good_frames": n, "stats": s} for n, s in self.stalls],
                  "final_stats": self.stats.values}
        with open(os.path.join(self.out, "sent.json"), "w") as f:
            json.dump(report, f, indent=1)
        print("soak_publisher: done: %d good frames, %d malformed in %.0f s (%.1f frames/s), "
              "%d stalls" % (len(self.good_stamps), sum(self.sent.values()), seconds,
                             len(self.good_stamps) / seconds, len(self.stalls)), flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("sequence")
    parser.add_argument("out")
    parser.add_argument("--frames", type=int, default=10000)
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("soak_publisher", disable_signals=True)
    Soak(Sequence(args.sequence), args.out, args.frames).run()


if __name__ == "__main__":
    main()
