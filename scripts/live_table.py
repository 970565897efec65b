#!/usr/bin/python3
"""The live benchmark's table (scripts/live_benchmark.sh) from its rows (one JSON object a run).

usage: live_table.py ROWS.jsonl LAUNCH
"""
import json
import sys

COMMAND = {"tum_bag": "scripts/live_benchmark.sh --no-build",
           "turtlebot3": "scripts/live_benchmark.sh --no-build --launch turtlebot3 --rates 1.0"}


def number(value, digits=0):
    return "–" if value is None else ("%.*f" % (digits, value))


def row_text(r):
    s = r["stats"]
    posed = s.get("tracked")
    ate = (r.get("ate") or {}).get("rmse")
    offline = r.get("offline_ate")
    ratio = ate / offline if ate is not None and offline else None
    return "| %s | %s | %.1f | %d | %s | %s | %s | %s / %s / %s | %s / %s / %s | %s | %s / %s | %s / %s (%s) | %s / %s | %s | %s | %s |" % (
        r["sequence"], r["model"].replace("yolov8n-seg-", "").replace(".onnx", ""), r["rate"],
        r["frames"], number(posed), number(s.get("lost")), number(s.get("dropped_behind")),
        number(s.get("lag_arrival_ms_p50")), number(s.get("lag_arrival_ms_p95")),
        number(s.get("lag_arrival_ms_max")), number(s.get("lag_stamp_ms_p50")),
        number(s.get("lag_stamp_ms_p95")), number(s.get("lag_stamp_ms_max")),
        number(s.get("segmented")), number(r.get("tracker_cpu_percent")),
        number(r.get("mapper_cpu_percent")), number(r.get("tracker_peak_rss_mb")),
        number(r.get("mapper_peak_rss_mb")), number(r.get("offline_peak_rss_mb")),
        number(s.get("follow_cpu_ms_max"), 1), number(r.get("mapper_callback_cpu_ms_max"), 1),
        number(ate, 4), number(offline, 4), number(ratio, 2))


def main():
    rows = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]
    launch = sys.argv[2]
    print("<!-- live_%s:begin -->" % launch)
    print("Command: `%s` (2 cores, nothing else running; bags from `scripts/tum_to_bag.py`, "
          "played by `rosbag play --clock` at the rate given, `%s.launch` with its defaults and "
          "`model:=`; the offline columns: `ply_slam_tum` with the same config and model). "
          "*Lag*: ms from the RGB-D pair's arrival, and from its image stamp (bag clock), to "
          "`~pose`; p50 / p95 / max over the posed frames. *Longest CPU*: thread CPU of "
          "tracking_node's longest follow of a map update between two frames (apart only) and of "
          "mapping_node's longest callback, each to stay under a frame period (33 ms at 30 Hz). "
          "*Dropped*: frames older than "
          "`frame_max_age` when the tracker came to them. CPU: %% of one core over the run "
          "(the network runs in tracking_node). RSS: peak (VmHWM), MB." % (COMMAND[launch], "turtlebot3_d435i" if launch == "turtlebot3" else launch))
    print()
    print("| sequence | segmenter | rate | frames | posed | lost | dropped | lag from arrival ms | "
          "lag from stamp ms | segmented | CPU % tracker / mapper | RSS MB tracker / mapper "
          "(offline) | longest CPU ms: follow / mapper callback | ATE live (m) | ATE offline (m) | "
          "live / offline |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(row_text(r))
    print("<!-- live_%s:end -->" % launch)


if __name__ == "__main__":
    main()
