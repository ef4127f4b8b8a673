"""The commands over recordings: `simulate`, `inspect`, `runs`, `ask`, `chat`, `annotate` and `web` (their typer
signatures; the bodies import what they need when they run)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Column, Table

from hexar.cli_guard import guarded, out


def simulate(
    out_dir: Annotated[Path, typer.Option("--out", help="folder for the 60 recordings")],
    storage: Annotated[str, typer.Option(help="sqlite3 or mcap")] = "sqlite3",
    seed: Annotated[int, typer.Option(help="changes timings and values, never the scenario")] = 0,
    scenario: Annotated[list[int] | None, typer.Option(help="only these scenarios (1-20)")] = None,
    arm: Annotated[bool, typer.Option("--arm", help="write the arm's fetch recordings instead (pick and place "
                                      "with MoveIt 2 and ros2_control; not among the paper's 20)")] = False,
) -> None:
    """Write the paper's 20 scenarios x 3 variants as rosbag2 recordings of a simulated TIAGo."""

    def body() -> int:
        from hexar.errors import BadOptionValueError, HexarError
        from hexar.evals.scenarios.suite import simulate_suite
        from hexar.inputs import output_dir

        if storage not in {"sqlite3", "mcap"}:
            raise HexarError(f"unknown storage {storage!r}: use sqlite3 or mcap")
        unknown = sorted(n for n in set(scenario or []) if not 1 <= n <= 20)
        if unknown:
            raise BadOptionValueError(f"--scenario {unknown[0]} is none of the paper's scenarios (1-20)")
        output_dir(out_dir, "--out")
        if arm:
            from hexar.evals.scenarios.arm import simulate_arm_suite

            if scenario:
                raise HexarError("--scenario names the paper's scenarios; --arm writes the arm's recordings")
            written = simulate_arm_suite(out_dir, storage, seed)  # type: ignore[arg-type]
            out.print(f"wrote {len(written)} recordings to {out_dir}")
            return 0
        wanted = set(scenario or [])
        written = simulate_suite(out_dir, storage, seed,  # type: ignore[arg-type]
                                 only=(lambda s, v: s in wanted) if wanted else None)
        out.print(f"wrote {len(written)} recordings to {out_dir}")
        return 0

    raise typer.Exit(guarded(body))


def inspect(
    run: Annotated[Path, typer.Argument(help="a rosbag2 folder or ROS 1 .bag")],
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    plot: Annotated[Path | None, typer.Option(help="also draw the latest task's path/timeline figure (PNG)")] = None,
) -> None:
    """Show a recording's topics, tasks, plans with per-skill status and times, and warnings."""

    def body() -> int:
        from hexar.events import read_recording
        from hexar.render import json_dumps, log_dict, print_inspection
        from hexar.safe_text import visible

        if plot is not None:
            from hexar.web.explain import plot_latest

            plot_latest(run, plot)
            print(f"wrote the figure of the latest task to {visible(plot)}", file=sys.stderr)
        log = read_recording(run)
        if as_json:
            print(json_dumps(log_dict(log), indent=2))
        else:
            print_inspection(out, log)
        return 0

    raise typer.Exit(guarded(body))


def runs(folder: Annotated[Path, typer.Argument(help="a folder of recordings (nested at any depth), or one recording")],
         as_json: Annotated[bool, typer.Option("--json")] = False) -> None:
    """List the recordings in a folder with their latest task's outcome."""

    def body() -> int:
        from hexar.errors import HexarError
        from hexar.events import EventsError, read_tasks
        from hexar.safe_text import clip, json_dumps, safe
        from hexar.web.pagedata import verdict
        from hexar.workspace import is_recording, recording_name, recordings_under

        if not folder.is_dir() and not is_recording(folder):
            raise HexarError(f"not a folder: {folder}")
        # only what holds a recording: a folder of other things (a virtualenv, notes) is no unreadable recording
        paths = recordings_under(folder)
        if not paths and not as_json:
            out.print(f"No recordings in {folder}: record one, or write the simulated suite with "
                      "`hexar simulate --out FOLDER`.")
            return 0
        rows: list[dict[str, Any]] = []
        for path in paths:
            name = recording_name(folder, path)
            try:
                log = read_tasks(path)
                task = log.task() if log.tasks else None
                rows.append({"recording": name, "instruction": task.instruction if task else "",
                             "outcome": task.outcome if task else "no task", "tasks": len(log.tasks),
                             "derived_from_nav2": bool(task and task.derived),
                             # "wrong plan": it succeeded as the robot counts it, on a plan that missed the request
                             "verdict": verdict(task) if task else "no task",
                             "recovered": any(w.startswith("recovered:") for w in log.warnings)})
            except EventsError as e:
                rows.append({"recording": name, "instruction": "", "outcome": f"unreadable: {e}", "tasks": 0})
        if as_json:
            print(json_dumps(rows, indent=2))
            return 0
        # the name is what `hexar ask` takes next: folded onto a second line, never cut short
        outcomes = [r.get("verdict", r["outcome"]) + (" (recovered)" if r.get("recovered") else "") for r in rows]
        short = max(len(r["recording"]) for r in rows) <= 40  # else folded onto more lines, never cut
        table = Table(Column("recording", no_wrap=short, overflow="fold"), Column("tasks", no_wrap=True),
                      "latest task", "outcome")
        for r, shown in zip(rows, outcomes, strict=True):
            table.add_row(safe(r["recording"]), str(r["tasks"]), safe(clip(r["instruction"])), safe(clip(shown)))
        out.print(table)
        return 0

    raise typer.Exit(guarded(body))


