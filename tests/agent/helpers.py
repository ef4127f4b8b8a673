from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.evals.scenarios.bag import BagBuilder, sec_ns


def converse(run: Path, *questions: str) -> list[dict[str, Any]]:
    """The questions asked in turn in one new conversation about a recording, without an LLM: their results."""
    session = Session(RunSettings(recording=run, llm="none"))
    thread = session.new_thread()
    return [session.ask(q, thread=thread) for q in questions]


class CountingModel:
    """A TextModel that records every call. It stands where a real model's API is; it answers 'none' so that
    routing must fall back to the deterministic parts."""

    name = "counting"
    max_prompt_chars = 600

    def __init__(self, reply: str = '{"explainer": "none"}') -> None:
        self.calls: list[Sequence[Mapping[str, str]]] = []
        self.reply = reply

    def chat(self, messages: Sequence[Mapping[str, str]], *, schema: Mapping[str, Any] | None = None,
             max_tokens: int = 160) -> str:
        self.calls.append(messages)
        if schema is not None:
            json.loads(self.reply)
        return self.reply


def one_step_task(b: BagBuilder, t0: int, every_s: float, instruction: str, skill: str, params: dict[str, Any],
                  outcome: str = "succeeded", error: str = "") -> None:
    """A /task_info task of one step, as the robot publishes it: waiting, running, then `outcome`, `every_s` apart
    from `t0` + 1 s (`error` on the last update)."""
    for k, status in enumerate(("waiting", "Running", outcome)):
        b.task_info(t0 + sec_ns(1 + every_s * k), {
            "instruction": instruction, "task_id": "t1", "task_status": "valid", "task_error_msg": "",
            "skill_sequence": [{"skill": skill, "params": params, "status": status,
                                "error_msg": error if status == outcome else ""}]})


def real_module_run(case_id: str, out: Path) -> Path:
    """The real module excerpt `case_id` (any suite of evals/data/real_modules) written with rosbags at `out`, its
    task derived from its logs as for any recording without /task_info."""
    from hexar.evals import real_modules

    case = next(e for suite in real_modules.FILES for e in real_modules.load_excerpts(suite) if e.id == case_id)
    return Path(real_modules.write_recording(case, out, task=False))


def real_nav2_run(case_id: str, out: Path) -> Path:
    """The real Nav2 excerpt `case_id` (the corpus or a blind set, evals/data/real_nav2) written with rosbags at
    `out`, its task derived from its logs."""
    from hexar.evals import real_nav2

    cases = [*real_nav2.corpus(), *(e for r in range(1, 30) for e in real_nav2.blind_set(r))]
    return Path(real_nav2.write_recording(next(e for e in cases if e.id == case_id), out, task=False))


def real_run_with_parameters(case_id: str, out: Path, declared: Mapping[str, Mapping[str, Any]],
                             changed: Sequence[tuple[float, str, str, Any]] = ()) -> Path:
    """The real Nav2 or module excerpt `case_id` as real_nav2_run or real_module_run writes it (its task derived from
    its logs), with the /parameter_events its nodes would have published: each node of `declared` announces its
    parameters 2 s before the first line, and each (seconds after the first line, node, name, value) of `changed`
    sets one."""
    from hexar.evals import real_modules, real_nav2
    from hexar.events.console import parse_console, stamped

    cases = [*real_nav2.corpus(), *(e for r in range(1, 30) for e in real_nav2.blind_set(r)),
             *real_modules.load_excerpts("real-modules")]
    case = next(e for e in cases if e.id == case_id)
    records = stamped(parse_console(case.lines))
    b = BagBuilder()
    for r in records:
        assert r.stamp_ns is not None
        b.log(r.stamp_ns, r.name or r.process, r.level, r.msg, r.file, r.function, r.line)
    first = min(r.stamp_ns or 0 for r in records)
    for k, (node, params) in enumerate(declared.items()):
        b.parameters(first - sec_ns(2) + k * 1_000_000, node, new=dict(params))
    for after_s, node, name, value in changed:
        b.parameters(first + sec_ns(after_s), node, changed={name: value})
    return b.write(out)
