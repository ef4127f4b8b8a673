"""Benchmark: `hexar triage` over 1,000 simulated recordings, and what its per-recording cost scales with.

1. Throughput: `hexar triage` in a fresh process on 1,000 recordings (17 simulator seeds of the 60 scenarios,
   cut to 1,000), locally with 1 and 2 workers and on a local Ray instance; recordings/s (median of --runs) and
   the peak memory of the whole process tree (driver, workers, Ray's own processes), sampled from /proc.
2. Scaling: the per-recording cost, in-process, of the same 40 recordings (a) as simulated, (b) with camera
   images on an unsubscribed topic, (c) with extra /rosout lines (a subscribed topic). The cost should follow the
   bytes of subscribed topics, not the camera data.

    .venv/bin/python scripts/bench_triage.py [--runs 3] [--dir DIR] [--skip-ray]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from hexar.evals.cases import recording_name, scenarios
from hexar.evals.scenarios.bag import TYPESTORE
from hexar.evals.scenarios.suite import record, simulate_suite

HEXAR = str(Path(sys.executable).with_name("hexar"))
N = 1000
IMAGE_BYTES = 640 * 480 * 3
IMAGES = 40  # 37 MB of camera per recording
EXTRA_LOGS = 20_000  # about 2 MB of /rosout per recording
T = TYPESTORE.types


def make_fleet(base: Path) -> Path:
    fleet = base / "fleet"
    if fleet.is_dir() and sum(1 for _ in fleet.glob("*/bagfile_*")) == N:
        return fleet
    seeds = -(-N // 60)
    for seed in range(seeds):
        robot = fleet / f"robot-{seed:02d}"
        if not (robot.is_dir() and sum(1 for _ in robot.iterdir()) == 60):  # kept from an interrupted run
            simulate_suite(robot, "sqlite3", seed)
    extra = sorted((fleet / f"robot-{seeds - 1:02d}").iterdir())[: seeds * 60 - N]
    for rec in extra:
        shutil.rmtree(rec)
    return fleet


def tree_rss_mb(pid: int) -> float:
    """Resident memory of a process and all its descendants."""
    total, stack = 0, [pid]
    while stack:
        p = stack.pop()
        try:
            with open(f"/proc/{p}/status") as f:
                total += next((int(line.split()[1]) for line in f if line.startswith("VmRSS")), 0)
            with open(f"/proc/{p}/task/{p}/children") as f:
                stack += [int(c) for c in f.read().split()]
        except (FileNotFoundError, ProcessLookupError):
            continue
    return total / 1024


def run_triage(fleet: Path, out: Path, extra: list[str]) -> dict[str, float]:
    shutil.rmtree(out, ignore_errors=True)
    start = time.perf_counter()
    proc = subprocess.Popen([HEXAR, "triage", str(fleet), "--out", str(out), "--no-figures", *extra],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    peak = 0.0
    while proc.poll() is None:
        peak = max(peak, tree_rss_mb(proc.pid))
        time.sleep(0.2)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        raise SystemExit(f"triage failed: {proc.stderr.read().decode() if proc.stderr else ''}")
    done = len((out / "results.jsonl").read_text().splitlines())
    return {"wall_s": wall, "recordings_per_s": done / wall, "peak_rss_mb": peak}


def throughput(fleet: Path, base: Path, runs: int, ray: bool) -> dict[str, dict[str, float]]:
    configs = {"local, 1 worker": ["--workers", "1"], "local, 2 workers": ["--workers", "2"]}
    if ray:
        configs["Ray local, 2 CPUs"] = ["--ray", "local", "--workers", "2"]
    out: dict[str, dict[str, float]] = {}
    for name, extra in configs.items():
        samples = [run_triage(fleet, base / "out", extra) for _ in range(runs)]
        out[name] = {k: round(statistics.median(s[k] for s in samples), 2) for k in samples[0]}
        print(f"{name:20s} {out[name]}", flush=True)
    return out


def variants(base: Path) -> dict[str, list[Path]]:
    """40 recordings (scenarios 1-20, variants 1-2) as simulated, with camera images, with extra log lines."""
    rng = np.random.default_rng(1)
    image = rng.integers(0, 255, IMAGE_BYTES, dtype=np.uint8)
    out: dict[str, list[Path]] = {"plain": [], "camera": [], "more_rosout": []}
    for s in scenarios():
        for v in (1, 2):
            for kind in out:
                path = base / "scaling" / kind / recording_name(s.id, v)
                out[kind].append(path)
                if path.exists():
                    continue
                b = record(s, v, 0)
                t0, t1 = min(m[0] for m in b.messages), max(m[0] for m in b.messages)
                if kind == "camera":
                    for i in range(IMAGES):
                        t = t0 + (t1 - t0) * i // IMAGES
                        stamp = T["builtin_interfaces/msg/Time"](sec=t // 10**9, nanosec=t % 10**9)
                        img = T["sensor_msgs/msg/Image"](
                            header=T["std_msgs/msg/Header"](stamp=stamp, frame_id="cam"), height=480, width=640,
                            encoding="rgb8", is_bigendian=0, step=640 * 3, data=image)
                        b.raw(t, "/head_front_camera/rgb/image_raw", "sensor_msgs/msg/Image", img)
                elif kind == "more_rosout":
                    for i in range(EXTRA_LOGS):
                        b.log(t0 + (t1 - t0) * i // EXTRA_LOGS, "controller_server", 10,
                              "Control loop missed its desired rate of 20.0000Hz")
                b.write(path)
    return out


SCALE_CHILD = """
import json, statistics, sys, time
from pathlib import Path
from hexar.triage import triage_recording
paths = [Path(p) for p in sys.argv[1:]]
triage_recording(paths[0], "warm")
per = []
for p in paths:
    t = time.perf_counter(); triage_recording(p, p.name); per.append(time.perf_counter() - t)
