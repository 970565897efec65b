#!/usr/bin/python3
"""Writes a TUM RGB-D folder as a rosbag with the topics and encodings of the TUM site's bags.

usage: tum_to_bag.py FOLDER OUT.bag [--d435i] [--config YAML] [--all-images] [--lz4]

  TUM layout (default): /camera/rgb/image_color (rgb8), /camera/depth/image (32FC1, metres,
  NaN = no depth), /camera/rgb/camera_info, frames /openni_rgb_optical_frame and
  /openni_depth_optical_frame.
  --d435i: realsense2_camera's names instead: /camera/color/image_raw (rgb8),
  /camera/aligned_depth_to_color/image_raw (16UC1, millimetres, 0 = no depth),
  /camera/color/camera_info, frame camera_color_optical_frame.
  Ground truth (groundtruth.txt), when present: /ground_truth/pose (geometry_msgs/PoseStamped,
  frame "world"). camera_info carries the intrinsics of the config (default: config/tum_frN.yaml
  chosen by "freiburgN"/"frN" in the folder name).
  Frames: the pairs of associations.txt when the folder has one (the frames ply_slam_tum
  tracks), else every image of rgb.txt and depth.txt; --all-images: every image regardless,
  as in TUM's own bags.
  --lz4: LZ4-compressed chunks (long sequences; rosbag play decompresses as it goes).

Runs with the system Python (/usr/bin/python3: rosbag, python3-opencv, python3-numpy).
"""
import argparse
import os
import re
import sys

import cv2
import numpy as np
import rosbag
import rospy
import yaml
from geometry_msgs.msg import PoseStamped
from sensor_msgs.msg import CameraInfo, Image

TUM = dict(rgb="/camera/rgb/image_color", depth="/camera/depth/image",
           info="/camera/rgb/camera_info", rgb_frame="/openni_rgb_optical_frame",
           depth_frame="/openni_depth_optical_frame")
D435I = dict(rgb="/camera/color/image_raw", depth="/camera/aligned_depth_to_color/image_raw",
             info="/camera/color/camera_info", rgb_frame="camera_color_optical_frame",
             depth_frame="camera_color_optical_frame")
GROUND_TRUTH_TOPIC = "/ground_truth/pose"


def fail(message):
    sys.exit("tum_to_bag.py: " + message)


def read_list(path, columns):
    """Rows of a TUM list file (stamp path ... / stamp values), '#' comments skipped."""
    rows = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            fields = line.split()
            if len(fields) < columns:
                fail("%s:%d: expected %d fields, got '%s'" % (path, number, columns, line))
            rows.append(fields)
    return rows


def parse_stamp(text):
    """'1305031234.529645' -> rospy.Time, exactly (no float rounding)."""
    sec, _, frac = text.partition(".")
    return rospy.Time(int(sec), int(frac.ljust(9, "0")[:9]))


def default_config(folder):
    match = re.search(r"(freiburg|fr)([123])", os.path.basename(os.path.normpath(folder)))
    if not match:
        fail("cannot choose a config for %s (no freiburg1/2/3 in the name): pass --config" % folder)
    here = os.path.dirname(os.path.realpath(__file__))
    return os.path.join(here, "..", "config", "tum_fr%s.yaml" % match.group(2))


def camera_info(camera, stamp, frame):
    info = CameraInfo()
    info.header.stamp = stamp
    info.header.frame_id = frame
    info.width, info.height = int(camera["width"]), int(camera["height"])
    fx, fy, cx, cy = (float(camera[k]) for k in ("fx", "fy", "cx", "cy"))
    info.distortion_model = "plumb_bob"
    info.D = [float(d) for d in camera.get("distortion", [0.0] * 5)]
    info.K = [fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0]
    info.R = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    info.P = [fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0]
    return info


def image_msg(array, encoding, stamp, frame):
    msg = Image()
    msg.header.stamp = stamp
    msg.header.frame_id = frame
    msg.height, msg.width = array.shape[:2]
    msg.encoding = encoding
    msg.is_bigendian = 0
    msg.step = array.strides[0]
    msg.data = array.tobytes()
    return msg


