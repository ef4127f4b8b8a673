"""Benchmark: the page opens a one-hour recording.

Writes a one-hour rosbag2 recording (200k /rosout lines, /amcl_pose at 5 Hz with its covariance, 1 Hz flags,
one navigation task that runs for the hour and fails at its end, like scripts/bench_events.py's recording plus
a task), starts the page's server in this process, reads the event log once, then loads the run's page N times.
Each load starts from a cold findings cache (the explainers run again) with the decoded event log kept, which
is the issue's "after the event log is read". Target (issue): under 2 s.

Reported, medians of N loads:
- http: GET /api/run (explainers + run data, including the thinned path the page draws); apart from it,
  GET /api/plot.png (the matplotlib figure, which the page only links to);
- browser: a fresh page load in headless Chromium until the timeline, the findings and the path are drawn
  (performance.now() at that moment); skipped when chromium/chromedriver are not installed.

    .venv/bin/python scripts/bench_web.py [--runs 5] [--dir DIR]
"""

from __future__ import annotations

import argparse
import json
import math
import random
import shutil
import statistics
import sys
import tempfile
import threading
import time
import urllib.request
from pathlib import Path

import numpy as np
from rosbags.rosbag2 import StoragePlugin, Writer

from hexar.evals.scenarios.bag import TYPESTORE, sec_ns
from hexar.events import contract as c

T = TYPESTORE.types
HOUR_S = 3600
LOG_LINES = 200_000
LOGGERS = ["controller_server", "planner_server", "bt_navigator", "amcl", "behavior_server"]
MESSAGES = ["Passing new path to controller.", "Received a goal, begin computing control effort.",
            "Control loop missed its desired rate of 20.0000Hz", "Reached the goal!", "Goal succeeded",
            "Begin navigating from current location (0.00, 0.00) to (4.20, 2.10)"]
NAME = "hour_task"