def ask(
    targets: Annotated[list[str], typer.Argument(
        metavar="RUN... [QUESTION]",
        help="one or more recordings (rosbag2 folders or ROS 1 .bag), then the question, e.g. \"Why didn't you "
             "bring it?\" (no question with --questions)")],
    questions: Annotated[Path | None, typer.Option(help="answer each line of this file as a new conversation")] = None,
    runs: Annotated[Path | None, typer.Option("--runs", help="also ask every recording in this folder")] = None,
    task: Annotated[str | None, typer.Option(help="task id, order number, 'first' or 'latest'")] = None,
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="auto, embedded, ollama[:model] or none")] = "auto",
    as_json: Annotated[bool, typer.Option("--json", help="print JSON (one object per line in a batch)")] = False,
    verbose: Annotated[bool, typer.Option("--verbose", "-v", help="show route, backend, evidence")] = False,
    phrase: Annotated[bool | None, typer.Option("--phrase/--no-phrase", help="let the LLM phrase answers "
                                                "(default: with Ollama yes, embedded no)")] = None,
    plot: Annotated[Path | None, typer.Option(help="also draw the task's path/timeline figure (PNG)")] = None,
) -> None:
    """Answer a question (or a file of questions) about one or many recorded runs, starting up once."""

    def body() -> int:
        from hexar.ask_cmd import ask as run_ask
        from hexar.errors import HexarError

        if plot is not None and questions is not None:
            raise HexarError("--plot draws one answer: give one question, not --questions")
        return run_ask(targets, questions, runs, task, llm, as_json, verbose, out, phrase, plot)

    raise typer.Exit(guarded(body))


def chat(
    run: Annotated[Path | None, typer.Argument(help="a rosbag2 folder or ROS 1 .bag")] = None,
    thread: Annotated[str | None, typer.Option(help="resume this conversation")] = None,
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="auto, embedded, ollama[:model] or none")] = "auto",
    checkpoints: Annotated[Path | None, typer.Option(help="SQLite file of conversations")] = None,
    phrase: Annotated[bool | None, typer.Option("--phrase/--no-phrase", help="let the LLM phrase answers")] = None,
    live: Annotated[bool, typer.Option("--live", help="talk with a running `hexar serve` (DDS) instead")] = False,
    domain: Annotated[int | None, typer.Option(help="with --live: DDS domain id [default: ROS_DOMAIN_ID or 0]")] = None,
    transport: Annotated[str, typer.Option(help="with --live: auto (dds if cyclonedds is installed), dds or rclpy")
                         ] = "auto",
) -> None:
    """Talk with the robot about a recorded run; follow-up questions keep the thread."""

    def body() -> int:
        from hexar.chat import chat as run_chat
        from hexar.errors import HexarError
        from hexar.inputs import checkpoints_file

        if live:
            from hexar.live.commands import chat_live_command

            return chat_live_command(domain, out, transport)
        if transport != "auto":
            raise HexarError("--transport needs --live (it picks how the chat reaches hexar serve)")
        if run is None:
            raise HexarError("give a recording, or --live to talk with a running hexar serve")
        checkpoints_file(checkpoints)
        return run_chat(run, thread, llm, out, checkpoints, phrase)

    raise typer.Exit(guarded(body))


def annotate(
    run: Annotated[Path, typer.Argument(help="a rosbag2 folder (sqlite3 or mcap)")],
    out_file: Annotated[Path, typer.Option("--out", help="the MCAP file to write")],
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="auto, embedded, ollama[:model] or none")] = "auto",
) -> None:
    """Copy a recording to MCAP with HEXAR's explanations on /hexar/explanations and /hexar/log."""

    def body() -> int:
        from hexar.web.annotate import annotate as run_annotate

        n = run_annotate(run, out_file, llm)
        out.print(f"wrote {out_file} with {n} explanation{'s' if n != 1 else ''}")
        return 0

    raise typer.Exit(guarded(body))


def web(
    folder: Annotated[Path | None, typer.Argument(help="a folder of recordings (default: here, or none with --live)")
                      ] = None,
    host: Annotated[str, typer.Option(help="address to listen on (loopback by default)")] = "127.0.0.1",
    port: Annotated[int, typer.Option(help="port to listen on")] = 8080,
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="auto, embedded, ollama[:model] or none")] = "auto",
    checkpoints: Annotated[Path | None, typer.Option(help="SQLite file of conversations (shared with hexar chat)")
                           ] = None,
    live: Annotated[bool, typer.Option("--live", help="also follow the robot over DDS (read-only)")] = False,
    domain: Annotated[int | None, typer.Option(help="DDS domain with --live (default: ROS_DOMAIN_ID, else 0)")
                      ] = None,
    launch_log: Annotated[Path | None, typer.Option(help="with --live, follow the newest launch.log in this folder of "
                                                    "launch's log folders [default: ROS_LOG_DIR, else ROS_HOME/log, "
                                                    "else ~/.ros/log, when it exists]")] = None,
    transport: Annotated[str, typer.Option(help="with --live: auto (dds if cyclonedds is installed), dds or rclpy")
                         ] = "auto",
) -> None:
    """Serve a page of the runs: timeline, path, evidence and a chat with the robot."""

    def body() -> int:
        from hexar.inputs import checkpoints_file, port_number
        from hexar.web.server import serve

        port_number(port, lowest=0)  # 0: any free port; the page's address line names the one it got
        checkpoints_file(checkpoints)
        return serve(folder, host, port, llm, checkpoints, live, domain, launch_log, transport)

    raise typer.Exit(guarded(body))

