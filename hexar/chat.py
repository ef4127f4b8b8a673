"""`hexar chat` (interactive) over one recording, and the answer panel `hexar ask` prints too."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.markup import escape
from rich.panel import Panel

from hexar.agent.context import RunSettings
from hexar.events.errors import NoTaskError
from hexar.events.log import EventLog
from hexar.events.tasks import Task
from hexar.render import clock

HELP = ("Ask why I did something. Commands: /task [ID] (switch or list tasks), /evidence (toggle evidence), "
        "/why (go deeper), /reset (new conversation), /thread (show its id), /help. Ctrl-D quits.")


def render_answer(console: Console, result: dict[str, Any], evidence: bool, verbose: bool = False) -> None:
    console.print(Panel(escape(result["answer"]), title="HEXAR", title_align="left", border_style="cyan"))
    if evidence:
        for ev in result["evidence"][:6]:
            console.print(f"  [dim]{clock(ev['t'])} {ev['topic']}[/dim]  {escape(ev['item'])}")
    if verbose:
        console.print(f"  [dim]route={result['route']} explainers={','.join(result['explainers'])} "
                      f"backend={result['backend']} causes={','.join(result['causes'])} "
                      f"total={result['timings_ms'].get('total')} ms[/dim]")


def chat(run: Path, thread: str | None, llm: str, console: Console, checkpoints: Path | None = None,
         phrase: bool | None = None) -> int:
    from hexar.agent.session import Session, default_checkpoints

    session = Session(RunSettings(recording=run, llm=llm, phrase=phrase),
                      checkpoints=checkpoints or default_checkpoints())
    thread = thread or session.new_thread()
    log = session.context.log
    task = log.task()
    console.print(f"[bold]{escape(run.name)}[/bold]: task \"{escape(task.instruction)}\" ({task.outcome}); "
                  f"backend {session.backend.name}; thread {thread}")
    for turn in session.history(thread):
        console.print(f"[dim]you: {escape(turn['question'])}\nHEXAR: {escape(turn['answer'])}[/dim]")
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
            console.print(thread)
            continue
        if line.startswith("/task"):
            arg = line.removeprefix("/task").strip()
            if not arg:
                for t in log.tasks:
                    name = f'"{escape(t.instruction)}"' if not t.is_recovery else "(my own recovery task)"
                    console.print(f"  {t.order}. {t.task_id} {name} {t.outcome}")
                continue
            try:
                chosen = log.task(arg)
            except NoTaskError as e:
                console.print(f"[yellow]{escape(str(e))}[/yellow]")
                continue
            session.switch(thread, chosen.task_id)
            console.print(f"Switched to task {chosen.order}: {escape(describe(chosen, log))}. "
                          "Ask me about it.")
            continue
        if line == "/why":
            line = "why?"
        result = session.ask(line, thread=thread)
        if result["error"]:
            console.print(f"[yellow]{escape(result['error'])}[/yellow]")
            continue
        render_answer(console, result, evidence)


def describe(task: Task, log: EventLog) -> str:
    from hexar.agent.content import task_name
    from hexar.explainers.recorded import plan_words

    return f"{task_name(task, log)}, {task.outcome}; its plan: {plan_words(task)}"


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
                console.print(f"you> {escape(line)}")
            return line

        return from_pipe
    from prompt_toolkit import PromptSession
    from prompt_toolkit.history import FileHistory

    prompt: PromptSession[str] = PromptSession(history=FileHistory(str(checkpoints.with_name("chat_history"))))
    return lambda: prompt.prompt("you> ").strip()
