#!/usr/bin/python3
"""The soak's verdict (scripts/soak.sh): checks a finished run folder and writes the results.

usage: soak_report.py RUN_DIR PLY_SLAM_EVAL RESULTS_MD COMMAND SCENE RENDERED_FRAMES

Checks: both nodes alive at the end and no "process has died" in the launch logs; the services
answered success; every frame sent has a pose or is counted lost (tracked + lost = frames sent,
the saved trajectory holds exactly the tracked stamps, all of them sent); every malformed message
is counted under the kind the node reports (~stats for the tracker, its log for the mapper, whose
faults come > 5 s apart so that each gets its own warning) and each kind has a warning in the
log; ATE against the looped ground truth. Memory: RSS of both nodes against the map's size
(soak.csv), plotted into soak.png and docs/soak.png. Writes report.json and the section between
<!-- soak:begin --> and <!-- soak:end --> of RESULTS_MD. Exit 1 when a check failed.
"""
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ATE_LIMIT = 0.02  # m: the office alone gives ~0.002 offline; 10x means something went wrong
# Where each malformed kind must show up: the tracker's ~stats key, or the mapper's log kind.
TRACKER_KEYS = ("encoding", "size", "empty", "camera_info", "stamp", "unpaired", "map_update")
MAPPER_KINDS = ("mapping_job", "pose")


def read(path):
    with open(path) as f:
        return f.read()


def final_stats(sent):
    """The tracker's counters: the last ~stats the publisher saw (taken after the last frame)."""
    return dict(sent["final_stats"])


def warnings(log, kind):
    """Warning lines of BadInputLog for `kind`, and the largest 'N in all' among them."""
    lines = re.findall(r"skipped input \(%s\):.*?(\d+) in all\]" % re.escape(kind), log)
    return len(lines), max((int(n) for n in lines), default=0)


def fit(rows, key, first_frame):
    """Least-squares slope of `key` per 1000 frames over the rows from `first_frame` on."""
    pts = [(r["frames"], r[key]) for r in rows if r["frames"] >= first_frame]
    if len(pts) < 2:
        return float("nan")
    n = len(pts)
    mx = sum(p[0] for p in pts) / n
    my = sum(p[1] for p in pts) / n
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return 1000.0 * sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx else float("nan")


def at(rows, frame):
    """The first sample at or after `frame` frames (the last one if none)."""
    return next((r for r in rows if r["frames"] >= frame), rows[-1])


def plot(rows, path):
    frames = [r["frames"] for r in rows]
    fig, (top, mid, bottom) = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    top.plot(frames, [r["tracker_rss_mb"] for r in rows], label="tracking_node")
    top.plot(frames, [r["mapper_rss_mb"] for r in rows], label="mapping_node")
    top.set_ylabel("RSS (MB)")
    top.legend()
    top.set_title("soak: RSS and map size against frames tracked")
    mid.plot(frames, [r["keyframes"] for r in rows], label="keyframes kept", color="C2")
    mid.set_ylabel("keyframes")
    twin = mid.twinx()
    twin.plot(frames, [r["map_points"] for r in rows], label="map points", color="C3")
    twin.set_ylabel("map points")
    mid.legend(loc="upper left")
    twin.legend(loc="upper right")
    bottom.plot(frames, [r["dense_points"] / 1000 for r in rows], label="dense points / 1000")
    bottom.plot(frames, [r["octree_voxels"] / 1000 for r in rows], label="octree voxels / 1000")
    bottom.set_xlabel("frames done (tracked + lost)")
    bottom.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=80)


