#!/usr/bin/python3
"""Relocalisation after a kidnap and after a covered lens (issue #55): ply_slam_tum with
--kidnap FROM:TO (frames skipped: the camera jumps) at ten cut positions per sequence, and
--cover FROM:TO (ten black frames) at the same positions; one table row per sequence and kind.

usage: kidnap_benchmark.py BIN_DIR OUT_DIR RESULTS_MD COMMAND SEQUENCE:CONFIG ...

A kidnap at position k of ten starts at frame 20 + k (N - 80) / 9 of an N-frame sequence: after
the map has a few keyframes, before the last 60 frames; it skips 30 frames (1 s at 30 Hz). A
cover blacks out 10 frames at every other of those positions.
"""
import json
import os
import statistics
import subprocess
import sys

KIDNAP_FRAMES, COVER_FRAMES = 30, 10
CUTS = {"kidnap": 10, "cover": 5}  # covers at every other kidnap position


def frames_of(sequence):
    with open(os.path.join(sequence, "rgb.txt")) as f:
        return sum(1 for line in f if line.strip() and not line.startswith("#"))


def run(bin_dir, out, sequence, config, segmenter, option):
    args = [os.path.join(bin_dir, "ply_slam_tum"), "--sequence", sequence, "--config", config,
            "--out", out, "--segmenter", segmenter] + option
    done = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit("kidnap_benchmark: %s failed (exit %d):\n%s" % (" ".join(args), done.returncode,
                                                                 done.stderr[-3000:]))
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def row(name, kind, gaps):
    tracked = [g["frames_until_tracked"] for g in gaps if g["frames_until_tracked"] is not None]
    firsts = [g for g in gaps if "first_error_m" in g]
    ates = [g["ate_after"]["rmse"] for g in gaps if g["ate_after"]["pairs"] > 0]
    fmt = lambda xs, f: f % statistics.median(xs) if xs else "–"
    return "| %s | %s | %d / %d | %s / %d | %s | %s / %s | %s | %d of %d |" % (
        name, kind, len(tracked), len(gaps), fmt(tracked, "%.0f"), max(tracked, default=0),
        fmt([g["first_error_m"] * 100 for g in firsts], "%.1f"),
        fmt([g["first_error_deg"] for g in firsts], "%.2f"),
        "%.2f" % max(g["first_error_deg"] for g in firsts) if firsts else "–",
        fmt([a * 1000 for a in ates], "%.1f"),
        sum(g["wrong_relocalisations"] for g in gaps), sum(g["relocalisations"] for g in gaps))


def main():
    bin_dir, out_root, results, command = sys.argv[1:5]
    rows = []
    for spec in sys.argv[5:]:
        sequence, config = spec.split(":")
        segmenter = "none"  # geometric rejection: the gap, not the network, is measured
        name = os.path.basename(sequence.rstrip("/"))
        n = frames_of(sequence)
        for kind, length in (("kidnap", KIDNAP_FRAMES), ("cover", COVER_FRAMES)):
            gaps = []
            for k in range(0, 10, 10 // CUTS[kind]):
                start = 20 + k * (n - 80) // 9
                out = os.path.join(out_root, "%s_%s_%d" % (name, kind, start))
                summary = run(bin_dir, out, sequence, config, segmenter,
                              ["--" + kind, "%d:%d" % (start, start + length)])
                gaps.append(summary["gap"])
                print("[kidnap_benchmark] %s %s at %d: %s" % (name, kind, start, summary["gap"]),
                      flush=True)
            rows.append(row(name, kind, gaps))
    section = [
        "<!-- kidnap:begin -->",
        "Command: `%s` (ply_slam_tum, each sequence's config, `--segmenter none`; kidnaps at "
        "frames 20 + k (N − 80) / 9, k = 0..9, %d frames skipped; covers at every other of those, "
        "%d frames black). *Tracked again*: runs with a pose after the gap; *frames until*: median / max of "
        "the frames after the gap before the first pose. *First pose*: its motion from the last "
        "pose before the gap against the truth's (median cm; median / max °). *ATE after*: the "
        "poses after the gap aligned as those before it, median over the runs. *Wrong*: "
        "relocalisations more than 0.1 m or 5° off (motion from the last tracked pose)."
        % (command, KIDNAP_FRAMES, COVER_FRAMES),
        "",
        "| sequence | gap | tracked again | frames until | first pose cm | first pose ° | ATE after (mm) | wrong relocalisations |",
        "|---|---|---|---|---|---|---|---|",
    ] + rows + ["<!-- kidnap:end -->"]
    section_path = os.path.join(out_root, "section.md")
    with open(section_path, "w") as f:
        f.write("\n".join(section) + "\n")
    subprocess.run([sys.executable, os.path.join(os.path.dirname(__file__), "results_section.py"),
                    "kidnap", results, section_path], check=True)
    print("\n".join(rows))


if __name__ == "__main__":
    main()
