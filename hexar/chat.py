"""`hexar chat` (interactive) over one recording, and the answer panel `hexar ask` prints too."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from rich.console import Console
from rich.markup import escape
from rich.panel import Panel

from hexar.agent.context import RunSettings
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
    from prompt_toolkit import PromptSession
    from prompt_toolkit.history import FileHistory

    from hexar.agent.session import Session, default_checkpoints

    session = Session(RunSettings(recording=run, llm=llm, phrase=phrase),
                      checkpoints=checkpoints or default_checkpoints())
    thread = thread or session.new_thread()
    history_file = (checkpoints or default_checkpoints()).with_name("chat_history")
    prompt: PromptSession[str] = PromptSession(history=FileHistory(str(history_file)))
    log = session.context.log
    task = log.task()
    console.print(f"[bold]{run.name}[/bold]: task \"{task.instruction}\" ({task.outcome}); "
                  f"backend {session.backend.name}; thread {thread}")
    for turn in session.history(thread):
        console.print(f"[dim]you: {turn['question']}\nHEXAR: {turn['answer']}[/dim]")
    console.print(f"[dim]{HELP}[/dim]")
    evidence = False
    task_ref: str | None = None
    while True:
        try:
            line = prompt.prompt("you> ").strip()
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
            thread, task_ref = session.new_thread(), None
            console.print(f"new thread {thread}")
            continue
        if line == "/thread":
            console.print(thread)
            continue
        if line.startswith("/task"):
            arg = line.removeprefix("/task").strip()
            if not arg:
                for t in log.tasks:
                    console.print(f"  {t.order}. {t.task_id} \"{t.instruction or '(recovery)'}\" {t.outcome}")
                continue
            task_ref = arg
            line = "What happened?"
        if line == "/why":
            line = "why?"
        result = session.ask(line, thread=thread, task=task_ref)
        task_ref = None
        if result["error"]:
            console.print(f"[yellow]{result['error']}[/yellow]")
            continue
        render_answer(console, result, evidence)
