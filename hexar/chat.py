"""`hexar chat` (interactive) over one recording, and the answer panel `hexar ask` prints too."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any
from urllib.parse import quote

from rich.console import Console
from rich.panel import Panel

from hexar.agent.context import RunSettings
from hexar.agent.questions import GOODBYE, is_farewell, small_talk_reply
from hexar.errors import USER_ERRORS
from hexar.events.errors import NoTaskError
from hexar.events.log import EventLog
from hexar.events.tasks import Task
from hexar.render import clock
from hexar.safe_text import safe

HELP = ("Ask why I did something. Commands: /task [ID] (switch or list tasks), /evidence (toggle evidence), "
        "/why (go deeper), /reset (new conversation), /thread (show its id), /help. Ctrl-D quits.")


SHOWN_EVIDENCE = 6  # /evidence in a chat; `ask --verbose` shows every item


def render_answer(console: Console, result: dict[str, Any], evidence: bool, verbose: bool = False) -> None:
    from rich.table import Table

    console.print(Panel(safe(result["answer"], keep_newlines=True), title="HEXAR", title_align="left",
                        border_style="cyan"))
    if evidence:
        # in time order, each item wrapped in its own column so a long log line never runs under the times
        items = sorted(result["evidence"], key=lambda ev: ev["t"])
        shown = items if verbose else items[:SHOWN_EVIDENCE]
        grid = Table.grid(padding=(0, 1))
        grid.add_column(no_wrap=True, style="dim")
        grid.add_column(no_wrap=True, style="dim")
        grid.add_column(overflow="fold")
        for ev in shown:
            grid.add_row(f"  {clock(ev['t'])}", safe(ev["topic"]), safe(ev["item"]))
        if shown:
            console.print(grid)
        if len(items) > len(shown):
            console.print(f"  [dim]… and {len(items) - len(shown)} more (ask --verbose or --json shows them "
                          "all)[/dim]")
        for figure in result.get("figures", []):
            console.print(f"  [dim]{safe(figure)}[/dim]")
    if verbose:
        for label, key in (("Would have helped", "counterfactual"), ("Fix", "fix")):
            if result.get(key):
                console.print(f"  [bold]{label}:[/bold] {safe(result[key])}")
        console.print(safe(f"  route={result['route']} explainers={','.join(result['explainers'])} "
                           f"backend={result['backend']} causes={','.join(result['causes'])} "
                           f"total={result['timings_ms'].get('total')} ms"), style="dim")


def chat(run: Path, thread: str | None, llm: str, console: Console, checkpoints: Path | None = None,
         phrase: bool | None = None) -> int:
    from hexar import progress

    with progress.shown():
        return _chat(run, thread, llm, console, checkpoints, phrase)


def _chat(run: Path, thread: str | None, llm: str, console: Console, checkpoints: Path | None,
          phrase: bool | None) -> int:
    from hexar import progress

    with progress.step(f"reading {run.name} and starting the conversation"):
        from hexar.agent.session import Session, default_checkpoints

        session = Session(RunSettings(recording=run, llm=llm, phrase=phrase),
                          checkpoints=checkpoints or default_checkpoints())
    thread = thread or session.new_thread()
    log = session.context.log
    try:
        task = log.task()
        about = f'task "{safe(task.instruction)}" ({safe(task.outcome)})'
    except NoTaskError as err:  # what it recorded can still be asked about (agent/whole.py)
        about = f"{safe(err)}; ask about its log, nodes, topics, parameters or times"
    console.print(f"[bold]{safe(run.name)}[/bold]: {about}; backend {safe(session.backend.name)}; "
                  f"thread {safe(thread)}")
    for turn in session.history(thread):
        console.print(f"[dim]you: {safe(turn['question'])}\nHEXAR: {safe(turn['answer'], keep_newlines=True)}[/dim]")
    console.print(f"[dim]{HELP}[/dim]")
    read = _reader(checkpoints or default_checkpoints(), console)
    evidence = False
    while True:
        try:
            line = read()
        except EOFError:
            console.print("bye")
            return 0
        except KeyboardInterrupt:
            continue
        if not line:
            continue
        if line in {"/quit", "/exit"}:
            return 0
        if is_farewell(line):  # "bye", "quit": the conversation ends as people end one
            console.print(GOODBYE)
            return 0
        if line == "/help":
            console.print(HELP)
            continue
        if line == "/evidence":
            evidence = not evidence
            console.print(f"evidence {'on' if evidence else 'off'}")
            continue
        if line == "/reset":
            thread = session.new_thread()
            console.print(f"new thread {thread}")
            continue
        if line == "/thread":
            # the page (`hexar web` on this recording's folder) continues it at #/run/NAME?thread=ID
            console.print(f"{safe(thread)}  (in `hexar web {safe(run.parent)}`: "
                          f"#/run/{safe(quote(run.name))}?thread={safe(quote(thread))})")
            continue
        if line.startswith("/task"):
            arg = line.removeprefix("/task").strip()
            if not arg:
                for t in log.tasks:
                    name = f'"{safe(t.instruction)}"' if not t.is_recovery else "(my own recovery task)"
                    console.print(f"  {t.order}. {safe(t.task_id)} {name} {safe(t.outcome)}")
                continue
            try:
                chosen = log.task(arg)
            except NoTaskError as e:
                console.print(f"[yellow]{safe(str(e))}[/yellow]")
                continue
            session.switch(thread, chosen.task_id)
            console.print(f"Switched to task {chosen.order}: {safe(describe(chosen, log))} "
                          "Ask me about it.")
            continue
        if line == "/why":
            line = "why?"
        reply = small_talk_reply(line)
        if reply is not None:  # "ok thanks": a reply, not a refusal
            console.print(reply)
            continue
        try:
            with progress.step("working out the answer"):
                result = session.ask(line, thread=thread)
        except USER_ERRORS as err:
            console.print(f"[yellow]{safe(err)}[/yellow]")
            continue
        except Exception as err:  # a bug in one answer must not end the conversation
            console.print(f"[red]internal error, please report it: {safe(type(err).__name__)}: {safe(err)}[/red]")
            continue
        if result["error"]:
            console.print(f"[yellow]{safe(result['error'])}[/yellow]")
            continue
        render_answer(console, result, evidence)


def describe(task: Task, log: EventLog) -> str:
    from hexar.agent.content import task_name
    from hexar.explainers.recorded import plan_words, sentence

    return sentence(f"{task_name(task, log)}, {task.outcome}; its plan: {plan_words(task)}")


def _reader(checkpoints: Path, console: Console) -> Callable[[], str]:
    """A prompt with history in a terminal; from a pipe, plain lines with one echoed prompt each (prompt_toolkit
    would warn that the input is not a terminal and draw its prompt twice)."""
    if not sys.stdin.isatty():
        def from_pipe() -> str:
            raw = sys.stdin.readline()
            if not raw:
                raise EOFError
            line = raw.strip()
            if line:
                console.print(f"you> {safe(line)}")
            return line

        return from_pipe
    from prompt_toolkit import PromptSession
    from prompt_toolkit.history import FileHistory

    prompt: PromptSession[str] = PromptSession(history=FileHistory(str(checkpoints.with_name("chat_history"))))
    return lambda: prompt.prompt("you> ").strip()