def load(folder, relative, flags):
    path = os.path.join(folder, relative)
    image = cv2.imread(path, flags)
    if image is None:
        fail("cannot read " + path)
    return image


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder")
    parser.add_argument("out")
    parser.add_argument("--d435i", action="store_true", help="D435i topic names, 16UC1 mm depth")
    parser.add_argument("--config", help="ply_slam YAML with the camera section")
    parser.add_argument("--lz4", action="store_true", help="LZ4-compressed chunks")
    parser.add_argument("--all-images", action="store_true",
                        help="every image of rgb.txt and depth.txt, even without associations")
    args = parser.parse_args()

    folder = args.folder
    for name in ("rgb.txt", "depth.txt"):
        if not os.path.isfile(os.path.join(folder, name)):
            fail("%s has no %s (not a TUM RGB-D folder)" % (folder, name))
    config_path = args.config or default_config(folder)
    with open(config_path) as f:
        camera = yaml.safe_load(f)["camera"]
    depth_factor = float(camera.get("depth_factor", 5000.0))
    names = D435I if args.d435i else TUM

    associations = os.path.join(folder, "associations.txt")
    if os.path.isfile(associations) and not args.all_images:
        pairs = read_list(associations, 4)
        rgb = [(p[0], p[1]) for p in pairs]
        depth = [(p[2], p[3]) for p in pairs]
    else:
        rgb = [(r[0], r[1]) for r in read_list(os.path.join(folder, "rgb.txt"), 2)]
        depth = [(r[0], r[1]) for r in read_list(os.path.join(folder, "depth.txt"), 2)]

    messages = []  # (stamp string, order, kind, path): written in time order
    messages += [(s, 0, "rgb", p) for s, p in rgb]
    messages += [(s, 1, "depth", p) for s, p in depth]
    gt_path = os.path.join(folder, "groundtruth.txt")
    if os.path.isfile(gt_path):
        # Only over the images' time span: groundtruth.txt may cover a longer recording.
        first = min(float(m[0]) for m in messages) - 0.1
        last = max(float(m[0]) for m in messages) + 0.1
        messages += [(r[0], 2, "gt", r[1:8]) for r in read_list(gt_path, 8)
                     if first <= float(r[0]) <= last]
    messages.sort(key=lambda m: (float(m[0]), m[1]))

    compression = rosbag.Compression.LZ4 if args.lz4 else rosbag.Compression.NONE
    with rosbag.Bag(args.out, "w", compression=compression) as bag:
        for stamp_text, _, kind, payload in messages:
            stamp = parse_stamp(stamp_text)
            if kind == "rgb":
                bgr = load(folder, payload, cv2.IMREAD_COLOR)
                rgb8 = np.ascontiguousarray(bgr[:, :, ::-1])
                bag.write(names["rgb"], image_msg(rgb8, "rgb8", stamp, names["rgb_frame"]), stamp)
                bag.write(names["info"], camera_info(camera, stamp, names["rgb_frame"]), stamp)
            elif kind == "depth":
                raw = load(folder, payload, cv2.IMREAD_UNCHANGED)
                if raw.dtype != np.uint16 or raw.ndim != 2:
                    fail("%s: depth must be 16-bit single channel" % payload)
                metres = raw.astype(np.float32) / depth_factor
                if args.d435i:
                    depth_image = np.round(metres * 1000.0).astype(np.uint16)
                    encoding = "16UC1"
                else:
                    metres[raw == 0] = np.nan
                    depth_image, encoding = metres, "32FC1"
                bag.write(names["depth"],
                          image_msg(depth_image, encoding, stamp, names["depth_frame"]), stamp)
            else:
                pose = PoseStamped()
                pose.header.stamp = stamp
                pose.header.frame_id = "world"
                tx, ty, tz, qx, qy, qz, qw = (float(v) for v in payload)
                pose.pose.position.x, pose.pose.position.y, pose.pose.position.z = tx, ty, tz
                o = pose.pose.orientation
                o.x, o.y, o.z, o.w = qx, qy, qz, qw
                bag.write(GROUND_TRUTH_TOPIC, pose, stamp)
    print("%s: %d rgb, %d depth images%s (%s topics, camera from %s)" % (
        args.out, len(rgb), len(depth), ", ground truth" if os.path.isfile(gt_path) else "",
        "D435i" if args.d435i else "TUM", config_path))


if __name__ == "__main__":
    main()
