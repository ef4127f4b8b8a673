"""Soak benchmark of `hexar serve` over DDS: robot traffic at real rates, sped up, for a simulated duration.

    .venv/bin/python scripts/bench_live.py [--sim-seconds 3600] [--speed 20] [--chatter 20]

The traffic is the 60 simulated recordings played back to back on one continuous robot clock (task ids made
unique per pass), plus `--chatter` extra /rosout lines per robot second from a node no explainer reads, all sped
up `--speed` times. A question goes to /hexar/question every simulated minute. Prints the node's RSS over
time and peak, and the latency percentiles of proactive explanations (failing /task_info -> answer, as a
listener sees them) and of questions, and whether each failure was explained with `hexar ask`'s cause.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from live_common import Listener, RssSampler, percentile, start_serve

from hexar.events import contract as c
from hexar.live import msgs
from hexar.live.node import FAILURE_QUESTION, INVALID_QUESTION
from hexar.live.replay import DdsReplayer, bag_messages, to_dds

NS = 1_000_000_000
GAP_S = 5.0


def expected_causes(run: Path) -> dict[str, list[str]]:
    from hexar.agent.context import RunSettings
    from hexar.agent.session import Session

    session = Session(RunSettings(recording=run, llm="none"))
    out = {}
    for task in session.context.log.tasks:
        if task.outcome in {"failed", "invalid"}:
            q = INVALID_QUESTION if task.outcome == "invalid" else FAILURE_QUESTION
            out[task.task_id] = session.ask(q, task=task.task_id)["causes"]
    return out


def shifted(msgtype: str, m: Any, offset: int, suffix: str) -> Any:
    d = to_dds(msgtype, m)
    if isinstance(d, msgs.Log):
        d.stamp = msgs.time_of(d.stamp.sec * NS + d.stamp.nanosec + offset)
    elif isinstance(d, msgs.String):
        obj = json.loads(d.data)
        obj["task_id"] = f"{obj['task_id']}{suffix}"
        d.data = json.dumps(obj)
    elif hasattr(d, "header"):
        d.header.stamp = msgs.time_of(d.header.stamp.sec * NS + d.header.stamp.nanosec + offset)
    return d


def traffic(runs: list[Path], sim_s: float, chatter: float) -> Iterator[tuple[int, str, str, Any, str]]:
    """(robot time, topic, type, DDS message, run name) in time order, with recordings back to back."""
    cursor = time.time_ns()
    end = cursor + int(sim_s * NS)
    n = 0
    while True:
        for run in runs:
            items, _, start, _ = bag_messages(run)
            offset = cursor - start
            suffix = f"-p{n // len(runs)}"
            n += 1
            last = cursor
            batch: list[tuple[int, str, str, Any, str]] = []
            for topic, msgtype, t, m in items:
                batch.append((t + offset, topic, msgtype, shifted(msgtype, m, offset, suffix), run.name + suffix))
                last = t + offset
            stop = last + int(GAP_S * NS)
            step = int(NS / chatter) if chatter > 0 else 0
            if step:
                batch.extend((t, c.ROSOUT, c.LOG_TYPE, msgs.Log(stamp=msgs.time_of(t), level=20, name="soak_chatter",
                                                                msg=f"heartbeat {t}"), "")
                             for t in range(cursor, stop, step))
            yield from sorted(batch, key=lambda x: x[0])
            cursor = stop
            if cursor >= end:
                return


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim-seconds", type=float, default=3600.0)
    ap.add_argument("--speed", type=float, default=20.0)
    ap.add_argument("--chatter", type=float, default=20.0, help="extra /rosout lines per robot second")
    ap.add_argument("--runs", type=Path, default=None, help="folder of recordings [default: simulate the suite]")
    ap.add_argument("--domain", type=int, default=os.getpid() % 100 + 20)
    args = ap.parse_args()

    folder = args.runs
    if folder is None:
        from hexar.evals.scenarios.suite import simulate_suite

        folder = Path(tempfile.mkdtemp(prefix="hexar-soak-"))
        simulate_suite(folder)
    runs = sorted(p for p in folder.iterdir() if (p / "metadata.yaml").is_file())
    expected = {run.name: expected_causes(run) for run in runs}

    serve = start_serve(args.domain)
    sampler = RssSampler(serve.pid, every_s=1.0)
    listener = Listener(args.domain)
    writer = DdsReplayer(args.domain)
    writer.prepare()
    time.sleep(1.0)
    started = time.monotonic()
    sim0: int | None = None
    next_question = 60 * NS
    questions: list[float] = []
    asked_at: list[float] = []
    want: dict[str, list[str]] = {}
    rss_by_sim: list[tuple[float, float]] = []
    for t, topic, _msgtype, d, run_name in traffic(runs, args.sim_seconds, args.chatter):
        sim0 = t if sim0 is None else sim0
        due = started + (t - sim0) / NS / args.speed
        delay = due - time.monotonic()
        if delay > 0:
            time.sleep(delay)
        writer.endpoint.writers[topic].write(d, timestamp=t)
        if topic == c.TASK_INFO and run_name:
            base, suffix = run_name.rsplit("-p", 1)
            for task_id, causes in expected[base].items():
                want[f"{task_id}-p{suffix}"] = causes
        if t - sim0 >= next_question:
            asked_at.append(time.monotonic())
            listener.ask("Why didn't you do it?")
            next_question += 60 * NS
            if sampler.samples:
                rss_by_sim.append(((t - sim0) / NS, sampler.samples[-1][1]))
    time.sleep(3.0)
    wall = time.monotonic() - started
    answers = listener.answers()
    failures = [(w, a) for w, a in answers if a.get("trigger") == "failure"]
    proactive = []
    for w, a in failures:
        key = next((k for k in listener.heard.failures if k.startswith(a["task_id"] + ":")), None)
        if key is not None:
            proactive.append(w - listener.heard.failures[key])
    replies = [w for w, a in answers if a.get("trigger") == "question"]
    for sent, got in zip(asked_at, replies, strict=False):
        questions.append(got - sent)
    right = sum(1 for _, a in failures if want.get(a["task_id"]) == a["causes"])
    samples = sampler.stop()
    listener.close()
    writer.close()
    serve.send_signal(signal.SIGTERM)
    _, err = serve.communicate(timeout=30)
    print(f"simulated {args.sim_seconds / 60:.0f} min of robot traffic at x{args.speed:g} in {wall:.0f} s wall "
          f"({len(runs)} recordings back to back, +{args.chatter:g} lines/s chatter)")
    print(f"node: {err.strip().splitlines()[-1] if err.strip() else '(no summary)'}")
    print("RSS MB by simulated minute:", ", ".join(f"{s / 60:.0f}:{mb:.0f}" for s, mb in rss_by_sim[::5]))
    print(f"RSS MB: first {samples[0][1]:.0f}, peak {max(mb for _, mb in samples):.0f}, last {samples[-1][1]:.0f}")
    print(f"failures explained {len(failures)} of {len(want)}, with hexar ask's cause {right}")
    print(f"proactive latency ms: p50 {percentile(proactive, 0.5) * 1000:.0f}, "
          f"p95 {percentile(proactive, 0.95) * 1000:.0f}, max {max(proactive, default=0) * 1000:.0f} "
          f"(n={len(proactive)})")
    print(f"question latency ms: p50 {percentile(questions, 0.5) * 1000:.0f}, "
          f"p95 {percentile(questions, 0.95) * 1000:.0f} (n={len(questions)} of {len(asked_at)})")
    print("traceback in node output:", "Traceback" in err)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
