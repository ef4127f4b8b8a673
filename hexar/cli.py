"""The `hexar` command line. Every command returns an exit code and reports bad input as one line."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.console import Console
from rich.table import Table

from hexar.errors import USER_ERRORS

app = typer.Typer(
    add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
    help="Ask a robot why it did what it did.",
)
out = Console(highlight=False)


def guarded(fn: Callable[[], int]) -> int:
    """Run a command body; a user error becomes `ERROR: ...` and exit code 2, never a traceback."""
    from hexar.safe_text import visible

    try:
        return fn()
    except USER_ERRORS as e:
        # the message may quote the recording (task ids, file names): never let it drive the terminal
        print(f"ERROR: {visible(e)}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130
    except Exception as e:  # the last guard: a bug reads as one line the user can report, not a traceback
        print(f"ERROR: internal error, please report it: {type(e).__name__}: {visible(e)}", file=sys.stderr)
        return 2


@app.command()
def simulate(
    out_dir: Annotated[Path, typer.Option("--out", help="folder for the 60 recordings")],
    storage: Annotated[str, typer.Option(help="sqlite3 or mcap")] = "sqlite3",
    seed: Annotated[int, typer.Option(help="changes timings and values, never the scenario")] = 0,
    scenario: Annotated[list[int] | None, typer.Option(help="only these scenarios (1-20)")] = None,
) -> None:
    """Write the paper's 20 scenarios x 3 variants as rosbag2 recordings of a simulated TIAGo."""

    def body() -> int:
        from hexar.errors import HexarError
        from hexar.evals.scenarios.suite import simulate_suite
        from hexar.inputs import output_dir

        if storage not in {"sqlite3", "mcap"}:
            raise HexarError(f"unknown storage {storage!r}: use sqlite3 or mcap")
        output_dir(out_dir, "--out")
        wanted = set(scenario or [])
        written = simulate_suite(out_dir, storage, seed,  # type: ignore[arg-type]
                                 only=(lambda s, v: s in wanted) if wanted else None)
        out.print(f"wrote {len(written)} recordings to {out_dir}")
        return 0

    raise typer.Exit(guarded(body))


@app.command()
def inspect(
    run: Annotated[Path, typer.Argument(help="a rosbag2 folder or ROS 1 .bag")],
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
) -> None:
    """Show a recording's topics, tasks, plans with per-skill status and times, and warnings."""

    def body() -> int:
        from hexar.events import read_recording
        from hexar.render import json_dumps, log_dict, print_inspection

        log = read_recording(run)
        if as_json:
            print(json_dumps(log_dict(log), indent=2))
        else:
            print_inspection(out, log)
        return 0

    raise typer.Exit(guarded(body))


@app.command()
def runs(folder: Annotated[Path, typer.Argument(help="a folder of recordings")],
         as_json: Annotated[bool, typer.Option("--json")] = False) -> None:
    """List the recordings in a folder with their latest task's outcome."""

    def body() -> int:
        from hexar.errors import HexarError
        from hexar.events import EventsError, read_recording
        from hexar.events.contract import TASK_INFO
        from hexar.safe_text import json_dumps, safe

        if not folder.is_dir():
            raise HexarError(f"not a folder: {folder}")
        rows: list[dict[str, Any]] = []
        for path in sorted(p for p in folder.iterdir() if p.is_dir() or p.suffix == ".bag"):
            try:
                log = read_recording(path, topics={TASK_INFO})
                task = log.task() if log.tasks else None
                rows.append({"recording": path.name, "instruction": task.instruction if task else "",
                             "outcome": task.outcome if task else "no task", "tasks": len(log.tasks)})
            except EventsError as e:
                rows.append({"recording": path.name, "instruction": "", "outcome": f"unreadable: {e}", "tasks": 0})
        if as_json:
            print(json_dumps(rows, indent=2))
            return 0
        table = Table("recording", "tasks", "latest task", "outcome")
        for r in rows:
            table.add_row(safe(r["recording"]), str(r["tasks"]), safe(r["instruction"]), safe(r["outcome"]))
        out.print(table)
        return 0

    raise typer.Exit(guarded(body))


@app.command()
def ask(
    run: Annotated[Path, typer.Argument(help="a rosbag2 folder or ROS 1 .bag")],
    question: Annotated[str | None, typer.Argument(help="the question, e.g. \"Why didn't you bring it?\"")] = None,
    questions: Annotated[Path | None, typer.Option(help="answer each line of this file as a new conversation")] = None,
    task: Annotated[str | None, typer.Option(help="task id, order number, 'first' or 'latest'")] = None,
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="auto, embedded, ollama[:model] or none")] = "auto",
    as_json: Annotated[bool, typer.Option("--json", help="print JSON")] = False,
    verbose: Annotated[bool, typer.Option("--verbose", "-v", help="show route, backend, evidence")] = False,
    phrase: Annotated[bool | None, typer.Option("--phrase/--no-phrase", help="let the LLM phrase answers "
                                                "(default: with Ollama yes, embedded no)")] = None,
) -> None:
    """Answer one question (or a file of questions) about a recorded run."""

    def body() -> int:
        from hexar.chat import ask as run_ask
        from hexar.errors import HexarError

        if question is None and questions is None:
            raise HexarError("give a question or --questions FILE")
        return run_ask(run, question, questions, task, llm, as_json, verbose, out, phrase)

    raise typer.Exit(guarded(body))


