"""What `hexar serve` says after the link to the robot dropped for a while: two network namespaces joined by a
virtual Ethernet link (the robot's computer and the user's), the link cut in the middle of a task.

    sudo .venv/bin/python scripts/bench_live_outage.py [--cuts 5 15 40] [--nodes rclpy dds] [--robots rclpy dds]
        [--run bagfile_5_1] [--rate 2] [--repeat 1] [--baseline PYTHON]

For each node transport x robot vendor x cut length, a robot (HEXAR's replayer, on rclpy/Fast DDS or Cyclone)
replays a failing simulated recording in namespace `hexar_robot`; `hexar serve` and a listener run in
`hexar_home`. Five seconds before the failure the link drops every packet (nftables on the robot's side) for the
cut's length, then carries them again. The vendors' default leases are kept (Cyclone DDS 10 s, Fast DDS 20 s):
a shorter cut is resent by DDS's reliability, a longer one drops the robot's participant and what it published
meanwhile on volatile topics. Printed per configuration: whether the failure was explained unasked with `hexar
ask`'s causes, the answer to a question 10 s after the link is back, and whether it tells of the hole. Needs root,
`ip` (iproute2) and `nft` (nftables); Fast DDS is kept to UDP, as between two computers.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

ROBOT_NS, HOME_NS = "hexar_robot", "hexar_home"
QUESTION = "Why did you fail?"
CUT = """table inet hexar_cut {
  chain out { type filter hook output priority 0; oifname "hx0" drop; }
  chain in { type filter hook input priority 0; iifname "hx0" drop; }
}"""


def sh(*cmd: str) -> None:
    subprocess.run(cmd, check=True, capture_output=True, text=True)


def make_link() -> None:
    drop_link()
    sh("ip", "netns", "add", ROBOT_NS)
    sh("ip", "netns", "add", HOME_NS)
    sh("ip", "link", "add", "hx0", "netns", ROBOT_NS, "type", "veth", "peer", "name", "hx1", "netns", HOME_NS)
    for ns, dev, addr in ((ROBOT_NS, "hx0", "10.77.0.1/24"), (HOME_NS, "hx1", "10.77.0.2/24")):
        sh("ip", "-n", ns, "addr", "add", addr, "dev", dev)
        sh("ip", "-n", ns, "link", "set", "lo", "up")
        sh("ip", "-n", ns, "link", "set", dev, "up", "multicast", "on")
        sh("ip", "-n", ns, "route", "add", "224.0.0.0/4", "dev", dev)  # DDS discovery's multicast


def drop_link() -> None:
    for ns in (ROBOT_NS, HOME_NS):
        subprocess.run(["ip", "netns", "del", ns], capture_output=True)


def cut(on: bool) -> None:
    if on:
        subprocess.run(["ip", "netns", "exec", ROBOT_NS, "nft", "-f", "-"], input=CUT, check=True, text=True)
    else:
        sh("ip", "netns", "exec", ROBOT_NS, "nft", "delete", "table", "inet", "hexar_cut")


def robot_role(vendor: str, domain: int, run: Path, rate: float, linger: float) -> None:
    from hexar.live.replay import replay
    from tests.live.dds_helpers import make_replayer

    writer = make_replayer(vendor, domain)
    replay(run, writer, rate=rate, warmup_s=30.0)
    time.sleep(linger)  # a robot keeps its participant: it comes back under the same GUID
    writer.close()


def home_role(node: str, domain: int, ask_at: float, until: float, python: str) -> None:
    """`hexar serve` and a listener; asks QUESTION at `ask_at` (seconds from now); prints the answers as JSON."""
    from live_common import Listener, start_serve

    serve = start_serve(domain, transport=node, python=python)
    listener = Listener(domain)
    t0 = time.monotonic()
    time.sleep(max(0.0, ask_at - (time.monotonic() - t0)))
    listener.ask(QUESTION)
    time.sleep(max(0.0, until - (time.monotonic() - t0)))
    listener.close()
    serve.send_signal(signal.SIGTERM)
    _, err = serve.communicate(timeout=60)
    for _, answer in listener.answers():
        print(json.dumps(answer), flush=True)
    print(json.dumps({"stderr": err[-2000:]}), flush=True)


def one(node: str, vendor: str, seconds: float, run: Path, rate: float, python: str) -> dict[str, object]:
    from hexar.events.reader import read_recording
    from tests.live.dds_helpers import fresh_domain
    from tests.live.test_replay_explains import expected

    failures, _ = expected(run)
    log = read_recording(run)
    failed = next(t for t in log.tasks if t.outcome == "failed")
    fail_s = (failed.last_update - log.start) / 1e9 / rate  # when the failure comes, from the replay's start
    length = (log.end - log.start) / 1e9 / rate
    domain = fresh_domain() + 20
    make_link()
    env = {**os.environ, "FASTDDS_BUILTIN_TRANSPORTS": "UDPv4", "ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET"}
    env.pop("CYCLONEDDS_URI", None)
    cut_at = max(1.0, fail_s - 5.0)
    back_at = cut_at + seconds
    ask_at = max(back_at, length) + 10.0 + 4.0  # the home side starts about 4 s before the robot
    me = [sys.executable, str(Path(__file__).resolve())]
    home = subprocess.Popen(["ip", "netns", "exec", HOME_NS, *me, "--role", "home", "--node", node, "--domain",
                             str(domain), "--ask-at", str(ask_at), "--until", str(ask_at + 8.0), "--python", python],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            cwd=tempfile.gettempdir())
    time.sleep(4.0)
    robot = subprocess.Popen(["ip", "netns", "exec", ROBOT_NS, *me, "--role", "robot", "--vendor", vendor,
                              "--domain", str(domain), "--run", str(run), "--rate", str(rate), "--linger",
                              str(ask_at + 10.0)], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             text=True, cwd=tempfile.gettempdir())
    try:
        # the replayer waits for its readers before its first message; the cut is timed from the replay's start
        time.sleep(cut_at + 1.0)
        cut(True)
        time.sleep(seconds)
        cut(False)
        out, _ = home.communicate(timeout=ask_at + 120)
    finally:
        robot.send_signal(signal.SIGTERM)
        robot.wait(timeout=30)
        drop_link()
    rows = [json.loads(line) for line in out.splitlines() if line.startswith("{")]
    answers = [r for r in rows if "trigger" in r]
    err = next((str(r["stderr"]) for r in rows if "stderr" in r), "")
    unasked = [a for a in answers if a.get("trigger") in {"failure", "correction"}]
    asked = [a for a in answers if a.get("trigger") == "question"]
    told = {a.get("task_id"): a.get("causes") for a in unasked}  # a correction replaces the first answer
    if not asked:  # the question went unanswered: what the node said is the only clue
        print(f"{node}/{vendor} {seconds:.0f}s: no answer to the question; hexar serve's stderr:\n{err}",
              file=sys.stderr, flush=True)
    return {"explained": told == failures, "asked": asked[-1] if asked else None,
            "lost": err.count("lost contact with"), "back": err.count(" again, ")}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--role", choices=["robot", "home"])
    ap.add_argument("--node", default="dds")
    ap.add_argument("--vendor", default="dds")
    ap.add_argument("--domain", type=int, default=0)
    ap.add_argument("--run", type=Path)
    ap.add_argument("--rate", type=float, default=2.0)
    ap.add_argument("--linger", type=float, default=60.0)
    ap.add_argument("--ask-at", type=float, default=0.0)
    ap.add_argument("--until", type=float, default=0.0)
    ap.add_argument("--python", default=sys.executable)
    ap.add_argument("--cuts", nargs="*", type=float, default=[5.0, 15.0, 40.0])
    ap.add_argument("--nodes", nargs="*", default=["rclpy", "dds"], choices=["rclpy", "dds"])
    ap.add_argument("--robots", nargs="*", default=["rclpy", "dds"], choices=["rclpy", "dds"])
    ap.add_argument("--suite", type=Path, help="folder of `hexar simulate` recordings (default: simulated now)")
    ap.add_argument("--recording", default="bagfile_5_1")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--baseline", metavar="PYTHON", help="also run another install's `hexar serve`")
    args = ap.parse_args()
    if args.role == "robot":
        robot_role(args.vendor, args.domain, args.run, args.rate, args.linger)
        return
    if args.role == "home":
        home_role(args.node, args.domain, args.ask_at, args.until, args.python)
        return
    missing = [tool for tool in ("ip", "nft") if shutil.which(tool) is None]
    if missing or os.geteuid() != 0:
        raise SystemExit(f"ERROR: needs root and {', '.join(missing) or 'ip, nft'} (Debian: iproute2, nftables)")
    suite = args.suite
    if suite is None:
        from hexar.evals.scenarios.suite import simulate_suite

        suite = Path(tempfile.mkdtemp()) / "suite"
        simulate_suite(suite)
    versions = {"head": sys.executable, **({"base": args.baseline} if args.baseline else {})}
    print(f"{'code':5} {'node':6} {'robot':6} {'cut':>5}  unasked  lost back  question's answer", flush=True)
    for seconds in args.cuts:
        for node in args.nodes:
            for vendor in args.robots:
                for _ in range(args.repeat):
                    for code, python in versions.items():
                        got = one(node, vendor, seconds, suite / args.recording, args.rate, python)
                        asked = got["asked"]
                        said = "(no answer)" if not isinstance(asked, dict) else \
                            f"{asked.get('causes')} {str(asked.get('answer', ''))[:160]}"
                        right = "right" if got["explained"] else "no"
                        print(f"{code:5} {node:6} {vendor:6} {seconds:4.0f}s  {right:7} {got['lost']:4} "
                              f"{got['back']:4}  {said}", flush=True)


if __name__ == "__main__":
    main()
