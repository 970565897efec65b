#!/usr/bin/python3
"""Writes the fuzzers' seed corpora into OUT/<target>/ from the shared data and the repo.

usage: fuzz_seeds.py SHARED_DATA_DIR REPO_DIR OUT_DIR

Seeds from ../shared stay in build/ (never committed): the first lines of each TUM folder's
lists, its first image pair shrunk to a few pixels as ROS messages, keyframe, map-update and
snapshot messages posed along its ground truth. Runs with the system Python and a workspace's
devel/lib/python3/dist-packages on PYTHONPATH (the ply_slam messages).
"""
import glob
import io
import os
import sys

import cv2
import numpy as np
import yaml
from geometry_msgs.msg import Pose, PoseStamped
from ply_slam.msg import (CameraMsg, FeatureMsg, InstanceMsg, JournalEntryMsg, KeyFrameMsg,
                          KeyFramePoseMsg, KeypointMsg, LandmarkCountsMsg, LandmarkMsg, Line3DMsg,
                          LineFitMsg, LineLinkMsg, MapLineMsg, MapPointMsg, MappingJobMsg,
                          MapSnapshotMsg, MapUpdateMsg, PointLinkMsg, RigidTransformMsg)
from sensor_msgs.msg import CameraInfo, Image

HEAD_LINES = 12  # per list file: enough for every format, small enough to mutate fast
SIDE = (16, 12)  # images shrunk to this (w, h)


def write(out, target, name, data):
    os.makedirs(os.path.join(out, target), exist_ok=True)
    with open(os.path.join(out, target, name), "wb") as f:
        f.write(data)


def serialize(*msgs):
    buf = io.BytesIO()
    for m in msgs:
        m.serialize(buf)
    return buf.getvalue()


def head(path):
    if not os.path.isfile(path):
        return b""
    with open(path, "rb") as f:
        return b"".join(f.readlines()[:HEAD_LINES])


def ground_truth(folder):
    poses = []
    for line in head(os.path.join(folder, "groundtruth.txt")).decode().splitlines():
        v = line.split()
        if len(v) == 8 and not line.startswith("#"):
            poses.append([float(x) for x in v])
    return poses or [[0, 0, 0, 0, 0, 0, 0, 1]]


def pose(v):
    p = Pose()
    p.position.x, p.position.y, p.position.z = v[1:4]
    p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w = v[4:8]
    return p


def rigid_cw(v):
    """The world -> camera transform of a ground-truth line (camera -> world) as a 3x4 matrix."""
    x, y, z, w = np.array(v[4:8]) / np.linalg.norm(v[4:8])
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    t = -r.T @ np.array(v[1:4])
    return RigidTransformMsg(matrix=list(np.hstack([r.T, t[:, None]]).ravel()))


def mapping_job(v, rgb, depth):
    """A keyframe of four features with a report of every kind of entry, and its images."""
    j = MappingJobMsg(id=4, frame_id=12, stamp=v[0], T_cw=rigid_cw(v), image_width=SIDE[0],
                      image_height=SIDE[1], depth_dt=0.01, line_slots=2, followed_updates=3)
    j.features = [FeatureMsg(x=3.0 * i, y=2.0 * i, size=31, angle=10.0 * i, response=0.5,
                             octave=i % 3, rectified_u=3.0 * i, rectified_v=2.0 * i, u=3.0 * i,
                             v=2.0 * i, depth=1.0 + 0.2 * i) for i in range(4)]
    j.descriptors = bytes((5 * i) % 256 for i in range(4 * 32))
    point = MapPointMsg(id=9, min_distance=0.2, max_distance=3.0, position_weight=10.0,
                        descriptor=bytes(range(32)), visible=1, found=1, first_keyframe=4)
    point.normal.z = 1.0
    line = MapLineMsg(id=2, start_weight=1.0, end_weight=2.0, descriptor=bytes(range(32)),
                      first_keyframe=4, observations=1, found=1)
    line.end.x = 1.0
    r = j.report
    r.keyframe = 4
    r.points = [LandmarkCountsMsg(id=1, visible=2, found=1)]
    r.lines = [LandmarkCountsMsg(id=2, found=1)]
    r.line_fits = [LineFitMsg(id=2, start_weight=1.0, end_weight=1.0)]
    r.point_links = [PointLinkMsg(keypoint=0, id=9, created=[point]),
                     PointLinkMsg(keypoint=2, id=1, weight=5.0)]
    r.line_links = [LineLinkMsg(line=1, id=2, created=[line])]
    j.rgb = image(rgb, "bgr8")
    j.depth = image(depth.astype(np.float32) / 5000.0, "32FC1")
    j.label_image = image(np.ones(depth.shape, np.uint16), "16UC1")
    j.instances = [InstanceMsg(id=1, class_name="person", score=0.8, dynamic=True)]
    j.dynamic_mask.encoding = "mono8"
    return j


def image(array, encoding):
    m = Image()
    m.height, m.width = array.shape[:2]
    m.encoding = encoding
    m.step = array.strides[0]
    m.data = array.tobytes()
    return m


def first_pair(folder):
    """The first rgb and depth image named in the folder's lists, shrunk to SIDE."""
    def first(name):
        for line in head(os.path.join(folder, name)).decode().splitlines():
            if line and not line.startswith("#"):
                return os.path.join(folder, line.split()[1])
    rgb = cv2.resize(cv2.imread(first("rgb.txt")), SIDE, interpolation=cv2.INTER_AREA)
    depth = cv2.imread(first("depth.txt"), cv2.IMREAD_UNCHANGED)
    depth = cv2.resize(depth, SIDE, interpolation=cv2.INTER_NEAREST)
    return rgb, depth


