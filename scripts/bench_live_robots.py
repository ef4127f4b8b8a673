"""Acceptance run of `hexar serve` on each transport against stand-in robots on both DDS vendors and clocks.

    .venv/bin/python scripts/bench_live_robots.py [--suite DIR] [--rate 10] [--runs bagfile_5_1 ... | all]
        [--nodes rclpy dds] [--robots rclpy dds] [--clocks live ...] [--loss PERMILLE | --netloss PERMILLE]
        [--python PYTHON] [--baseline PYTHON]

For each node transport (rclpy/Fast DDS, dds/Cyclone) x robot vendor (rclpy, Cyclone) x robot clock, one
`hexar serve` process hears a stand-in robot replaying failing simulated recordings at `--rate`:
- live: every stamp is the publishing time (a robot running now), source times are now;
- bag-play: the recording's stamps, source times of now (`ros2 bag play` of an old recording);
- bag-play+clock: the same with /clock at 40 Hz (`ros2 bag play --clock`).
Each failure must be explained unasked with the cause `hexar ask` gives on the recording, and a question after
it must get `hexar ask`'s answer. Latency is failing /task_info -> /hexar/answer as a Cyclone listener sees both;
medians and p95 per node transport. The stand-in robots publish through HEXAR's replayer writers (rclpy raw CDR,
or the Cyclone IDL types), restamping the messages themselves.

A lossy network: `--loss 200` makes every Cyclone DDS participant of this run (the Cyclone robot, the listener,
and a node on the dds transport) drop 200 of every 1,000 packets it sends, Cyclone's own fault injection
(Internal/Test/XmitLossiness). Reliable topics are resent, late. "explained" counts the node's first unasked
answers that give `hexar ask`'s causes, "final" the same after the node's corrections (live/recheck.py): the run
waits 6 s after each recording, and at the end until the node's last look (15 s after its last answer) is due.
`--baseline PYTHON` runs another install's `hexar serve` on each configuration too.

`--netloss 200` instead loses the packets in the kernel: the whole run moves into a network namespace of its own
whose loopback link drops 200 of every 1,000 UDP datagrams that any process sends (nftables), whichever DDS vendor
sent them, so a real rclpy/Fast DDS robot is on the lossy link too. Fast DDS is kept to UDP there, as between two
computers (its shared memory would pass the link by). Needs root, `unshare`, `ip` and `nft`.
"""

from __future__ import annotations

import argparse
import os
import signal
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from live_common import Listener, in_lossy_netns, lossy, netns_dropped, percentile, start_serve

from hexar.events import contract as c
from hexar.live.recheck import AFTER_S
from hexar.live.replay import QOS_OF, replay, to_dds
from tests.live.dds_helpers import fresh_domain, make_replayer
from tests.live.test_replay_explains import QUESTION, expected

RUNS = ("bagfile_2_1", "bagfile_5_1", "bagfile_11_1", "bagfile_19_1")  # planner, navigation, ask human, TTS
CLOCKS = ("live", "bag-play", "bag-play+clock")


class StandIn:
    """A robot on `vendor`: restamps (live clock) and writes with today's source time, as a ROS 2 node does."""

    def __init__(self, vendor: str, domain: int, clock: str) -> None:
        self.writer = make_replayer(vendor, domain)
        self.vendor, self.clock_mode = vendor, clock
        self.wants_dds = False

    def prepare(self) -> None:
        self.writer.prepare()

    def matched(self, topic: str) -> int:
        return int(self.writer.matched(topic))

    def clock(self, t: int) -> None:
        if self.vendor == "rclpy":
            self.writer.clock(t)
            return
        from hexar.live import msgs
        from hexar.live.clock import CLOCK, CLOCK_TYPE
        from hexar.live.topics import CLOCK_QOS

        # as `ros2 bag play --clock`: the recording's time inside, the time of writing as source time
        self.writer.endpoint.writer(CLOCK, CLOCK_TYPE, CLOCK_QOS).write(msgs.Clock(clock=msgs.time_of(t)))

    def write(self, topic: str, msgtype: str, msg: Any, t: int) -> None:
        if self.clock_mode == "live":
            _restamp(msg, time.time_ns())
        if self.vendor == "rclpy":
            self.writer.write(topic, msgtype, msg, t)
            return
        # Cyclone: the source timestamp is the time of writing, not the recording's
        self.writer.endpoint.writer(topic, c.TYPE_OF[topic], QOS_OF[topic]).write(to_dds(msgtype, msg))

    def close(self) -> None:
        self.writer.close()


