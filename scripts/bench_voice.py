"""Voice benchmark: word error rate of the default transcriber, routing of transcribed vs typed questions, and the
latency of one spoken turn (transcription + answer + synthesis), on this machine's CPU.

    .venv/bin/python scripts/bench_voice.py [--runs 3] [--json out.json]

The 180 eval questions (40 distinct texts) are synthesised with two voices (piper `joe`, espeak-ng), transcribed
with the bundled whisper tiny.en, and routed with `--llm none` on the matching simulated recording, as the
`hexar listen` loop would (transcript repaired by `hexar.voice.transcripts.repair`).
"""

from __future__ import annotations

import argparse
import json
import re
import statistics
import tempfile
import time
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.table import Table

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.evals.cases import Case, cases
from hexar.evals.scenarios.suite import simulate_suite
from hexar.voice.audio import Audio
from hexar.voice.loop import say_answer
from hexar.voice.stt import WhisperTranscriber
from hexar.voice.transcripts import normalise, repair
from hexar.voice.tts import EspeakSynthesizer, PiperSynthesizer, Synthesizer


def words(text: str) -> list[str]:
    return re.sub(r"[^a-z0-9' ]+", " ", text.lower().replace("-", " ")).split()


def edit_distance(ref: list[str], hyp: list[str]) -> int:
    row = list(range(len(hyp) + 1))
    for i, r in enumerate(ref, start=1):
        prev, row[0] = row[0], i
        for j, h in enumerate(hyp, start=1):
            prev, row[j] = row[j], min(row[j] + 1, row[j - 1] + 1, prev + (r != h))
    return row[-1]


def wer(pairs: list[tuple[str, str]]) -> float:
    errors = sum(edit_distance(words(r), words(h)) for r, h in pairs)
    return errors / max(1, sum(len(words(r)) for r, _ in pairs))


def route(sessions: dict[str, Session], case: Case, question: str) -> bool:
    result = sessions[case.recording].ask(question)
    return bool(result["explainers"]) and result["explainers"][0] == case.scenario.explainer


def timed(fn: Any, *args: Any) -> tuple[Any, float]:
    started = time.perf_counter()
    value = fn(*args)
    return value, (time.perf_counter() - started) * 1000


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=3, help="latency runs; medians of the per-run medians")
    ap.add_argument("--json", type=Path, help="also write the figures to this file")
    args = ap.parse_args()
    console = Console(highlight=False)
    all_cases = cases()
    texts = sorted({c.question for c in all_cases})

    started = time.perf_counter()
    stt = WhisperTranscriber()
    load_stt = time.perf_counter() - started
    started = time.perf_counter()
    voices: dict[str, Synthesizer] = {"piper-joe": PiperSynthesizer(), "espeak-ng": EspeakSynthesizer()}
    load_tts = time.perf_counter() - started

    audio: dict[str, dict[str, Audio]] = {}
    heard: dict[str, dict[str, str]] = {}
    stt_ms: dict[str, list[float]] = {}
    for name, synth in voices.items():
        audio[name] = {t: synth.synthesize(t) for t in texts}
        heard[name], stt_ms[name] = {}, []
        for t in texts:
            heard[name][t], ms = timed(stt.transcribe, audio[name][t])
            stt_ms[name].append(ms)

    with tempfile.TemporaryDirectory() as tmp:
        simulate_suite(Path(tmp), "sqlite3", 0)
        sessions = {c.recording: Session(RunSettings(recording=Path(tmp) / c.recording, llm="none"))
                    for c in all_cases}
        typed = [route(sessions, c, c.question) for c in all_cases]
        lowered = [route(sessions, c, normalise(c.question)) for c in all_cases]
        spoken_ok = {n: [route(sessions, c, repair(heard[n][c.question])) for c in all_cases] for n in voices}
        misroutes = {n: sorted({heard[n][c.question] for c, ok in zip(all_cases, spoken_ok[n], strict=True)
                                if not ok}) for n in voices}

        # latency of a spoken turn with the default voice: hear the question, answer it, synthesise the answer
        piper = voices["piper-joe"]
        run_medians: list[dict[str, float]] = []
        for _ in range(args.runs):
            per: dict[str, list[float]] = {"transcribe": [], "answer": [], "synthesise": [], "total": []}
            for c in all_cases[::3]:  # one question per recording
                text, t_stt = timed(stt.transcribe, audio["piper-joe"][c.question])
                result, t_ans = timed(sessions[c.recording].ask, repair(text))
                _, t_tts = timed(lambda r: [piper.synthesize(u) for u in say_answer(r)], result)
                for k, v in (("transcribe", t_stt), ("answer", t_ans), ("synthesise", t_tts),
                             ("total", t_stt + t_ans + t_tts)):
                    per[k].append(v)
            run_medians.append({k: statistics.median(v) for k, v in per.items()})

    pct = lambda ok: round(100 * sum(ok) / len(ok), 1)  # noqa: E731
    figures: dict[str, Any] = {
        "cases": len(all_cases), "distinct_questions": len(texts),
        "model_load_s": {"whisper_tiny_en": round(load_stt, 2), "tts_voices": round(load_tts, 2)},
        "wer_percent": {n: {"cases": round(100 * wer([(c.question, heard[n][c.question]) for c in all_cases]), 1),
                            "distinct": round(100 * wer([(t, heard[n][t]) for t in texts]), 1)} for n in voices},
        "routing_percent": {"typed": pct(typed), "typed_lowercase_no_punctuation": pct(lowered),
                            **{f"spoken_{n}": pct(spoken_ok[n]) for n in voices}},
        "transcribe_ms_median": {n: round(statistics.median(v), 1) for n, v in stt_ms.items()},
        "latency_ms_median": {k: round(statistics.median(r[k] for r in run_medians), 1) for k in run_medians[0]},
        "latency_ms_per_run": [{k: round(v, 1) for k, v in r.items()} for r in run_medians],
        "misrouted_transcripts": misroutes,
        "transcripts": heard,
    }

    table = Table("measure", *voices, title="HEXAR voice benchmark (whisper tiny.en, --llm none)")
    table.add_row("WER, 180 cases (%)", *(str(figures["wer_percent"][n]["cases"]) for n in voices))
    table.add_row("WER, 40 distinct questions (%)", *(str(figures["wer_percent"][n]["distinct"]) for n in voices))
    table.add_row("routing, transcribed (%)", *(str(figures["routing_percent"][f"spoken_{n}"]) for n in voices))
    table.add_row("routing, typed (%)", *[str(figures["routing_percent"]["typed"])] * len(voices))
    table.add_row("transcription, median ms", *(str(figures["transcribe_ms_median"][n]) for n in voices))
    console.print(table)
    lat = Table("median ms per spoken question", *figures["latency_ms_median"],
                title=f"latency, piper voice, {args.runs} runs x {len(all_cases[::3])} questions")
    lat.add_row("median of run medians", *(str(v) for v in figures["latency_ms_median"].values()))
    console.print(lat)
    summary = {k: v for k, v in figures.items() if k != "transcripts"}
    print(json.dumps(summary, indent=2))
    if args.json:
        args.json.write_text(json.dumps(figures, indent=2), encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