def _stamp(t: int) -> object:
    return T["builtin_interfaces/msg/Time"](sec=t // 1_000_000_000, nanosec=t % 1_000_000_000)


def _task(status: str, error: str = "") -> str:
    return json.dumps({"instruction": "Patrol to the kitchen", "task_id": "hour01", "task_status": "valid",
                       "task_error_msg": "", "skill_sequence": [
                           {"skill": "navigate_to_zone", "params": {"zone": "kitchen"}, "status": status,
                            "error_msg": error}]})


def write(path: Path) -> None:
    rng = random.Random(1)
    t0 = sec_ns(1_741_600_800)
    end = t0 + HOUR_S * 1_000_000_000
    events: list[tuple[int, object, bytes]] = []
    with Writer(path, version=9, storage_plugin=StoragePlugin.SQLITE3) as w:
        log = w.add_connection(c.ROSOUT, c.LOG_TYPE, typestore=TYPESTORE)
        pose = w.add_connection(c.AMCL_POSE, c.POSE_COV_TYPE, typestore=TYPESTORE)
        task = w.add_connection(c.TASK_INFO, c.STRING_TYPE, typestore=TYPESTORE)
        flags = [w.add_connection(topic, c.BOOL_TYPE, typestore=TYPESTORE) for topic in (c.JOY_PRIORITY,
                                                                                          c.IS_CHARGING)]

        def log_line(t: int, name: str, level: int, msg: str) -> None:
            m = T[c.LOG_TYPE](stamp=_stamp(t), level=level, name=name, msg=msg, file="src.cpp", function="f", line=1)
            events.append((t, log, TYPESTORE.serialize_cdr(m, c.LOG_TYPE)))

        for i in range(LOG_LINES):
            log_line(t0 + i * (HOUR_S * 1_000_000_000 // LOG_LINES), rng.choice(LOGGERS), 20, rng.choice(MESSAGES))
        for t, level, name, msg in ((end - sec_ns(30), 40, "controller_server", "Failed to make progress"),
                                    (end - sec_ns(29), 30, "planner_server",
                                     "GridBased: failed to create plan with tolerance 0.50."),
                                    (end - sec_ns(2), 40, "bt_navigator", "Goal failed")):
            log_line(t, name, level, msg)
        for i in range(HOUR_S * 5):
            t = t0 + i * 200_000_000
            a = 2 * math.pi * i / (HOUR_S * 5) * 6  # six laps of a room
            cov = np.zeros(36, dtype=np.float64)
            cov[0] = cov[7] = 0.02 + 0.3 * max(0.0, math.sin(a / 3)) ** 8
            cov[35] = 0.01
            p = T["geometry_msgs/msg/Pose"](position=T["geometry_msgs/msg/Point"](x=3 * math.cos(a), y=2 * math.sin(a),
                                                                                  z=0.0),
                                            orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))
            m = T[c.POSE_COV_TYPE](header=T["std_msgs/msg/Header"](stamp=_stamp(t), frame_id="map"),
                                   pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=p, covariance=cov))
            events.append((t, pose, TYPESTORE.serialize_cdr(m, c.POSE_COV_TYPE)))
        for i in range(HOUR_S):
            for conn in flags:
                events.append((t0 + i * 1_000_000_000, conn,
                               TYPESTORE.serialize_cdr(T[c.BOOL_TYPE](data=False), c.BOOL_TYPE)))
        for t, payload in ((t0, _task("waiting")), (t0 + sec_ns(1), _task("Running")),
                           (end - sec_ns(1), _task("failed", "Navigation to kitchen failed"))):
            events.append((t, task, TYPESTORE.serialize_cdr(T[c.STRING_TYPE](data=payload), c.STRING_TYPE)))
        for t, conn, raw in sorted(events, key=lambda e: e[0]):
            w.write(conn, t, raw)  # type: ignore[arg-type]


def _get(url: str) -> bytes:
    with urllib.request.urlopen(url, timeout=120) as r:
        return bytes(r.read())


def browser_loads(url: str, runs: int, reset: object) -> list[float] | None:
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from tests.web.browser import chrome, chromium_paths

    if chromium_paths() is None:
        return None
    from selenium.webdriver.support.ui import WebDriverWait

    ready = ("return document.body.dataset.ready && document.getElementById('path-line') ? performance.now() "
             ": null")
    samples = []
    with chrome() as driver:
        for i in range(runs):
            reset()  # type: ignore[operator]
            driver.get(f"{url}?load={i}#/run/{NAME}")
            samples.append(WebDriverWait(driver, 120, poll_frequency=0.02).until(
                lambda d: d.execute_script(ready)) / 1000)
    return samples


def main() -> int:
    from hexar.web.pagedata import Findings
    from hexar.web.server import make_server
    from hexar.web.store import Store

    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--dir", type=Path, default=None)
    args = ap.parse_args()
    root = args.dir or Path(tempfile.mkdtemp(prefix="hexar-bench-web-"))
    bag = root / NAME
    if not bag.exists():
        t = time.perf_counter()
        write(bag)
        print(f"wrote the one-hour recording in {time.perf_counter() - t:.0f} s", file=sys.stderr)
    store = Store(root, "none", root / "threads.sqlite")
    t = time.perf_counter()
    log = store.log(NAME)
    read_s = time.perf_counter() - t
    server = make_server(store, "127.0.0.1", 0)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = f"http://127.0.0.1:{server.server_address[1]}/"

    def reset() -> None:
        store.findings = Findings()

    http, png = [], []
    for _ in range(args.runs):
        reset()
        t = time.perf_counter()
        run = json.loads(_get(f"{url}api/run?name={NAME}"))
        http.append(time.perf_counter() - t)
        t = time.perf_counter()
        _get(f"{url}api/plot.png?name={NAME}")
        png.append(time.perf_counter() - t)
    browser = browser_loads(url, args.runs, reset)
    server.shutdown()
    result = {"runs": args.runs, "log_lines": len(log.logs), "poses": len(log.poses), "event_log_read_s": read_s,
              "http_load_s": statistics.median(http), "http_samples_s": http, "png_figure_s": statistics.median(png),
              "browser_load_s": statistics.median(browser) if browser else None, "browser_samples_s": browser,
              "causes": [c for f in run["findings"] for c in f["causes"]], "target_s": 2.0}
    print(f"one-hour recording: {len(log.logs):,} /rosout lines, {len(log.poses):,} poses; "
          f"event log read once in {read_s:.2f} s")
    print(f"page data over HTTP, explainers included (median of {args.runs}): {result['http_load_s']:.2f} s; "
          f"the PNG figure (on request) {result['png_figure_s']:.2f} s")
    if browser:
        print(f"page load in headless Chromium until timeline, findings and path are drawn (median of {args.runs}): "
              f"{result['browser_load_s']:.2f} s (target < 2 s)")
    else:
        print("headless Chromium not installed: browser load not measured")
    print(json.dumps(result))
    if args.dir is None:
        shutil.rmtree(root, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
