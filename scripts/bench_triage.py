"""Benchmark: `hexar triage` throughput on the simulated fleet, and what its per-recording cost scales with.

1. Throughput: `hexar triage` in a fresh process on the 60 recordings of `hexar simulate` (seed 0) and on 1,000
   (17 simulator seeds of the 60 scenarios, cut to 1,000), locally with 1 and 2 workers (and on a local Ray
   instance unless --skip-ray). Per configuration, the median of --runs of: recordings/s of wall time (start-up
   included), recordings per CPU-second of the whole process tree (driver and workers: what one core does, so
   it holds on a shared machine where wall time does not), and peak memory of the process tree, from /proc.
   The marginal rate, (1,000 - 60) recordings over the difference of the two fleets' wall times, is the
   per-recording throughput without the fixed start-up (interpreter, imports, report). `--baseline HEXAR`
   runs another `hexar` (the code before a change, installed elsewhere) on the same recordings in the same run
   and prints the ratios. The read-only floor: reading every message of the same recordings from their storage.
   The runs are interleaved (floor, then every configuration and code, then again), and each figure is printed
   with the machine's load average before and after it and the cores other processes kept busy meanwhile (from
   /proc/stat, less this run's own CPU): on shared cores, compare figures taken while others used little.
   Every run must write the same tasks table and report per fleet: the first run's, or --expect DIR's (the code
   before a change); --baseline's runs are checked the same way. `--no-pizza` adds the 60 less the 3 recordings
   whose findings are LIME's answers, to show the fixed cost of importing scikit-learn and LIME. The medians are
   printed against the targets of issue 25 (55 recordings/s with one worker, 2 workers 1.7x one).
2. Scaling: the per-recording cost, in-process, of the same 40 recordings (a) as simulated, (b) with camera
   images on an unsubscribed topic, (c) with extra /rosout lines (a subscribed topic). The cost should follow the
   bytes of subscribed topics, not the camera data.

    .venv/bin/python scripts/bench_triage.py [--runs 3] [--dir DIR] [--skip-ray] [--baseline OLD/bin/hexar]
        [--wait-quiet 0.2] [--no-pizza] [--expect DIR]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import sqlite3
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
TARGET_PER_CORE = 55  # recordings/s with one worker (issue 25)
TARGET_SCALING = 1.7  # 2 workers over 1
PIZZA = "bagfile_20_"  # the 3 of the 60 whose findings are LIME's answers: the scikit-learn/LIME import
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


def without_pizza(fleet: Path, out: Path) -> Path:
    """The 60 less the 3 pizza recommendations: what the same fleet costs without importing scikit-learn and LIME."""
    for rec in sorted(fleet.iterdir()):
        if not rec.name.startswith(PIZZA) and not (out / rec.name).is_dir():
            shutil.copytree(rec, out / rec.name)
    return out


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


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _own_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def load_average() -> float:
    """The machine's 1-minute load average, printed beside every figure: the cores are shared."""
    return round(os.getloadavg()[0], 2)


def busy_cpu_s() -> float:
    """CPU-seconds the whole machine has been busy since boot (every process, not only ours), from /proc/stat."""
    with open("/proc/stat") as f:
        fields = [int(v) for v in f.readline().split()[1:9]]
    user, nice, system, _idle, _iowait, irq, softirq, steal = fields
    return (user + nice + system + irq + softirq + steal) / os.sysconf("SC_CLK_TCK")


def wait_quiet(cores: float | None, limit_s: float = 300) -> None:
    """On a shared machine: wait (up to `limit_s`) until other processes keep fewer than `cores` cores busy over a
    second, so that a 2-worker run finds two cores free."""
    deadline = time.monotonic() + limit_s
    while cores is not None and time.monotonic() < deadline:
        busy0 = busy_cpu_s()
        time.sleep(1.0)
        if busy_cpu_s() - busy0 < cores:
            return