print(json.dumps(per))
"""


def subscribed_bytes(path: Path) -> tuple[int, int]:
    """Bytes of messages on the topics triage reads, and on all topics (from the sqlite3 storage)."""
    import sqlite3

    from hexar.events.contract import ALL_TOPICS

    db = sqlite3.connect(next(path.glob("*.db3")))
    rows = db.execute("SELECT t.name, SUM(LENGTH(m.data)) FROM messages m JOIN topics t ON m.topic_id = t.id "
                      "GROUP BY t.name").fetchall()
    db.close()
    return sum(n for name, n in rows if name in ALL_TOPICS), sum(n for _, n in rows)


def scaling(base: Path, runs: int) -> dict[str, dict[str, float]]:
    out: dict[str, dict[str, float]] = {}
    for kind, paths in variants(base).items():
        medians = []
        for _ in range(runs):
            done = subprocess.run([sys.executable, "-c", SCALE_CHILD, *map(str, paths)], capture_output=True,
                                  text=True, check=True)
            medians.append(statistics.median(json.loads(done.stdout)))
        sub, total = zip(*(subscribed_bytes(p) for p in paths), strict=True)
        out[kind] = {"ms_per_recording": round(1000 * statistics.median(medians), 1),
                     "subscribed_kb": round(statistics.median(sub) / 1024, 1),
                     "total_mb": round(statistics.median(total) / 2**20, 2)}
        print(f"{kind:12s} {out[kind]}", flush=True)
    return out


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--dir", type=Path, default=None, help="keep the recordings here between runs")
    ap.add_argument("--skip-ray", action="store_true")
    ap.add_argument("--skip-throughput", action="store_true")
    args = ap.parse_args()
    base = args.dir or Path(tempfile.mkdtemp(prefix="hexar-triage-bench-"))
    t = time.perf_counter()
    fleet = make_fleet(base)
    print(f"{N} recordings in {fleet} ({time.perf_counter() - t:.0f} s to simulate); {os.cpu_count()} CPUs; "
          f"load average {os.getloadavg()[0]:.1f}", flush=True)
    result: dict[str, object] = {"recordings": N, "cpus": os.cpu_count(), "runs": args.runs}
    if not args.skip_throughput:
        result["throughput"] = throughput(fleet, base, args.runs, not args.skip_ray)
    result["scaling"] = sc = scaling(base, args.runs)
    ratio_camera = sc["camera"]["ms_per_recording"] / sc["plain"]["ms_per_recording"]
    ratio_logs = sc["more_rosout"]["ms_per_recording"] / sc["plain"]["ms_per_recording"]
    print(f"camera data x{sc['camera']['total_mb'] / sc['plain']['total_mb']:.0f} bytes -> time x{ratio_camera:.2f}; "
          f"subscribed /rosout x{sc['more_rosout']['subscribed_kb'] / sc['plain']['subscribed_kb']:.1f} bytes -> "
          f"time x{ratio_logs:.2f}")
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
