"""Benchmark: reading a one-hour recording.

Writes ~200k /rosout lines, /amcl_pose at 5 Hz, /joy_priority, /power/is_charging and /diagnostics at 1 Hz,
with and without >= 1 GB of camera images on an unsubscribed topic, then reports (median of N runs, each in a
fresh process): load time, the time the image topic adds, /rosout lines decoded per second, peak RSS.
Targets (issue): the image topic adds < 0.5 s; decoding >= 100k log lines/s.

    .venv/bin/python scripts/bench_events.py [--storage sqlite3|mcap] [--runs 5] [--dir DIR]
"""

from __future__ import annotations

import argparse
import json
import random
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from rosbags.rosbag2 import StoragePlugin, Writer

from hexar.evals.scenarios.bag import TYPESTORE, sec_ns
from hexar.events import contract as c

T = TYPESTORE.types
HOUR_S = 3600
LOG_LINES = 200_000
IMAGE_BYTES = 640 * 480 * 3
IMAGES = 1200  # 1.1 GB
LOGGERS = ["controller_server", "planner_server", "bt_navigator", "amcl", "behavior_server",
           "local_costmap.local_costmap", "global_costmap.global_costmap"]
MESSAGES = ["Passing new path to controller.", "Received a goal, begin computing control effort.",
            "Control loop missed its desired rate of 20.0000Hz", "Reached the goal!", "Goal succeeded",
            "Begin navigating from current location (0.00, 0.00) to (4.20, 2.10)"]


def _stamp(t: int) -> object:
    return T["builtin_interfaces/msg/Time"](sec=t // 1_000_000_000, nanosec=t % 1_000_000_000)


def write(path: Path, storage: str, images: bool) -> None:
    rng = random.Random(1)
    t0 = sec_ns(1_741_600_800)
    plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
    with Writer(path, version=9, storage_plugin=plugin) as w:
        log = w.add_connection(c.ROSOUT, c.LOG_TYPE, typestore=TYPESTORE)
        pose = w.add_connection(c.AMCL_POSE, c.POSE_COV_TYPE, typestore=TYPESTORE)
        joy = w.add_connection(c.JOY_PRIORITY, c.BOOL_TYPE, typestore=TYPESTORE)
        chg = w.add_connection(c.IS_CHARGING, c.BOOL_TYPE, typestore=TYPESTORE)
        cam = w.add_connection("/head_front_camera/rgb/image_raw", "sensor_msgs/msg/Image", typestore=TYPESTORE)
        events: list[tuple[int, object, bytes]] = []
        for i in range(LOG_LINES):
            t = t0 + i * (HOUR_S * 1_000_000_000 // LOG_LINES)
            m = T["rcl_interfaces/msg/Log"](stamp=_stamp(t), level=20, name=rng.choice(LOGGERS),
                                             msg=rng.choice(MESSAGES), file="src.cpp", function="f", line=1)
            events.append((t, log, TYPESTORE.serialize_cdr(m, c.LOG_TYPE)))
        cov = np.zeros(36, dtype=np.float64)
        for i in range(HOUR_S * 5):
            t = t0 + i * 200_000_000
            p = T["geometry_msgs/msg/Pose"](position=T["geometry_msgs/msg/Point"](x=1.0, y=2.0, z=0.0),
                                            orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))
            m = T["geometry_msgs/msg/PoseWithCovarianceStamped"](
                header=T["std_msgs/msg/Header"](stamp=_stamp(t), frame_id="map"),
                pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=p, covariance=cov))
            events.append((t, pose, TYPESTORE.serialize_cdr(m, c.POSE_COV_TYPE)))
        for i in range(HOUR_S):
            t = t0 + i * 1_000_000_000
            for conn in (joy, chg):
                events.append((t, conn, TYPESTORE.serialize_cdr(T["std_msgs/msg/Bool"](data=False), c.BOOL_TYPE)))
        if images:
            data = np.frombuffer(rng.randbytes(IMAGE_BYTES), dtype=np.uint8)
            for i in range(IMAGES):
                t = t0 + i * (HOUR_S * 1_000_000_000 // IMAGES)
                m = T["sensor_msgs/msg/Image"](header=T["std_msgs/msg/Header"](stamp=_stamp(t), frame_id="cam"),
                                               height=480, width=640, encoding="rgb8", is_bigendian=0,
                                               step=640 * 3, data=data)
                events.append((t, cam, TYPESTORE.serialize_cdr(m, "sensor_msgs/msg/Image")))
        for t, conn, raw in sorted(events, key=lambda e: e[0]):
            w.write(conn, t, raw)  # type: ignore[arg-type]


# ru_maxrss survives execve on Linux (the child would report the parent's peak); VmHWM belongs to the new image.
CHILD = """
import json, sys, time
from hexar.events import read_recording
t = time.perf_counter()
log = read_recording(sys.argv[1])
dt = time.perf_counter() - t
hwm = next(int(l.split()[1]) for l in open("/proc/self/status") if l.startswith("VmHWM"))
print(json.dumps({"load_s": dt, "logs": len(log.logs), "poses": len(log.poses), "rss_mb": hwm / 1024}))
"""


def measure(path: Path, runs: int) -> dict[str, float]:
    samples = []
    for _ in range(runs):
        out = subprocess.run([sys.executable, "-c", CHILD, str(path)], capture_output=True, text=True, check=True)
        samples.append(json.loads(out.stdout))
    load = statistics.median(s["load_s"] for s in samples)
    logs = samples[0]["logs"]
    return {"load_s": load, "logs": logs, "log_lines_per_s": logs / load,
            "peak_rss_mb": statistics.median(s["rss_mb"] for s in samples)}


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--storage", default="sqlite3", choices=["sqlite3", "mcap"])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--dir", type=Path, default=None)
    args = ap.parse_args()
    base = args.dir or Path(tempfile.mkdtemp(prefix="hexar-bench-"))
    plain, heavy = base / f"hour_{args.storage}", base / f"hour_{args.storage}_images"
    t = time.perf_counter()
    if not plain.exists():
        write(plain, args.storage, images=False)
    if not heavy.exists():
        write(heavy, args.storage, images=True)
    size = sum(f.stat().st_size for f in heavy.iterdir()) / 1e9
    print(f"wrote recordings in {time.perf_counter() - t:.0f} s (with images: {size:.2f} GB)", file=sys.stderr)
    a, b = measure(plain, args.runs), measure(heavy, args.runs)
    added = b["load_s"] - a["load_s"]
    result = {"storage": args.storage, "runs": args.runs, "recording_gb": round(size, 2),
              "without_images": a, "with_images": b, "image_topic_adds_s": added,
              "targets": {"image_topic_adds_s": 0.5, "log_lines_per_s": 100_000},
              "meets": {"image_topic_adds_s": added < 0.5, "log_lines_per_s": b["log_lines_per_s"] >= 100_000}}
    print(f"{'':28}{'without images':>16}{'with 1.1 GB images':>20}")
    print(f"{'load time (median)':28}{a['load_s']:>15.2f}s{b['load_s']:>19.2f}s")
    print(f"{'/rosout lines decoded/s':28}{a['log_lines_per_s']:>16,.0f}{b['log_lines_per_s']:>20,.0f}")
    print(f"{'peak RSS':28}{a['peak_rss_mb']:>14.0f}MB{b['peak_rss_mb']:>18.0f}MB")
    print(f"image topic adds {added:+.2f} s (target < 0.5 s); "
          f"decoding {b['log_lines_per_s']:,.0f} lines/s (target >= 100,000)")
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
