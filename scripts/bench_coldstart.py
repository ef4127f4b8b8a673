"""Cold-start benchmark: wall time of one-shot `hexar` commands, each a fresh process, median of N rounds.

    .venv/bin/python scripts/bench_coldstart.py [--rounds 5] [--suite runs/suite] [--no-embedded] [--no-voice]
                                                [--baseline OLD/bin/hexar]

Commands are interleaved round by round, so `ask --llm none / inspect` is a ratio of figures taken under the same
load (other work on the machine slows both alike). Measured: `inspect`; `ask --llm none` (the before-stop hook's
command); `ask --llm embedded` when the failure check decides and when the model routes, plus the model's load
time apart; `chat` until its first prompt (in a pseudo-terminal); `listen` until its first spoken answer is
printed (a WAV question made with espeak-ng). Then an import-time breakdown of `ask --llm none` (`python -X
importtime`, self time summed per top-level package). Targets are the issue's: ask <= 1.0 s and <= 1.3x inspect;
embedded <= 3 s (failure check) and <= 4 s (model routes). `--baseline` times another installation's `hexar`
(the code before a change) on `inspect` and `ask --llm none` in the same rounds and prints new / old.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from collections.abc import Callable
from pathlib import Path

QUESTION = "Why didn't you bring me the coffee?"
FAILED = "bagfile_5_1"  # navigation failed: the failure check decides
ROUTED = ("bagfile_8_1", "Why did you move like that?")  # the task succeeded: the question is routed
TARGETS = {"ask --llm none": 1.0, "ask --llm embedded (failure check)": 3.0, "ask --llm embedded (model routes)": 4.0}
RATIO_TARGET = 1.3


def hexar() -> list[str]:
    exe = Path(sys.executable).with_name("hexar")
    return [str(exe)] if exe.is_file() else [sys.executable, "-m", "hexar"]


def timed(argv: list[str], env: dict[str, str] | None = None) -> tuple[float, str]:
    began = time.perf_counter()
    done = subprocess.run(argv, capture_output=True, text=True, timeout=600, env=env)
    took = time.perf_counter() - began
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)} exited {done.returncode}: {done.stderr.strip()[-300:]}")
    return took, done.stdout


def until(argv: list[str], marker: str, stdin: str | None = None) -> float:
    """Seconds from start until `marker` appears in the output; then the process is stopped."""
    began = time.perf_counter()
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            stdin=subprocess.DEVNULL if stdin is None else subprocess.PIPE)
    assert proc.stdout is not None
    seen = ""
    for line in proc.stdout:
        seen += line
        if marker in line:
            took = time.perf_counter() - began
            proc.kill()
            proc.wait()
            return took
    proc.wait()
    raise RuntimeError(f"{' '.join(argv)} never printed {marker!r}: {seen[-300:]}")


def chat_first_prompt(run: Path, db: Path) -> float:
    import pexpect

    began = time.perf_counter()
    exe, *rest = hexar()
    child = pexpect.spawn(exe, [*rest, "chat", str(run), "--llm", "none", "--checkpoints", str(db)],
                          encoding="utf-8", timeout=60, dimensions=(40, 120))
    child.expect("you>")
    took = time.perf_counter() - began
    child.sendeof()
    child.expect(pexpect.EOF)
    return took


def model_load_s() -> float:
    code = ("from hexar.agent.backends import EmbeddedModel\nm = EmbeddedModel()\nm._llm  # noqa: B018\n"
            "print(m.load_s)\n")
    return float(timed([sys.executable, "-c", code])[1].strip().splitlines()[-1])


def import_breakdown(argv: list[str], top: int = 10) -> tuple[float, list[tuple[str, float]]]:
    """Total import time and self time per top-level package, in seconds, from `python -X importtime`."""
    done = subprocess.run([sys.executable, "-X", "importtime", "-m", "hexar", *argv], capture_output=True,
                          text=True, timeout=600)
    per: dict[str, float] = defaultdict(float)
    for line in done.stderr.splitlines():
        m = re.match(r"import time:\s+(\d+) \|\s+\d+ \|\s*(\S+)", line)
        if m:
            per[m.group(2).split(".")[0]] += int(m.group(1)) / 1e6
    ranked = sorted(per.items(), key=lambda kv: -kv[1])
    return sum(per.values()), ranked[:top]


def median(xs: list[float]) -> float:
    return statistics.median(xs) if xs else float("nan")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--suite", type=Path, default=Path("runs/suite"))
    parser.add_argument("--no-embedded", action="store_true")
    parser.add_argument("--no-voice", action="store_true")
    parser.add_argument("--json", type=Path, help="also write the figures here")
    parser.add_argument("--baseline", help="another installation's hexar executable, timed in the same rounds")
    args = parser.parse_args()
    suite: Path = args.suite
    if not (suite / FAILED).is_dir():
        from hexar.evals.scenarios.suite import simulate_suite

        simulate_suite(suite, only=lambda s, v: (s, v) in {(5, 1), (8, 1)})
    from hexar.agent.backends import embedded_available

    embedded = not args.no_embedded and embedded_available()
    tmp = Path(tempfile.mkdtemp(prefix="hexar-bench-"))
    cmds: dict[str, Callable[[], float]] = {
        "inspect": lambda: timed([*hexar(), "inspect", str(suite / FAILED)])[0],
        "ask --llm none": lambda: timed([*hexar(), "ask", str(suite / FAILED), QUESTION, "--llm", "none"])[0],
        "chat (to first prompt)": lambda: chat_first_prompt(suite / FAILED, tmp / "threads.sqlite"),
    }
    if args.baseline:
        old = [args.baseline]
        cmds["inspect (baseline)"] = lambda: timed([*old, "inspect", str(suite / FAILED)])[0]
        cmds["ask --llm none (baseline)"] = lambda: timed(
            [*old, "ask", str(suite / FAILED), QUESTION, "--llm", "none"])[0]
    if importlib.util.find_spec("ros_wheels_bootstrapper") is not None:
        # The `ros` extra's wheels re-execute every Python start to set LD_LIBRARY_PATH, unless
        # _ROS_WHEELS_BOOTSTRAP_COMPLETE is set. This script inherits it from its own start, so the rows above
        # run without the re-execution; these two start as from a shell that never set it: `hexar` itself (which
        # scripts/hexar_ros_lazy.pth keeps from re-executing) and the same command started through `python -c`,
        # which the wheels' bootstrap re-executes as it did before that file existed.
        shell = {k: v for k, v in os.environ.items()
                 if k not in {"LD_LIBRARY_PATH", "_ROS_WHEELS_BOOTSTRAP_COMPLETE", "_HEXAR_ROS_LAZY"}}
        ask = ["ask", str(suite / FAILED), QUESTION, "--llm", "none"]
        cmds["ask --llm none, from a shell"] = lambda: timed([*hexar(), *ask], env=shell)[0]
        cmds["ask --llm none, wheels' re-exec"] = lambda: timed(
            [sys.executable, "-c", f"import sys; from hexar.cli import main; sys.exit(main({ask!r}))"], env=shell)[0]
    if embedded:
        cmds["ask --llm embedded (failure check)"] = lambda: timed(
            [*hexar(), "ask", str(suite / FAILED), QUESTION, "--llm", "embedded"])[0]
        cmds["ask --llm embedded (model routes)"] = lambda: timed(
            [*hexar(), "ask", str(suite / ROUTED[0]), ROUTED[1], "--llm", "embedded"])[0]
        cmds["embedded model load (in-process)"] = model_load_s
    if not args.no_voice:
        try:
            from hexar.voice.audio import write_wav
            from hexar.voice.tts import EspeakSynthesizer

            wav = write_wav(tmp / "q.wav", EspeakSynthesizer().synthesize(QUESTION))
            cmds["listen (to first answer)"] = lambda: until(
                [*hexar(), "listen", str(suite / FAILED), "--wav", str(wav), "--llm", "none", "--out",
                 str(tmp / "answers"), "--checkpoints", str(tmp / "voice.sqlite")], "HEXAR:")
        except Exception as err:  # no espeak-ng or no speech extras: report, measure the rest
            print(f"listen not measured: {err}", file=sys.stderr)
    times: dict[str, list[float]] = {name: [] for name in cmds}
    ratios: list[float] = []
    for r in range(args.rounds):
        for name, fn in cmds.items():
            times[name].append(fn())
        ratios.append(times["ask --llm none"][-1] / times["inspect"][-1])
        print(f"round {r + 1}/{args.rounds}: " + ", ".join(f"{n} {t[-1]:.2f}s" for n, t in times.items()),
              file=sys.stderr)
    total, breakdown = import_breakdown(["ask", str(suite / FAILED), QUESTION, "--llm", "none"])
    ask_med, inspect_med = median(times["ask --llm none"]), median(times["inspect"])
    figures = {
        "rounds": args.rounds, "cores": os.cpu_count(), "load_avg_1min": round(os.getloadavg()[0], 2),
        "median_s": {n: round(median(t), 3) for n, t in times.items()},
        "all_s": {n: [round(x, 3) for x in t] for n, t in times.items()},
        "ask_over_inspect": {"of_medians": round(ask_med / inspect_med, 3), "median_per_round": round(
            median(ratios), 3)},
        "import_s": {"total": round(total, 3), "by_package": {k: round(v, 3) for k, v in breakdown}},
        "embedded": "measured" if embedded else "not measured (llama-cpp-python or the model is missing)",
    }
    print(f"cold start, median of {args.rounds} one-shot runs ({os.cpu_count()} cores, "
          f"1-min load average {figures['load_avg_1min']}):")
    for name, t in times.items():
        target = TARGETS.get(name)
        verdict = "" if target is None else f"  target <= {target:.1f} s: {'ok' if median(t) <= target else 'MISSED'}"
        print(f"  {name:38s} {median(t):6.2f} s{verdict}")
    ok = figures["ask_over_inspect"]["of_medians"] <= RATIO_TARGET  # type: ignore[index]
    print(f"  ask --llm none / inspect (same run)    {ask_med / inspect_med:6.2f} x  target <= {RATIO_TARGET} x: "
          f"{'ok' if ok else 'MISSED'} (per-round median {median(ratios):.2f} x)")
    if args.baseline:
        for name in ("inspect", "ask --llm none"):
            new, old_t = times[name], times[f"{name} (baseline)"]
            per_round = median([a / b for a, b in zip(new, old_t, strict=True)])
            figures[f"{name} new/old"] = {"of_medians": round(median(new) / median(old_t), 3),
                                          "median_per_round": round(per_round, 3)}
            print(f"  {name + ' new / baseline':38s} {median(new) / median(old_t):6.2f} x  "
                  f"(per-round median {per_round:.2f} x)")
    print(f"import time of `ask --llm none`: {total:.2f} s; by package (self time):")
    for pkg, secs in breakdown:
        print(f"  {pkg:24s} {secs * 1000:7.0f} ms")
    if args.json:
        args.json.write_text(json.dumps(figures, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