@app.command()
def chat(
    run: Annotated[Path, typer.Argument(help="a rosbag2 folder or ROS 1 .bag")],
    thread: Annotated[str | None, typer.Option(help="resume this conversation")] = None,
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="auto, embedded, ollama[:model] or none")] = "auto",
    checkpoints: Annotated[Path | None, typer.Option(help="SQLite file of conversations")] = None,
    phrase: Annotated[bool | None, typer.Option("--phrase/--no-phrase", help="let the LLM phrase answers")] = None,
) -> None:
    """Talk with the robot about a recorded run; follow-up questions keep the thread."""

    def body() -> int:
        from hexar.chat import chat as run_chat

        return run_chat(run, thread, llm, out, checkpoints, phrase)

    raise typer.Exit(guarded(body))


@app.command()
def listen(
    run: Annotated[Path, typer.Argument(help="a rosbag2 folder or ROS 1 .bag")],
    wav: Annotated[list[Path] | None, typer.Option("--wav", help="spoken questions from WAV files, in order")] = None,
    mic: Annotated[bool, typer.Option("--mic", help="listen on the default microphone (the default)")] = False,
    speak: Annotated[bool, typer.Option("--speak", help="say answers: robot TTS on a robot, else loudspeaker")] = False,
    out_dir: Annotated[Path | None, typer.Option("--out", help="write each answer as DIR/turn_NN.wav")] = None,
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="auto, embedded, ollama[:model] or none")] = "auto",
    thread: Annotated[str | None, typer.Option(help="resume this conversation (also from hexar chat)")] = None,
    checkpoints: Annotated[Path | None, typer.Option(help="SQLite file of conversations")] = None,
    vosk_model: Annotated[Path | None, typer.Option("--vosk-model", envvar="HEXAR_VOSK_MODEL",
                                                    help="recognise with this vosk model folder, not whisper")] = None,
    voice: Annotated[str, typer.Option(help="auto, robot, piper or espeak")] = "auto",
) -> None:
    """Talk with the robot: spoken questions in, short spoken answers out; follow-ups keep the thread."""

    def body() -> int:
        from hexar.voice.loop import listen as run_listen

        return run_listen(run, wavs=wav, mic=mic, speak=speak, out_dir=out_dir, llm=llm, thread=thread,
                          checkpoints=checkpoints, vosk_model=vosk_model, voice=voice, console=out)

    raise typer.Exit(guarded(body))


@app.command("eval")
def eval_(
    runs: Annotated[Path | None, typer.Option(help="folder of the 60 recordings, simulated there when missing "
                                              "[default: ~/.cache/hexar/eval-runs/seed-SEED]")] = None,
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="none, embedded, ollama[:model] or auto "
                                     "(default none: a full LLM run takes hours on a CPU)")] = "none",
    method: Annotated[list[str] | None, typer.Option(help="hexar, end-to-end, all-components [default: all]")] = None,
    scenario: Annotated[list[int] | None, typer.Option(help="only these scenarios (1-20)")] = None,
    module: Annotated[list[str] | None, typer.Option(
        help="only these modules: planning, navigation, ask_human_for_help, text_to_speech, pizza_recommender")] = None,
    kind: Annotated[list[str] | None, typer.Option(help="only these questions: generic, task, observed")] = None,
    first: Annotated[int | None, typer.Option(help="only the first N cases of each scenario")] = None,
    judge: Annotated[str | None, typer.Option(help="an LLM judge beside the graders, e.g. ollama:phi4")] = None,
    audit: Annotated[int, typer.Option(help="print N graded answers beside their grades")] = 0,
    out_dir: Annotated[Path, typer.Option("--out", help="folder for report.json, results.md and the figures")] = Path(
        "eval-out"),
    baseline: Annotated[Path | None, typer.Option(help="exit 1 on a regression against this baseline")] = None,
    write_baseline: Annotated[Path | None, typer.Option(help="write this run as a baseline file")] = None,
    tolerance: Annotated[float, typer.Option(help="allowed metric drop against the baseline (0.02 = 2 points)")] = 0.02,
    seed: Annotated[int, typer.Option(help="simulation seed of recordings that are missing")] = 0,
    resimulate: Annotated[bool, typer.Option(help="simulate the recordings again even if present")] = False,
    figures: Annotated[bool, typer.Option(help="draw the PNG figures")] = True,
) -> None:
    """Reproduce the paper's evaluation: 180 cases x HEXAR and both baselines, graded, tested, plotted."""

    def body() -> int:
        from hexar.evals.cli import EvalOptions, eval_command

        opts = EvalOptions(
            out=out_dir, runs=runs, llm=llm, methods=tuple(method or ()), scenarios=tuple(scenario or ()),
            modules=tuple(module or ()), kinds=tuple(kind or ()), first=first, judge=judge, audit=audit,
            baseline=baseline, write_baseline=write_baseline, tolerance=tolerance, seed=seed,
            resimulate=resimulate, figures=figures,
        )
        return eval_command(opts, out)

    raise typer.Exit(guarded(body))


def main(argv: list[str] | None = None) -> int:
    """Entry point; returns the exit code (usage errors: 2, bad input: 2, success: 0)."""
    try:
        app(args=argv)
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
