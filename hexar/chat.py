"""`hexar ask` (one-shot and batch) and `hexar chat` (interactive) over one recording."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from rich.console import Console
from rich.panel import Panel

from hexar.agent.context import RunSettings
from hexar.agent.errors import BadQuestionError
from hexar.agent.session import Session, default_checkpoints
from hexar.errors import USER_ERRORS
from hexar.inputs import read_text_arg
from hexar.render import clock
from hexar.safe_text import json_dumps, safe, visible

HELP = ("Ask why I did something. Commands: /task [ID] (switch or list tasks), /evidence (toggle evidence), "
        "/why (go deeper), /reset (new conversation), /thread (show its id), /help. Ctrl-D quits.")


def render_answer(console: Console, result: dict[str, Any], evidence: bool, verbose: bool = False) -> None:
    console.print(Panel(safe(result["answer"], keep_newlines=True), title="HEXAR", title_align="left",
                        border_style="cyan"))
    if evidence:
        for ev in result["evidence"][:6]:
            console.print(f"  [dim]{clock(ev['t'])} {safe(ev['topic'])}[/dim]  {safe(ev['item'])}")
    if verbose:
        console.print(safe(f"  route={result['route']} explainers={','.join(result['explainers'])} "
                           f"backend={result['backend']} causes={','.join(result['causes'])} "
                           f"total={result['timings_ms'].get('total')} ms"), style="dim")


def ask(run: Path, question: str | None, questions: Path | None, task: str | None, llm: str,
        as_json: bool, verbose: bool, console: Console, phrase: bool | None = None) -> int:
    # a bad questions file fails before the recording and the models load
    lines = [ln.strip() for ln in read_text_arg(questions, "--questions").splitlines()
             if ln.strip()] if questions is not None else []
    session = Session(RunSettings(recording=run, llm=llm, phrase=phrase))
    if questions is not None:
        worst = 0
        for line in lines:
            result = session.ask(line, task=task)
            worst = max(worst, 2 if result["error"] else 0)
            print(json_dumps(result) if as_json
                  else visible(result["answer"], keep_newlines=True) or f"ERROR: {visible(result['error'])}")
        return worst
    result = session.ask(question or "", task=task)
    if result["error"]:
        raise BadQuestionError(result["error"])
    if as_json:
        print(json_dumps(result, indent=2))
    else:
        render_answer(console, result, evidence=verbose, verbose=verbose)
    return 0


def chat(run: Path, thread: str | None, llm: str, console: Console, checkpoints: Path | None = None,
         phrase: bool | None = None) -> int:
    from prompt_toolkit import PromptSession
    from prompt_toolkit.history import FileHistory

    session = Session(RunSettings(recording=run, llm=llm, phrase=phrase),
                      checkpoints=checkpoints or default_checkpoints())
    thread = thread or session.new_thread()
    history_file = (checkpoints or default_checkpoints()).with_name("chat_history")
    prompt: PromptSession[str] = PromptSession(history=FileHistory(str(history_file)))
    log = session.context.log
    task = log.task()
    console.print(f"[bold]{safe(run.name)}[/bold]: task \"{safe(task.instruction)}\" ({safe(task.outcome)}); "
                  f"backend {safe(session.backend.name)}; thread {safe(thread)}")
    for turn in session.history(thread):
        console.print(f"[dim]you: {safe(turn['question'])}\nHEXAR: {safe(turn['answer'], keep_newlines=True)}[/dim]")
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
            console.print(safe(thread))
            continue
        if line.startswith("/task"):
            arg = line.removeprefix("/task").strip()
            if not arg:
                for t in log.tasks:
                    console.print(f"  {t.order}. {safe(t.task_id)} \"{safe(t.instruction or '(recovery)')}\" "
                                  f"{safe(t.outcome)}")
                continue
            try:
                log.task(arg)
            except USER_ERRORS as err:  # an unknown task is a typo, not the end of the conversation
                console.print(f"[yellow]{safe(err)}[/yellow]")
                continue
            task_ref = arg
            line = "What happened?"
        if line == "/why":
            line = "why?"
        try:
            result = session.ask(line, thread=thread, task=task_ref)
        except USER_ERRORS as err:
            console.print(f"[yellow]{safe(err)}[/yellow]")
            continue
        except Exception as err:  # a bug in one answer must not end the conversation
            console.print(f"[red]internal error, please report it: {safe(type(err).__name__)}: {safe(err)}[/red]")
            continue
        finally:
            task_ref = None
        if result["error"]:
            console.print(f"[yellow]{safe(result['error'])}[/yellow]")
            continue
        render_answer(console, result, evidence)