def camera(config):
    c = yaml.safe_load(open(config))["camera"]
    m = CameraMsg(fx=c["fx"], fy=c["fy"], cx=c["cx"], cy=c["cy"], width=SIDE[0], height=SIDE[1])
    m.distortion = list(c.get("distortion", []))
    m.depth_factor, m.min_depth, m.max_depth = 5000.0, 0.1, 8.0
    return m


def keyframe(i, v, cam, rgb, depth, with_images):
    k = KeyFrameMsg(id=i, frame_id=3 * i, stamp=v[0], T_wc=pose(v), camera=cam)
    k.sequence = i
    k.keypoints = [KeypointMsg(u=2.0 * j, v=1.5 * j, depth=1.0 + 0.1 * j, level=j % 3,
                               landmark=j if j % 2 else -1) for j in range(4)]
    k.descriptor_bytes = 32
    k.descriptors = bytes((7 * j) % 256 for j in range(4 * 32))
    k.points = [LandmarkMsg(id=j, position=pose(v).position) for j in (1, 3)]
    k.lines = [Line3DMsg(id=5, start=pose(v).position, end=pose(v).position)]
    k.instances = [InstanceMsg(id=1, class_name="person", score=0.8, dynamic=True)]
    if with_images:
        k.rgb = image(rgb, "bgr8")
        k.depth = image(depth.astype(np.float32) / 5000.0, "32FC1")
        k.label_image = image(np.ones(depth.shape, np.uint16), "16UC1")
        k.dynamic_mask = image(np.zeros(depth.shape, np.uint8), "mono8")
    else:  # 0x0 images, as in a snapshot
        k.rgb.encoding, k.depth.encoding = "bgr8", "32FC1"
        k.label_image.encoding, k.dynamic_mask.encoding = "16UC1", "mono8"
    return k


def sequence_seeds(folder, config, out):
    name = os.path.basename(folder)
    lists = [head(os.path.join(folder, f))
             for f in ("rgb.txt", "depth.txt", "associations.txt", "groundtruth.txt")]
    write(out, "fuzz_tum_lists", name, b"\0".join(lists))
    write(out, "fuzz_tum_lists", name + "_no_associations",
          b"\0".join([lists[0], lists[1], b"", lists[3]]))

    rgb, depth = first_pair(folder)
    poses = ground_truth(folder)
    cam = camera(config)
    info = CameraInfo(width=SIDE[0], height=SIDE[1], distortion_model="plumb_bob")
    info.K = [cam.fx, 0, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1]
    info.D = cam.distortion
    for enc, colour in (("rgb8", rgb[:, :, ::-1]), ("bgra8", cv2.cvtColor(rgb, cv2.COLOR_BGR2BGRA))):
        c = image(np.ascontiguousarray(colour), enc)
        c.header.stamp.secs = 1305031102
        metres = image(depth.astype(np.float32) / 5000.0, "32FC1")
        units = image(depth, "16UC1")
        for d, tag in ((metres, "32FC1"), (units, "16UC1")):
            d.header.stamp = c.header.stamp
            write(out, "fuzz_rgbd_decoder", "%s_%s_%s" % (name, enc, tag), serialize(c, d, info))

    k0 = keyframe(0, poses[0], cam, rgb, depth, True)
    write(out, "fuzz_keyframe_msg", name, serialize(k0))
    write(out, "fuzz_keyframe_msg", name + "_no_images",
          serialize(keyframe(1, poses[-1], cam, rgb, depth, False)))

    update = MapUpdateMsg(stamp=poses[-1][0], whole_map=True)
    update.keyframes = [KeyFramePoseMsg(id=i, T_cw=rigid_cw(v), parent=i - 1)
                        for i, v in enumerate(poses[:4])]
    update.points = k0.points
    update.lines = k0.lines
    update.erased_points = [3]
    update.erased_lines = [1]
    update.erased_keyframes = [2]
    update.journal = [JournalEntryMsg(change=c, keyframe=1, point=3, winner=1, index=2,
                                      min_point_observers=3) for c in range(5)]
    update.world_corrections = [rigid_cw(poses[1])]
    write(out, "fuzz_map_update_msg", name, serialize(update))
    write(out, "fuzz_mapping_job_msg", name, serialize(mapping_job(poses[0], rgb, depth)))

    snapshot = MapSnapshotMsg(next_keyframe_sequence=2, next_update_sequence=1)
    snapshot.keyframes = [keyframe(i, v, cam, rgb, depth, False) for i, v in enumerate(poses[:2])]
    for v in poses[:6]:
        p = PoseStamped(pose=pose(v))
        p.header.stamp.secs = int(v[0])
        p.header.stamp.nsecs = int((v[0] % 1) * 1e9)
        snapshot.trajectory.append(p)
    write(out, "fuzz_map_snapshot_msg", name, serialize(snapshot))


def main():
    shared, repo, out = sys.argv[1:4]
    for config in glob.glob(os.path.join(repo, "config", "*.yaml")) + \
            glob.glob(os.path.join(repo, "test", "ros", "*.yaml")):
        write(out, "fuzz_config", os.path.basename(config), open(config, "rb").read())
    folders = sorted(os.path.dirname(p) for p in glob.glob(os.path.join(shared, "*", "*", "rgb.txt")))
    for folder in folders:
        fr = "tum_fr1.yaml" if "freiburg1" in folder or "fr1" in folder else "bonn.yaml"
        sequence_seeds(folder, os.path.join(repo, "config", fr), out)
    print("[fuzz] seeds from %d folders and the repo's configs in %s" % (len(folders), out))


if __name__ == "__main__":
    main()
