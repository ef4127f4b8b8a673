"""`hexar ask`: one question, a file of questions (`--questions`), or many recordings, in one process.

Every question is a new conversation, so the agent runs one-shot (agent/oneshot.py): the same nodes as the
LangGraph agent, without importing LangGraph. Start-up (imports, explainers, model load) is paid once however
many questions and recordings there are; each recording is decoded once.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

from hexar.agent.context import RunSettings
from hexar.agent.errors import BadQuestionError
from hexar.errors import USER_ERRORS, HexarError
from hexar.safe_text import json_dumps, visible

if TYPE_CHECKING:
    from rich.console import Console


def recordings_in(folder: Path) -> list[Path]:
    """The recordings `--runs` names, as `hexar runs` lists them: the folder itself when it is one, else every
    recording under it at any depth."""
    from hexar.workspace import is_recording, recordings_under

    if not folder.is_dir() and not is_recording(folder):
        raise HexarError(f"not a folder: {folder}")
    found = recordings_under(folder)
    if not found:
        raise HexarError(f"no recordings in {folder}")
    return found


def split_targets(targets: list[str], questions: Path | None, runs: Path | None) -> tuple[list[Path], str | None]:
    """`RUN... QUESTION`: the last argument is the question unless the questions come from --questions."""
    paths = [Path(t) for t in targets]
    question: str | None = None
    if questions is None and targets:
        question = targets[-1]
        paths = paths[:-1]
    if runs is not None:
        paths.extend(recordings_in(runs))
    if not paths:
        raise HexarError("give a recording, then a question (or --questions FILE)")
    if questions is None and question is None:
        raise HexarError("give a question or --questions FILE")
    return paths, question


def read_questions(path: Path) -> list[tuple[int, str]]:
    """The questions of a file with their line numbers in it (blank lines are skipped, not renumbered)."""
    from hexar.inputs import read_text_arg

    return [(n, ln.strip()) for n, ln in enumerate(read_text_arg(path, "--questions").splitlines(), start=1)
            if ln.strip()]


def ask(targets: list[str], questions: Path | None, runs: Path | None, task: str | None, llm: str,
        as_json: bool, verbose: bool, console: Console, phrase: bool | None = None,
        plot: Path | None = None) -> int:
    from hexar import progress

    with progress.shown():
        return _ask(targets, questions, runs, task, llm, as_json, verbose, console, phrase, plot)


def _ask(targets: list[str], questions: Path | None, runs: Path | None, task: str | None, llm: str,
         as_json: bool, verbose: bool, console: Console, phrase: bool | None, plot: Path | None) -> int:
    from hexar import progress
    from hexar.agent.backends import resolve
    from hexar.agent.oneshot import OneShot

    paths, question = split_targets(targets, questions, runs)
    lines = read_questions(questions) if questions is not None else [(1, question or "")]
    with progress.step(f"finding the LLM backend ({llm})"):
        backend = resolve(llm)  # one backend (and one model load) for every recording
    if plot is not None and (questions is not None or len(paths) > 1):
        raise HexarError("--plot draws one answer: give one recording and one question")
    if len(paths) == 1 and questions is None:
        with progress.step(f"reading {paths[0].name}"):
            agent = OneShot(RunSettings(recording=paths[0], llm=llm, phrase=phrase), backend)
        _say_recovered(agent)
        with progress.step("working out the answer"):
            result = agent.ask(lines[0][1], task=task)
        if result["error"]:
            raise BadQuestionError(result["error"])
        if plot is not None:
            from hexar.web.explain import plot_task

            plot_task(agent.context.log, result, plot)
            print(f"wrote the figure of this answer to {visible(plot)}", file=sys.stderr)
        if as_json:
            print(json_dumps(result, indent=2))
        else:
            from hexar.chat import render_answer

            render_answer(console, result, evidence=verbose, verbose=verbose)
        return 0
    worst = 0
    names = labels(paths)
    for path in paths:
        try:
            with progress.step(f"reading {names[path]}"):
                agent = OneShot(RunSettings(recording=path, llm=llm, phrase=phrase), backend)
        except USER_ERRORS as err:
            worst = 2
            _refused({"recording": str(path), "error": str(err)}, as_json, names[path])
            continue
        _say_recovered(agent)
        for n, line in lines:
            try:
                with progress.step(f"answering line {n}"):
                    result = agent.ask(line, task=task)
            except USER_ERRORS as err:  # e.g. --task names a task this recording does not have
                result = {"answer": "", "error": str(err), "recording": str(path)}
            result = {**result, "question": line, "line": n}
            if result["error"]:
                worst = 2
                _refused(result, as_json, names[path])
            elif as_json:
                print(json_dumps(result))
            else:
                # One answer line per answer (after the echoed question in a --questions batch), so a batch's
                # output lines up with its questions.
                if questions is not None:
                    print(f"Q: {visible(line)}")
                answer = visible(result["answer"], keep_newlines=True)
                print(f"{visible(names[path])}: {answer}" if len(paths) > 1 else answer)
    return worst


def _say_recovered(agent: Any) -> None:
    """A recording cut short and recovered (events/recover.py) is answered, with a note on stderr saying so."""
    for warning in agent.context.log.warnings:
        if warning.startswith("recovered:"):
            print(f"note: {visible(agent.context.log.path.name)}: {visible(warning)}", file=sys.stderr)


def labels(paths: list[Path]) -> dict[Path, str]:
    """What each answer of a batch is printed after: the recording's folder name, or where two share one (the same
    run name under two robots), its path under the folder they have in common."""
    if len({p.name for p in paths}) == len(paths):
        return {p: p.name for p in paths}
    common = Path(os.path.commonpath([p.absolute() for p in paths]))
    under = {p: p.absolute().relative_to(common).as_posix() for p in paths}
    return {p: p.name if rel == "." else rel for p, rel in under.items()}


def _refused(result: dict[str, Any], as_json: bool, where: str) -> None:
    """A refused line or unreadable recording: its own JSON object with `error`, or one ERROR line."""
    if as_json:
        print(json_dumps({"answer": "", **result}))
        return
    line = f" line {result['line']}" if "line" in result else ""
    print(f"ERROR: {visible(where)}{line}: {visible(result['error'])}", file=sys.stderr)