def run_triage(hexar: str, fleet: Path, out: Path, extra: list[str], quiet: float | None = None) -> dict[str, float]:
    """One `hexar triage` in a fresh process. The CPU time covers the process and every worker it waited for
    (Ray's own daemons are not its children: a Ray run's CPU time counts the driver only)."""
    shutil.rmtree(out, ignore_errors=True)
    wait_quiet(quiet)
    load = load_average()
    cpu0, own0, busy0, start = _children_cpu(), _own_cpu(), busy_cpu_s(), time.perf_counter()
    proc = subprocess.Popen([hexar, "triage", str(fleet), "--out", str(out), "--no-figures", *extra],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    peak = 0.0
    while proc.poll() is None:
        peak = max(peak, tree_rss_mb(proc.pid))
        time.sleep(0.05)
    wall, cpu = time.perf_counter() - start, _children_cpu() - cpu0
    # the load average lags, and counts this run too; this is what everything else took meanwhile
    others = max(0.0, busy_cpu_s() - busy0 - cpu - (_own_cpu() - own0)) / wall
    if proc.returncode != 0:
        raise SystemExit(f"triage failed: {proc.stderr.read().decode() if proc.stderr else ''}")
    done = len((out / "results.jsonl").read_text().splitlines())
    return {"wall_s": wall, "recordings_per_s": done / wall, "per_cpu_s": done / cpu, "peak_rss_mb": peak,
            "load_before": load, "load_after": load_average(), "other_cores": others}


def same_results(out: Path, fleet_name: str, key: str, expected: dict[str, str]) -> None:
    """Every configuration, and the code before a change, writes the same tasks table (and report) as the first
    run of this fleet, or as `--expect DIR/<fleet>/` when given: a faster triage that answers otherwise is no
    faster triage. A difference ends the benchmark."""
    for name in ("tasks.jsonl", "report.md"):
        got = (out / name).read_text(encoding="utf-8")
        want = expected.setdefault(f"{fleet_name}/{name}", got)
        if got != want:
            raise SystemExit(f"{key}: {name} differs from the expected one ({len(got.splitlines())} lines, "
                             f"{len(want.splitlines())} expected)")


def read_floor(fleet: Path) -> float:
    """Recordings/s of reading every message of every recording from its sqlite3 storage, nothing decoded."""
    files = sorted(fleet.rglob("*.db3"))
    start = time.perf_counter()
    for file in files:
        db = sqlite3.connect(f"file:{file}?mode=ro", uri=True)
        for _row in db.execute("SELECT topic_id, timestamp, data FROM messages"):
            pass
        db.close()
    return len(files) / (time.perf_counter() - start)


def uptime() -> str:
    return subprocess.run(["uptime"], capture_output=True, text=True, check=False).stdout.strip()


def throughput(fleets: dict[str, Path], base: Path, runs: int, ray: bool, baseline: str | None,
               quiet: float | None = None, expected: dict[str, str] | None = None) -> dict[str, dict[str, float]]:
    configs = {"1 worker": ["--workers", "1"], "2 workers": ["--workers", "2"]}
    if ray:
        configs["Ray local, 2 CPUs"] = ["--ray", "local", "--workers", "2"]
    codes = {"new": HEXAR, **({"old": baseline} if baseline else {})}
    samples: dict[str, list[dict[str, float]]] = {}
    expected = {} if expected is None else expected
    for run in range(runs):
        print(f"run {run + 1}: {uptime()}", flush=True)
        # interleaved, so that a change of load on a shared machine hits every configuration and code alike
        for fleet_name, fleet in fleets.items():
            wait_quiet(quiet)
            load = load_average()
            floor = {"recordings_per_s": read_floor(fleet), "load_before": load, "load_after": load_average()}
            samples.setdefault(f"{fleet_name}, read-only floor", []).append(floor)
            print(f"run {run + 1}: {fleet_name + ', read-only floor':30s} {floor['recordings_per_s']:7.1f} "
                  f"recordings/s (load {load:.2f} -> {floor['load_after']:.2f})", flush=True)
            for name, extra in configs.items():
                for code, hexar in codes.items():
                    key = f"{fleet_name}, {name}, {code}"
                    sample = run_triage(hexar, fleet, base / "out", extra, quiet)
                    same_results(base / "out", fleet_name, key, expected)
                    samples.setdefault(key, []).append(sample)
                    print(f"run {run + 1}: {key:30s} {sample['recordings_per_s']:7.1f} recordings/s "
                          f"(load {sample['load_before']:.2f} -> {sample['load_after']:.2f}, getloadavg "
                          f"{os.getloadavg()}; other processes used {sample['other_cores']:.2f} cores meanwhile)",
                          flush=True)
    print(f"results: every run of every configuration{' and code' if baseline else ''} wrote the same tasks "
          f"table and report per fleet ({len(expected) // 2} fleets checked)", flush=True)
    out: dict[str, dict[str, float]] = {}
    for key, rows in samples.items():
        out[key] = {k: round(statistics.median(s[k] for s in rows), 2) for k in rows[0]}
        print(f"median {key:30s} {out[key]}", flush=True)
    return out


def summarise(result: dict[str, dict[str, float]], sizes: dict[str, int], baseline: bool) -> dict[str, float]:
    """Scaling with workers, the marginal rate without start-up, and the ratios to the baseline."""
    small, large = list(sizes)[:2]
    codes = ["new", "old"] if baseline else ["new"]
    lines: dict[str, float] = {}
    for code in codes:
        for workers in ("1 worker", "2 workers"):
            a, b = result[f"{small}, {workers}, {code}"], result[f"{large}, {workers}, {code}"]
            lines[f"marginal {workers}, {code}"] = round((sizes[large] - sizes[small]) / (b["wall_s"] - a["wall_s"]), 1)
        for fleet in (small, large):
            one, two = result[f"{fleet}, 1 worker, {code}"], result[f"{fleet}, 2 workers, {code}"]
            lines[f"2 workers / 1, {fleet}, {code}"] = round(two["recordings_per_s"] / one["recordings_per_s"], 2)
    if baseline:
        for key, row in result.items():
            if key.endswith(", new") and key[:-5] + ", old" in result:
                old = result[key[:-5] + ", old"]
                lines[f"new/old {key[:-5]}, wall"] = round(row["recordings_per_s"] / old["recordings_per_s"], 2)
                lines[f"new/old {key[:-5]}, CPU"] = round(row["per_cpu_s"] / old["per_cpu_s"], 2)
    for k, v in lines.items():
        print(f"{k:40s} {v}")
    for fleet in sizes:
        one, two = result[f"{fleet}, 1 worker, new"], result[f"{fleet}, 2 workers, new"]
        floor = result[f"{fleet}, read-only floor"]
        print(f"== {fleet} recordings, medians: 1 worker {one['recordings_per_s']:.1f} recordings/s "
              f"({one['per_cpu_s']:.1f} per CPU-second), 2 workers {two['recordings_per_s']:.1f}/s, 2 workers / 1 "
              f"{two['recordings_per_s'] / one['recordings_per_s']:.2f}; read-only floor "
              f"{floor['recordings_per_s']:.0f}/s; load average {one['load_before']:.2f} / {two['load_before']:.2f}"
              f" / {floor['load_before']:.2f} before each; other processes used {one['other_cores']:.2f} / "
              f"{two['other_cores']:.2f} cores during the 1- and 2-worker runs")
        ratio = two["recordings_per_s"] / one["recordings_per_s"]
        print(f"   target (issue 25) {fleet}: 1 worker >= {TARGET_PER_CORE}/s: "
              f"{'PASS' if one['recordings_per_s'] >= TARGET_PER_CORE else 'FAIL'} ({one['recordings_per_s']:.1f}); "
              f"2 workers / 1 >= {TARGET_SCALING}: {'PASS' if ratio >= TARGET_SCALING else 'FAIL'} ({ratio:.2f})")
    return lines


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
from hexar.fleet.work import triage_recording
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
    ap.add_argument("--skip-scaling", action="store_true")
    ap.add_argument("--baseline", default=None, help="another hexar executable to compare with, in the same run")
    ap.add_argument("--no-pizza", action="store_true",
                    help="also the 60 less the 3 recordings whose findings need LIME (the fixed cost of its import)")
    ap.add_argument("--expect", type=Path, default=None, metavar="DIR",
                    help="DIR/<fleet>/tasks.jsonl and report.md that every run must write (e.g. from the code "
                         "before a change); default: the first run's")
    ap.add_argument("--wait-quiet", type=float, default=None, metavar="CORES",
                    help="before each run, wait (up to 5 minutes) until other processes use fewer than CORES cores")
    args = ap.parse_args()
    base = args.dir or Path(tempfile.mkdtemp(prefix="hexar-triage-bench-"))
    t = time.perf_counter()
    fleet = make_fleet(base)
    print(f"{N} recordings in {fleet} ({time.perf_counter() - t:.0f} s to simulate); {os.cpu_count()} CPUs; "
          f"{uptime()}", flush=True)
    fleets = {"60": fleet / "robot-00", str(N): fleet}  # robot-00 is `hexar simulate --seed 0`
    if args.no_pizza:
        fleets["57, no pizza"] = without_pizza(fleet / "robot-00", base / "no-pizza")
    result: dict[str, object] = {"recordings": N, "cpus": os.cpu_count(), "runs": args.runs}
    if not args.skip_throughput:
        expected = {f"{name}/{f}": (args.expect / name / f).read_text(encoding="utf-8")
                    for name in fleets for f in ("tasks.jsonl", "report.md")
                    if args.expect and (args.expect / name / f).is_file()}
        if args.expect:
            print(f"expected results: {len(expected)} files from {args.expect}", flush=True)
        tp = throughput(fleets, base, args.runs, not args.skip_ray, args.baseline, args.wait_quiet, expected)
        result["throughput"] = tp
        result["summary"] = summarise(tp, {name: len(list(path.rglob("metadata.yaml")))
                                           for name, path in fleets.items()}, args.baseline is not None)
    if not args.skip_scaling:
        result["scaling"] = sc = scaling(base, args.runs)
        ratio_camera = sc["camera"]["ms_per_recording"] / sc["plain"]["ms_per_recording"]
        ratio_logs = sc["more_rosout"]["ms_per_recording"] / sc["plain"]["ms_per_recording"]
        more = sc["more_rosout"]["subscribed_kb"] / sc["plain"]["subscribed_kb"]
        print(f"camera data x{sc['camera']['total_mb'] / sc['plain']['total_mb']:.0f} bytes -> time "
              f"x{ratio_camera:.2f}; subscribed /rosout x{more:.1f} bytes -> time x{ratio_logs:.2f}")
    print(uptime())
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
