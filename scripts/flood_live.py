"""Flood `hexar serve` over DDS and check that it keeps answering with flat memory.

    .venv/bin/python scripts/flood_live.py [--rate 10000] [--seconds 10]           # /rosout lines
    .venv/bin/python scripts/flood_live.py --questions [--rate 2000] [--seconds 60]  # /hexar/question
    .venv/bin/python scripts/flood_live.py --failures [--rate 100] [--seconds 30]    # failing tasks on /task_info

Prints the send rate reached, what the node received, its RSS before/during/after, and the answer latency of
questions asked before, during and after the flood. With --questions the flood is questions on /hexar/question
(half plain text, half JSON with made-up thread ids, as anyone on the domain can send), and after it a person's
questions (their own thread) are asked one by one: their median latency, against the same questions asked
before the flood, is what the flood cost them.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
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


def ask_as(listener: Listener, thread: str, question: str = QUESTION, timeout: float = 30.0) -> float:
    """Latency of one question sent with its own thread id, found among any number of other answers."""
    import json

    sent = time.monotonic()
    listener.ask(json.dumps({"question": question, "thread": thread}))
    deadline = sent + timeout
    while time.monotonic() < deadline:
        got = [t for t, a in listener.answers("question") if a.get("thread") == thread]
        if got:
            return got[0] - sent
        time.sleep(0.005)
    return float("inf")


def question_flood(args: argparse.Namespace) -> int:
    import json

    serve = start_serve(args.domain)
    sampler = RssSampler(serve.pid)
    listener = Listener(args.domain)
    time.sleep(1.5)
    before = [ask_as(listener, f"before{i}") for i in range(5)]
    rss_before = rss_mb(serve.pid)
    sent, started = 0, time.monotonic()
    while (now := time.monotonic()) - started < args.seconds:
        due = int((now - started) * args.rate)
        while sent < due:
            listener.ask(QUESTION if sent % 2 else json.dumps({"question": QUESTION, "thread": f"flood{sent}"}))
            sent += 1
        time.sleep(0.001)
    elapsed = time.monotonic() - started
    rss_flood = max(mb for _, mb in sampler.samples)
    after = [ask_as(listener, f"person{i}") for i in range(5)]
    rss_after = rss_mb(serve.pid)
    samples = sampler.stop()
    answered = len(listener.answers("question"))
    listener.close()
    serve.send_signal(signal.SIGTERM)
    _, err = serve.communicate(timeout=30)
    ok_before = [x for x in before if x != float("inf")]
    ok_after = [x for x in after if x != float("inf")]
    base = percentile(ok_before, 0.5)
    print(f"sent {sent} questions in {elapsed:.1f} s = {sent / elapsed:.0f}/s (asked for {args.rate:.0f}); "
          f"answers published {answered}")
    print(f"node: {err.strip().splitlines()[-1] if err.strip() else '(no summary)'}")
    print(f"RSS MB: before {rss_before:.0f}, peak during {rss_flood:.0f}, after {rss_after:.0f} "
          f"(after/before {rss_after / rss_before:.2f}); samples "
          f"{[round(mb) for _, mb in samples[:: max(1, len(samples) // 12)]]}")
    after_ms = percentile(ok_after, 0.5) * 1000
    print(f"a person's question: answered {len(ok_after)}/{len(after)} after the flood, median {after_ms:.0f} ms "
          f"(max {max(ok_after, default=float('inf')) * 1000:.0f} ms); before the flood median {base * 1000:.0f} ms; "
          f"ratio {percentile(ok_after, 0.5) / base:.2f}")
    print("traceback in node output:", "Traceback" in err)
    return 0 if len(ok_after) == len(after) and "Traceback" not in err else 1


TTS = "/hexar_flood_tts"


def failure_flood(args: argparse.Namespace) -> int:
    """Failing tasks on /task_info, each with its own id, as a buggy or hostile publisher on the domain can send:
    the node explains failures unasked and, with --proactive speak, says them on the robot's TTS topic."""
    import json

    from hexar.live.topics import TopicQos

    serve = start_serve(args.domain, "--proactive", "speak", "--tts-topic", TTS, python=args.python)
    sampler = RssSampler(serve.pid)
    listener = Listener(args.domain)
    endpoint = DdsEndpoint(args.domain)
    writer = endpoint.writer(c.TASK_INFO, c.STRING_TYPE, QOS_OF[c.TASK_INFO])
    spoken = listener.endpoint.reader(TTS, c.STRING_TYPE, TopicQos(depth=10_000))  # reliable: every utterance
    said: list[tuple[float, str]] = []
    time.sleep(1.5)
    before = [ask_as(listener, f"before{i}") for i in range(5)]
    rss_before = rss_mb(serve.pid)
    during: list[float] = []
    sent, started = 0, time.monotonic()
    next_q = started + 2.0
    while (now := time.monotonic()) - started < args.seconds:
        due = int((now - started) * args.rate)
        while sent < due:
            step = {"skill": "navigate_to_zone", "params": {"zone": "kitchen"}, "status": "failed",
                    "error_msg": "The skill has been aborted"}
            writer.write(msgs.String(data=json.dumps({"instruction": "go", "task_id": f"flood{sent}",
                                                      "task_status": "valid", "task_error_msg": "",
                                                      "skill_sequence": [step]})))
            sent += 1
        if now >= next_q:  # a person's question during the flood, from another thread so the flood goes on
            import threading

            thread = f"during{len(during)}-{sent}"
            threading.Thread(target=lambda t=thread: during.append(ask_as(listener, t)), daemon=True).start()
            next_q += 3.0
        said += [(time.monotonic(), str(s.data)) for s in spoken.take(256) if s.sample_info.valid_data]
        time.sleep(0.001)
    elapsed = time.monotonic() - started
    rss_flood = max(mb for _, mb in sampler.samples)
    end = time.monotonic() + 10.0  # what the node still says after the flood ended
    while time.monotonic() < end:
        said += [(time.monotonic(), str(s.data)) for s in spoken.take(256) if s.sample_info.valid_data]
        time.sleep(0.05)
    after = [ask_as(listener, f"person{i}") for i in range(5)]
    rss_after = rss_mb(serve.pid)
    sampler.stop()
    unasked = len(listener.answers("failure"))
    replies = sum(1 for _, a in listener.answers("question"))
    listener.close()
    endpoint.close()
    serve.send_signal(signal.SIGTERM)
    _, err = serve.communicate(timeout=60)
    ok = [x for x in during + after if x != float("inf")]
    late = sum(1 for t, _ in said if t > started + elapsed)
    print(f"sent {sent} failing tasks in {elapsed:.1f} s = {sent / elapsed:.0f}/s (asked for {args.rate:.0f}); "
          f"unasked answers published {unasked}; utterances on the TTS topic {len(said)} ({late} after the flood "
          f"ended), with the answers to the person's {replies} questions (the node's line below counts the unasked "
          "ones it did not say)")
    print(f"node: {err.strip().splitlines()[-1] if err.strip() else '(no summary)'}")
    print(f"RSS MB: before {rss_before:.0f}, peak during {rss_flood:.0f}, after {rss_after:.0f}")
    base = percentile(before, 0.5)
    print(f"a person's question: before the flood median {base * 1000:.0f} ms; during it "
          f"{len([x for x in during if x != float('inf')])}/{len(during)} answered, median "
          f"{percentile([x for x in during if x != float('inf')] or [float('inf')], 0.5) * 1000:.0f} ms; after it "
          f"{len([x for x in after if x != float('inf')])}/{len(after)}, median "
          f"{percentile([x for x in after if x != float('inf')] or [float('inf')], 0.5) * 1000:.0f} ms")
    print("traceback in node output:", "Traceback" in err)
    return 0 if len(ok) == len(during) + len(after) and "Traceback" not in err else 1


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rate", type=float, default=None, help="lines (or questions) per second to send "
                    "[10000 lines, 2000 questions]")
    ap.add_argument("--seconds", type=float, default=None, help="[10 for lines, 60 for questions]")
    ap.add_argument("--questions", action="store_true", help="flood /hexar/question instead of /rosout")
    ap.add_argument("--failures", action="store_true", help="flood /task_info with failing tasks instead")
    ap.add_argument("--domain", type=int, default=os.getpid() % 100 + 120)
    ap.add_argument("--python", default=sys.executable, help="the python whose `hexar serve` is flooded")
    args = ap.parse_args()
    if args.failures:
        args.rate = args.rate or 100.0
        args.seconds = args.seconds or 30.0
        return failure_flood(args)
    if args.questions:
        args.rate = args.rate or 2_000.0
        args.seconds = args.seconds or 60.0
        return question_flood(args)
    args.rate = args.rate or 10_000.0
    args.seconds = args.seconds or 10.0

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