def _restamp(msg: Any, now: int) -> None:
    stamp = msg.stamp if hasattr(msg, "stamp") else getattr(getattr(msg, "header", None), "stamp", None)
    if stamp is not None:
        stamp.sec, stamp.nanosec = now // 1_000_000_000, now % 1_000_000_000


def one_case(suite: Path, runs: list[str], node: str, vendor: str, clock: str,
             rate: float, wait_corrections: float = 0.0, python: str = sys.executable
             ) -> tuple[int, int, int, list[float]]:
    """(failures explained right at once, failures right after the node's corrections, failures in all,
    proactive latencies in s) for one serve process; after each recording the run waits `wait_corrections` s (the
    node's first looks again), and when that is not 0, once more at the end until its last look is due."""
    domain = fresh_domain()
    serve = start_serve(domain, transport=node, python=python)
    listener = Listener(domain)
    # one robot for all the runs, as a robot keeps its writers: a writer deleted right after its last message
    # can take unacknowledged messages with it on a lossy network
    robot = StandIn(vendor, domain, clock)
    good = total = 0
    latencies: list[float] = []
    told: list[tuple[str, dict[str, Any]]] = []  # (recording, first unasked answer) of every failure
    want: dict[str, Any] = {}
    try:
        for name in runs:
            failures, asked = expected(suite / name)
            want.update(failures)
            total += len(failures)
            before = len(listener.answers("failure"))
            replay(suite / name, robot, rate=rate, clock_hz=40.0 if clock.endswith("clock") else 0.0)
            got = listener.wait_answers(before + len(failures), "failure", timeout=10.0)[before:]
            told += [(name, a) for a in got]
            time.sleep(wait_corrections)
            n_q = len(listener.answers("question"))
            listener.ask(QUESTION)
            answer = listener.wait_answers(n_q + 1, "question", timeout=15.0)[n_q:]
            ok_q = bool(answer) and answer[0].get("causes") == asked
            for a in got:
                right = failures.get(a.get("task_id", "")) == a.get("causes")
                good += int(right and ok_q)
                if not right or not ok_q:
                    want_a = failures.get(a.get("task_id", ""))
                    print(f"  {name}: unasked {a.get('causes')} {a.get('error', '')[:80]} (want {want_a}), "
                          f"asked {answer[0].get('causes') if answer else None} (want {asked})\n"
                          f"    said: {a.get('answer', '')[:300]}", flush=True)
            for received, a in listener.answers("failure")[before:]:
                key = next((k for k in listener.heard.failures if k.startswith(a.get("task_id", "") + ":")), None)
                if key is not None:
                    latencies.append(received - listener.heard.failures[key])
        # the node's last look comes 15 s after an answer (live/recheck.py AFTER_S): wait for it once, at the end
        time.sleep(max(AFTER_S) + 1.0 if wait_corrections else 0.0)
        corrected: dict[str, Any] = {}
        for _, a in listener.answers("correction"):
            corrected[a.get("task_id", "")] = a.get("causes")  # the last correction of a failure stands
        final = sum(int(want.get(a.get("task_id", "")) == corrected.get(a.get("task_id", ""), a.get("causes")))
                    for _, a in told)
        for name, a in told:
            task = a.get("task_id", "")
            if task in corrected:
                print(f"  {name}: corrected {a.get('causes')} -> {corrected[task]} (want {want.get(task)})",
                      flush=True)
    finally:
        robot.close()
        listener.close()
        serve.send_signal(signal.SIGTERM)
        _, err = serve.communicate(timeout=60)
        if serve.returncode != 0 or "terminate called" in err:
            print(f"  serve exited {serve.returncode}: {err.strip()[-300:]}", flush=True)
    return good, final, total, latencies


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--suite", type=Path, default=None, help="folder of `hexar simulate` recordings")
    ap.add_argument("--rate", type=float, default=10.0)
    ap.add_argument("--runs", nargs="*", default=list(RUNS), help="recordings of the suite, or `all` with failures")
    ap.add_argument("--nodes", nargs="*", default=["rclpy", "dds"], choices=["rclpy", "dds"])
    ap.add_argument("--robots", nargs="*", default=["rclpy", "dds"], choices=["rclpy", "dds"])
    ap.add_argument("--clocks", nargs="*", default=list(CLOCKS), choices=list(CLOCKS))
    ap.add_argument("--loss", type=int, default=0, metavar="PERMILLE",
                    help="Cyclone DDS drops this many of every 1,000 packets it sends (XmitLossiness)")
    ap.add_argument("--netloss", type=int, default=0, metavar="PERMILLE",
                    help="a network namespace whose link drops this many of every 1,000 UDP datagrams (nftables)")
    ap.add_argument("--python", default=sys.executable, help="the python whose `hexar serve` is measured")
    ap.add_argument("--baseline", metavar="PYTHON", help="also run `hexar serve` of another install (its python), "
                    "each configuration after the code's own")
    args = ap.parse_args()
    if not 0 <= args.loss <= 1000 or not 0 <= args.netloss <= 1000:
        raise SystemExit("ERROR: --loss and --netloss are packets per 1,000, from 0 to 1000")
    if args.netloss:
        in_lossy_netns(args.netloss)
    if args.loss:
        os.environ["CYCLONEDDS_URI"] = lossy(os.environ.get("CYCLONEDDS_URI", ""), args.loss)
    suite = args.suite
    if suite is None:
        from hexar.evals.scenarios.suite import simulate_suite

        suite = Path(tempfile.mkdtemp()) / "suite"
        simulate_suite(suite)
    runs = args.runs
    if runs == ["all"]:
        runs = sorted(p.name for p in suite.iterdir() if p.is_dir() and expected(p)[0])
    versions = {"head": args.python, **({"base": args.baseline} if args.baseline else {})}
    per_node: dict[str, list[float]] = {}
    wait = 6.0 if args.loss or args.netloss else 0.0  # the node's first looks again: 1 s and 4 s after an answer
    print(f"{'code':5} {'node':6} {'robot':6} {'clock':15} explained  final    median   p95", flush=True)
    for node in args.nodes:
        for vendor in args.robots:
            for clock in args.clocks:
                for code, python in versions.items():
                    if wait:  # what one_case prints of a wrong answer comes before its row: say whose it is
                        print(f"-- {code} {node} {vendor} {clock}", flush=True)
                    good, final, total, lat = one_case(suite, runs, node, vendor, clock, args.rate, wait, python)
                    per_node.setdefault(f"{code} {node}", []).extend(lat)
                    med = statistics.median(lat) * 1000 if lat else float("nan")
                    p95 = percentile(lat, 0.95) * 1000 if lat else float("nan")
                    print(f"{code:5} {node:6} {vendor:6} {clock:15} {good:3}/{total:<3}  {final:3}/{total:<3}  "
                          f"{med:6.0f} ms {p95:5.0f} ms", flush=True)
    if dropped := netns_dropped():
        print(f"the link dropped {dropped} ({args.netloss} per 1,000 UDP datagrams)")
    for node, lat in per_node.items():
        if not lat:
            continue
        print(f"{node}: failure -> /hexar/answer median {statistics.median(lat) * 1000:.0f} ms, "
              f"p95 {percentile(lat, 0.95) * 1000:.0f} ms over {len(lat)} failures")


if __name__ == "__main__":
    main()
