"""What `hexar serve` answers when a dropped robot comes back and its writers resend the hole behind newer messages.

    .venv/bin/python scripts/bench_live_resends.py [--runs 5] [--transport rclpy] [--suite DIR] [--load 3]

A robot (`hexar replay --transport dds`, a Cyclone participant announcing a 2 s lease) replays bagfile_5_1 (a
blocked path) at x5 into a node in this process; a second after its task starts it is stopped (SIGSTOP) for 7 s,
35 s of its clock, so the node's DDS drops it, then it goes on and fails. Three node configurations run
interleaved, `--runs` times each:
- before: no reconnection is known to the live log (`Limits(resend_s=-1)`) and no wait: the code of round 40;
- jump fix: resends after a reconnection are late, never a clock jump (`live/log.py`), no wait;
- both: and a failure that comes as the robot is heard again waits for its resends (`resend_quiet_s=0.5`).
Printed per run and per configuration: whether the first unasked answer gave `hexar ask`'s cause, whether it did
after the node's corrections (up to its last look, 15 s after), the clock jumps the log saw, and the median latency
from the failing `/task_info` to the answer. `--load N` runs N busy loops beside, as a loaded machine.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from hexar.live.limits import Limits  # noqa: E402
from tests.live.dds_helpers import Listener, fresh_domain, live_node  # noqa: E402
from tests.live.test_contact import robot_dropped_mid_task  # noqa: E402
from tests.live.test_replay_explains import expected  # noqa: E402

CONFIGS = {"before": (Limits(resend_s=-1.0), 0.0), "jump fix": (Limits(), 0.0), "both": (Limits(), 0.5)}


def one(run: Path, transport: str, limits: Limits, quiet: float, want: dict[str, list[str]]) -> dict[str, object]:
    domain = fresh_domain()
    listener = Listener(domain)
    try:
        with live_node(domain, limits=limits, transport=transport, resend_quiet_s=quiet) as node:
            robot, _ = robot_dropped_mid_task(node, run, domain)
            robot.communicate(timeout=120)
            listener.wait_answers(len(want), "failure", timeout=15)
            time.sleep(16.5)  # the node's last look comes 15 s after its answer
            answers, corrections = listener.answers("failure"), listener.answers("correction")
            jumps = node.log.stats()["clock_jumps"]
    finally:
        listener.close()
    first = {a["task_id"]: a["causes"] for _, a in answers}
    final = {**first, **{a["task_id"]: a["causes"] for _, a in corrections}}
    return {"first_right": first == want, "right_after": final == want, "corrections": len(corrections),
            "clock_jumps": jumps, "latency_ms": answers[0][1].get("latency_ms") if answers else None}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--transport", choices=("rclpy", "dds"), default="rclpy")
    ap.add_argument("--suite", type=Path, help="folder of `hexar simulate` recordings (default: simulated now)")
    ap.add_argument("--load", type=int, default=0, help="busy loops to run beside")
    args = ap.parse_args()
    suite = args.suite
    if suite is None:
        from hexar.evals.scenarios.suite import simulate_suite

        suite = Path(tempfile.mkdtemp()) / "suite"
        simulate_suite(suite, only=lambda s, v: (s, v) == (5, 1))
    run = suite / "bagfile_5_1"
    want, _ = expected(run)
    hogs = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(args.load)]
    rows: list[tuple[str, dict[str, object]]] = []
    try:
        for _ in range(args.runs):
            for name, (limits, quiet) in CONFIGS.items():
                row = one(run, args.transport, limits, quiet, want)
                rows.append((name, row))
                print(json.dumps({"config": name, **row}), flush=True)
    finally:
        for hog in hogs:
            hog.kill()
    for name in CONFIGS:
        got = [r for n, r in rows if n == name]
        lat = [float(str(r["latency_ms"])) for r in got if r["latency_ms"] is not None]
        print(f"{name}: first answer right {sum(bool(r['first_right']) for r in got)}/{len(got)}, right after "
              f"corrections {sum(bool(r['right_after']) for r in got)}/{len(got)}, runs with a clock jump "
              f"{sum(bool(r['clock_jumps']) for r in got)}, median latency "
              f"{statistics.median(lat) if lat else float('nan'):.0f} ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
