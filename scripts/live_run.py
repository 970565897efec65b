#!/usr/bin/python3
"""One live run for scripts/live_benchmark.sh: a bag through tum_bag.launch (both nodes; --robot:
turtlebot3_d435i.launch as a robot runs it) at its
recorded rate times RATE, as a robot would see it, on a roscore of its own. Meters both nodes
(CPU seconds from /proc/PID/stat, peak resident memory VmHWM), reads tracking_node's ~stats at
the end (frames posed, dropped, latencies, the longest follow of a map update), asks
mapping_node's ~save_trajectory (its longest callback) and scores it
with ply_slam_eval. Prints one JSON object; the logs stay in OUT.

usage: live_run.py --bag B --config C --frames N --groundtruth GT --eval BIN --out OUT
                   [--model ONNX] [--rate R] [--robot]
                   [--map DIR --align-with REF --align-truth REF_GT]
--map: tracking_node localises in DIR/map.plymap (localisation only); the ATE is then taken in
the map's frame: aligned as REF (the trajectory of the run that made the map) is to REF_GT.
"""
import argparse
import json
import os
import re
import signal
import socket
import subprocess
import sys
import time

NS = "/ply_slam/"
CLOCK_TICKS = os.sysconf("SC_CLK_TCK")


def free_port():
    s = socket.socket()
    s.bind(("", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def cpu_seconds(pid):
    """User + system CPU of a process so far (fields 14 and 15 of /proc/PID/stat)."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / CLOCK_TICKS
    except OSError:
        return None


def peak_rss_mb(pid):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return None


def child_pid(parent, binary, timeout=30.0):
    """The process among `parent`'s descendants whose command is `binary`."""
    end = time.time() + timeout
    while time.time() < end:
        out = subprocess.run(["ps", "-e", "-o", "pid=,ppid=,args="], capture_output=True,
                             text=True).stdout
        rows = [line.split(None, 2) for line in out.splitlines() if line.strip()]
        children = {}
        for pid, ppid, *args in rows:
            children.setdefault(int(ppid), []).append((int(pid), args[0] if args else ""))
        stack = [parent]
        while stack:
            for pid, args in children.get(stack.pop(), []):
                if args.split()[0].endswith("/" + binary) or args.split()[0] == binary:
                    return pid
                stack.append(pid)
        time.sleep(0.2)
    raise RuntimeError("no %s started under roslaunch within %.0f s" % (binary, timeout))


def parse_stats(text):
    values = {}
    for item in text.split():
        key, _, value = item.partition("=")
        try:
            values[key] = float(value)
        except ValueError:
            pass
    return values


class Stats:
    """tracking_node's latched ~stats, newest message."""

    def __init__(self, rospy, String):
        self.values = {}
        rospy.Subscriber(NS + "tracking_node/stats", String, self._on)

    def _on(self, msg):
        self.values = parse_stats(msg.data)

    def done(self):
        v = self.values
        return v.get("tracked", 0) + v.get("lost", 0) + v.get("dropped_behind", 0)


def longest_callback_cpu_ms(reply):
    """mapping_node's save_trajectory reply: "...; longest keyframe or map-update callback W ms,
    C ms of CPU)": C, or None in a reply without it."""
    found = re.search(r"callback [0-9.]+ ms, ([0-9.]+) ms of CPU", reply)
    return float(found.group(1)) if found else None


def process_alive(pid, popen=None):
    """A child of ours stays in /proc as a zombie until it is waited for: poll it."""
    if popen is not None:
        return popen.poll() is None
    return os.path.exists("/proc/%d" % pid)


def wait_for_end(stats, player_alive, frames, quiet_s=5.0, limit_s=600.0):
    """Until the bag has played and every frame is accounted for (or nothing moved for
    quiet_s after the bag ended: frames the synchroniser never paired). Returns when the last
    frame was accounted for."""
    start, last_change, last = time.time(), time.time(), -1
    while time.time() - start < limit_s:
        done = stats.done()
        if done != last:
            last, last_change = done, time.time()
        if not player_alive() and (done >= frames or time.time() - last_change > quiet_s):
            return last_change
        time.sleep(0.1)
    raise RuntimeError("the run did not end within %.0f s" % limit_s)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bag", required=True)
    p.add_argument("--config", required=True)
    p.add_argument("--frames", type=int, required=True)
    p.add_argument("--groundtruth", required=True)
    p.add_argument("--eval", required=True, help="ply_slam_eval binary")
    p.add_argument("--out", required=True)
    p.add_argument("--model", default="")
    p.add_argument("--rate", default="1.0")
    p.add_argument("--robot", action="store_true",
                   help="turtlebot3_d435i.launch (camera:=false) with its defaults, the bag (D435i "
                        "topics) played beside it")
    p.add_argument("--map", default="", help="a saved map's folder to localise in")
    p.add_argument("--align-with", default="", help="with --map: the mapping run's trajectory")
    p.add_argument("--align-truth", default="", help="with --map: its ground truth")
    a = p.parse_args()
    if bool(a.map) != bool(a.align_with) or bool(a.align_with) != bool(a.align_truth):
        p.error("--map, --align-with and --align-truth go together")
    # roslaunch runs the nodes in ROS_HOME: every path absolute.
    a.bag, a.config, a.out = (os.path.abspath(x) for x in (a.bag, a.config, a.out))
    a.model, a.map, a.align_with, a.align_truth = (
        os.path.abspath(x) if x else "" for x in (a.model, a.map, a.align_with, a.align_truth))
    os.makedirs(a.out, exist_ok=True)
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI="http://localhost:%d" % port,
               ROS_HOME=a.out, ROS_LOG_DIR=a.out)
    os.environ.update(env)
    procs = []

    def stop_all():
        for proc in reversed(procs):
            if proc.poll() is None:
                proc.send_signal(signal.SIGINT)
        for proc in reversed(procs):
            try:
                proc.wait(30)
            except subprocess.TimeoutExpired:
                proc.kill()

    try:
        procs.append(subprocess.Popen(["roscore", "-p", str(port)], env=env,
                                      stdout=open(os.path.join(a.out, "roscore.log"), "w"),
                                      stderr=subprocess.STDOUT))
        for _ in range(100):
            if subprocess.run(["rosparam", "list"], env=env, capture_output=True).returncode == 0:
                break
            time.sleep(0.2)
        import rospy
        from std_msgs.msg import String
        rospy.init_node("live_benchmark", anonymous=True, disable_signals=True)
        stats = Stats(rospy, String)
        log = open(os.path.join(a.out, "roslaunch.log"), "w")
        common = ["config:=" + a.config, "rviz:=false", "output:=log", "model:=" + a.model]
        if a.map:
            common += ["map:=" + a.map, "localisation_only:=true"]
        if a.robot:
            subprocess.run(["rosparam", "set", "/use_sim_time", "true"], env=env, check=True)
            args = ["roslaunch", "ply_slam", "turtlebot3_d435i.launch", "camera:=false",
                    "odometry:=false"] + common
        else:
            args = ["roslaunch", "ply_slam", "tum_bag.launch", "bag:=" + a.bag, "rate:=" + a.rate,
                    "sim_time:=true"] + common
        procs.append(subprocess.Popen(args, env=env, stdout=log, stderr=subprocess.STDOUT))
        launch = procs[-1]
        tracker = child_pid(launch.pid, "tracking_node")
        mapper = child_pid(launch.pid, "mapping_node")
        if a.robot:
            procs.append(subprocess.Popen(["rosbag", "play", "--quiet", "--clock", "--delay=3",
                                           "--rate=" + a.rate, a.bag], env=env, stdout=log,
                                          stderr=subprocess.STDOUT))
            player_popen = procs[-1]
            player = player_popen.pid
        else:
            player_popen, player = None, child_pid(launch.pid, "play")
        while stats.values.get("rgb_received", 0) == 0:
            if launch.poll() is not None or not process_alive(player, player_popen):
                raise RuntimeError("roslaunch or the player ended before the first frame (%s)"
                                   % log.name)
            time.sleep(0.05)
        t0 = time.time()
        cpu0 = {n: cpu_seconds(pid) for n, pid in (("tracker", tracker), ("mapper", mapper))}
        # CPU over the frames' span
        wall = wait_for_end(stats, lambda: process_alive(player, player_popen), a.frames) - t0
        result = {"rate": float(a.rate), "model": os.path.basename(a.model) or "none",
                  "frames": a.frames, "wall_s": wall}
        for name, pid in (("tracker", tracker), ("mapper", mapper)):
            result[name + "_cpu_percent"] = 100.0 * (cpu_seconds(pid) - cpu0[name]) / wall
            result[name + "_peak_rss_mb"] = peak_rss_mb(pid)
        result["stats"] = stats.values
        trajectory = os.path.join(a.out, "CameraTrajectory.txt")
        saved = subprocess.run(["rosservice", "call", NS + "mapping_node/save_trajectory",
                                "path: '%s'" % trajectory], env=env, check=True,
                               capture_output=True, text=True, timeout=60)
        result["mapper_callback_cpu_ms_max"] = longest_callback_cpu_ms(saved.stdout)
        in_map = ["--align-with", a.align_with, "--align-truth", a.align_truth] if a.map else []
        ate = subprocess.run([a.eval, "ate", a.groundtruth, trajectory, "--json"] + in_map,
                             capture_output=True, text=True, timeout=60)
        result["ate"] = json.loads(ate.stdout) if ate.returncode == 0 else None
        print(json.dumps(result))
    finally:
        stop_all()


if __name__ == "__main__":
    try:
        main()
    except (RuntimeError, subprocess.CalledProcessError, subprocess.TimeoutExpired) as e:
        sys.exit("live_run.py: %s" % e)