def main():
    run, evaluator, results, command, scene, rendered = sys.argv[1:7]
    sent = json.load(open(os.path.join(run, "sent.json")))
    tracker_log, mapper_log = read(os.path.join(run, "tracker.log")), read(
        os.path.join(run, "mapper.log"))
    stats = final_stats(sent)
    checks = []  # (what, expected, measured, ok)

    def check(what, expected, measured, ok):
        checks.append((what, str(expected), str(measured), bool(ok)))

    alive = read(os.path.join(run, "alive.txt")).split("\n")
    died = len(re.findall(r"process has died", tracker_log + mapper_log))
    check("nodes alive at the end", "2", sum(l.startswith("alive") for l in alive),
          all(l.startswith("alive") for l in alive if l))
    check("crashes (roslaunch 'process has died')", 0, died, died == 0)
    for name in ("save_trajectory", "save_map"):
        reply = read(os.path.join(run, name + ".txt"))
        check(name + " answers success", "success: True", " ".join(reply.split())[:160],
              "success: True" in reply)

    # Frames: each one sent has a pose or is counted lost; the trajectory holds the tracked ones.
    good = [float(s) for s in read(os.path.join(run, "good.txt")).split()]
    tracked, lost = int(stats.get("tracked", 0)), int(stats.get("lost", 0))
    check("frames sent = tracked + lost", sent["frames_sent"], "%d + %d" % (tracked, lost),
          tracked + lost == sent["frames_sent"])
    trajectory = []
    path = os.path.join(run, "CameraTrajectory.txt")
    if os.path.exists(path):
        trajectory = [float(l.split()[0]) for l in open(path) if l.strip() and l[0] != "#"]
    sent_stamps = set(round(s, 4) for s in good)
    foreign = [s for s in trajectory if round(s, 4) not in sent_stamps]
    zero_depth = sent["malformed"].get("all-zero depth", 0)
    check("saved poses = tracked (stamps all sent: good frames or all-zero-depth ones)", tracked,
          "%d (%d not a good frame's)" % (len(trajectory), len(foreign)),
          len(trajectory) == tracked and len(foreign) <= zero_depth)
    check("stalls (no pose within 20 s)", 0, len(sent["stalls"]), not sent["stalls"])

    # Malformed messages, by where they must be counted.
    expected = {}
    for name, (node, kind) in sent["expected"].items():
        if kind:
            expected.setdefault((node, kind), 0)
            expected[(node, kind)] += sent["malformed"][name]
    for key in TRACKER_KEYS:
        n = expected.get(("tracker", key), 0)
        logged, in_all = warnings(tracker_log, key)
        measured = int(stats.get(key, 0))
        check("tracker counts '%s'" % key, n, "%d (%d warnings, last says %d in all)" % (
            measured, logged, in_all), measured == n and (n == 0 or logged > 0))
    dropped = int(stats.get("rgb_received", 0) + stats.get("depth_received", 0) -
                  2 * stats.get("synchronised", 0))
    check("images the synchroniser dropped = counted 'unpaired'", dropped,
          int(stats.get("unpaired", 0)), dropped == stats.get("unpaired", 0))
    for kind in MAPPER_KINDS:
        n = expected.get(("mapper", kind), 0)
        logged, in_all = warnings(mapper_log, kind)
        check("mapper warns '%s' (one each)" % kind, n, "%d warnings, last says %d in all" % (
            logged, in_all), logged == n and in_all == n)
    other = {k: v for k, v in stats.items()
             if k in ("invalid_frame", "error", "behind", "dropped_behind") and v}
    check("other skips (invalid_frame, error, dropped behind)", 0, other or 0, not other)

    ate = {}
    if trajectory:
        out = subprocess.run([evaluator, "ate", os.path.join(run, "groundtruth.txt"), path,
                              "--json"], capture_output=True, text=True)
        ate = json.loads(out.stdout) if out.returncode == 0 else {"error": out.stderr.strip()}
    rmse = ate.get("rmse", float("nan"))
    check("ATE RMSE against the looped ground truth (m)", "<= %g" % ATE_LIMIT,
          "%.4f (%s pairs)" % (rmse, ate.get("pairs")), rmse <= ATE_LIMIT)
    # All-zero depth: a pose from the map alone is fine if it is right. The frame shows the
    # image of the good frame after it (same true pose): their estimates must agree.
    zero = [float(s) for s in read(os.path.join(run, "zero_depth.txt")).split()]
    positions = {}
    if trajectory:
        for line in open(path):
            if line.strip() and line[0] != "#":
                f = line.split()
                positions[round(float(f[0]), 4)] = [float(v) for v in f[1:4]]
    stamps = sorted(positions)
    gaps = []
    for z in (round(s, 4) for s in zero):
        later = [s for s in stamps if s > z][:1]
        if z in positions and later:
            gaps.append(sum((a - b) ** 2 for a, b in zip(positions[z], positions[later[0]])) ** 0.5)
    largest = max(gaps, default=0.0)
    check("all-zero-depth frames: posed (largest distance to the next frame's pose, same view, "
          "m) or lost", "<= %g" % ATE_LIMIT, "%d of %d posed (%.4f)" % (len(gaps), len(zero),
                                                                      largest),
          largest <= ATE_LIMIT)

    # Memory against the map.
    rows = []
    with open(os.path.join(run, "soak.csv")) as f:
        for r in csv.DictReader(f):
            if r["mapper_rss_mb"] == "" or int(r["frames"]) == 0:
                continue
            rows.append({k: float(v) for k, v in r.items()})
    plot(rows, os.path.join(run, "soak.png"))
    docs_png = os.path.join(os.path.dirname(results), "soak.png")
    shutil.copyfile(os.path.join(run, "soak.png"), docs_png)
    frames = int(rows[-1]["frames"])
    marks = sorted(set([int(rows[0]["frames"])] + list(range(1000, frames, 1000)) + [frames]))
    keys = ("tracker_rss_mb", "mapper_rss_mb", "keyframes", "map_points", "dense_points",
            "octree_voxels")
    warm = min(2000, frames // 2)
    slopes = {k: fit(rows, k, warm) for k in keys}
    report = {"checks": checks, "ate": ate, "stats": stats, "sent": sent, "slopes_per_1000": slopes,
              "samples": len(rows)}
    with open(os.path.join(run, "report.json"), "w") as f:
        json.dump(report, f, indent=1)

    ok = all(c[3] for c in checks)
    lines = [
        "<!-- soak:begin -->",
        "<!-- generated by scripts/soak.sh; edits between these markers are overwritten -->",
        "### Soak: 10 000 frames through both nodes with 1 % malformed messages",
        "",
        "- date: %s" % time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "- command: `%s`" % command,
        "- machine: %d cores, shared with another engineer's experiments" % os.cpu_count(),
        "- sequence: synthetic %s, %s frames rendered with `--loop` (seamless), looped to %d good "
        "frames with stamps 1/30 s apart; config its camera.yaml with `loop.enabled: true` (dense "
        "maps and grid on); `tracking.launch` + `mapping.launch` with their defaults; dense cloud "
        "and octree subscribed (as rviz would)." % (scene, rendered, sent["good_frames"]),
        "- pace: a frame goes out when at most 2 wait for the tracker, never faster than 30 Hz: "
        "%.1f frames/s over %.0f s (%.0f s of it waiting for the tracker)." % (
            sent["good_frames"] / sent["seconds"], sent["seconds"], sent["waited_for_tracker_s"]),
        "- malformed: %d, every 100th slot, in turn: %s." % (
            sum(sent["malformed"].values()),
            "; ".join("%s %d" % (k, v) for k, v in sent["malformed"].items())),
        "",
        "| check | expected | measured | ok |",
        "|---|---|---|---|",
    ]
    lines += ["| %s | %s | %s | %s |" % (w, e, m.replace("|", "/"), "yes" if o else "**NO**")
              for w, e, m, o in checks]
    lines += [
        "",
        "RSS (VmRSS, sampled every few seconds) and the map (`build/soak/run/soak.csv`, plot "
        "`docs/soak.png`):",
        "",
        "| frames | tracking_node RSS (MB) | mapping_node RSS (MB) | keyframes kept | map points "
        "| dense points | octree voxels |",
        "|---:|---:|---:|---:|---:|---:|---:|",
    ]
    shown = []
    for m in marks:
        r = at(rows, m)
        if r in shown:
            continue
        shown.append(r)
        lines.append("| %d | %.1f | %.1f | %d | %d | %d | %d |" % tuple(
            [r["frames"]] + [r[k] for k in keys]))
    lines += [
        "",
        "Slopes per 1000 frames from frame %d on (least squares): tracking_node %+.2f MB, "
        "mapping_node %+.2f MB (%+.0f and %+.0f bytes per frame); keyframes %+.1f, map points "
        "%+.0f, dense points %+.0f, octree voxels %+.0f." % (
            (warm, slopes["tracker_rss_mb"], slopes["mapper_rss_mb"],
             slopes["tracker_rss_mb"] * 1048.576, slopes["mapper_rss_mb"] * 1048.576) +
            tuple(slopes[k] for k in keys[2:])),
        "<!-- soak:end -->",
    ]
    section = os.path.join(run, "section.md")
    with open(section, "w") as f:
        f.write("\n".join(lines) + "\n")
    here = os.path.dirname(os.path.realpath(__file__))
    subprocess.run(["/usr/bin/python3", os.path.join(here, "results_section.py"), "soak", results,
                    section], check=True)
    print("\n".join(lines))
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
