"""Flood `hexar serve` with /rosout lines over DDS and check that it keeps answering with flat memory.

    .venv/bin/python scripts/flood_live.py [--rate 10000] [--seconds 10]

Prints the send rate reached, what the node received, its RSS before/during/after, and the answer latency of
questions asked before, during and after the flood.
"""

from __future__ import annotations

import argparse
import os
import signal
import time

from live_common import Listener, RssSampler, percentile, rss_mb, start_serve

from hexar.events import contract as c
from hexar.live import msgs
from hexar.live.dds import DdsEndpoint
from hexar.live.replay import QOS_OF

QUESTION = "What happened?"


def ask(listener: Listener, n_before: int) -> float:
    sent = time.monotonic()
    listener.ask(QUESTION)
    got = listener.wait_answers(n_before + 1, "question", timeout=30)
    return (listener.answers("question")[-1][0] - sent) if len(got) > n_before else float("inf")


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rate", type=float, default=10_000.0, help="lines per second to send")
    ap.add_argument("--seconds", type=float, default=10.0)
    ap.add_argument("--domain", type=int, default=os.getpid() % 100 + 120)
    args = ap.parse_args()

    serve = start_serve(args.domain)
    sampler = RssSampler(serve.pid)
    listener = Listener(args.domain)
    endpoint = DdsEndpoint(args.domain)
    writer = endpoint.writer(c.ROSOUT, c.LOG_TYPE, QOS_OF[c.ROSOUT])
    time.sleep(1.5)
    latencies = [ask(listener, 0)]
    rss_before = rss_mb(serve.pid)
    t0 = time.time_ns()
    sent, started = 0, time.monotonic()
    batch = max(1, int(args.rate / 100))
    next_q = started + 2.0
    while (now := time.monotonic()) - started < args.seconds:
        due = int((now - started) * args.rate)
        while sent < due:
            for _ in range(min(batch, due - sent)):
                stamp = t0 + sent * 100_000
                writer.write(msgs.Log(stamp=msgs.time_of(stamp), level=20, name="controller_server",
                                      msg=f"flood line {sent}: Passing new path to controller."), timestamp=stamp)
                sent += 1
        if now >= next_q:  # questions during the flood, sent from another thread so the flood goes on
            import threading

            threading.Thread(target=lambda: latencies.append(ask(listener, len(listener.answers("question")))),
                             daemon=True).start()
            next_q += 3.0
        time.sleep(0.001)
    elapsed = time.monotonic() - started
    rss_flood = max(mb for _, mb in sampler.samples)
    time.sleep(2.0)
    latencies.append(ask(listener, len(listener.answers("question"))))
    rss_after = rss_mb(serve.pid)
    samples = sampler.stop()
    listener.close()
    endpoint.close()
    serve.send_signal(signal.SIGTERM)
    _, err = serve.communicate(timeout=30)
    print(f"sent {sent} /rosout lines in {elapsed:.1f} s = {sent / elapsed:.0f} lines/s (asked for {args.rate:.0f})")
    print(f"node: {err.strip().splitlines()[-1] if err.strip() else '(no summary)'}")
    print(f"RSS MB: before {rss_before:.0f}, peak during {rss_flood:.0f}, after {rss_after:.0f}; "
          f"samples {[round(mb) for _, mb in samples[:: max(1, len(samples) // 12)]]}")
    ok = [x for x in latencies if x != float("inf")]
    print(f"questions answered {len(ok)}/{len(latencies)}; latency ms median {percentile(ok, 0.5) * 1000:.0f}, "
          f"max {max(ok) * 1000:.0f}")
    print("traceback in node output:", "Traceback" in err)
    return 0 if len(ok) == len(latencies) and "Traceback" not in err else 1


if __name__ == "__main__":
    raise SystemExit(main())
