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
    except BrokenPipeError:
        # the reader went away (`hexar inspect RUN --json | head -2`): what it wanted was written; stop quietly,
        # and point stdout at nothing so the interpreter's final flush does not raise again
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0
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


@app.command()
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


@app.command()
def runs(folder: Annotated[Path, typer.Argument(help="a folder of recordings")],
         as_json: Annotated[bool, typer.Option("--json")] = False) -> None:
    """List the recordings in a folder with their latest task's outcome."""

    def body() -> int:
        from hexar.errors import HexarError
        from hexar.events import EventsError, read_tasks
        from hexar.safe_text import clip, json_dumps, safe

        if not folder.is_dir():
            raise HexarError(f"not a folder: {folder}")
        from hexar.render import natural_key

        rows: list[dict[str, Any]] = []
        from hexar.web.pagedata import verdict
        from hexar.workspace import is_recording

        # only what holds a recording: a folder of other things (a virtualenv, notes) is no unreadable recording
        paths = sorted((p for p in folder.iterdir() if is_recording(p)), key=natural_key)
        if not paths and not as_json:
            out.print(f"No recordings in {folder}: record one, or write the simulated suite with "
                      "`hexar simulate --out FOLDER`.")
            return 0
        for path in paths:
            try:
                log = read_tasks(path)
                task = log.task() if log.tasks else None
                rows.append({"recording": path.name, "instruction": task.instruction if task else "",
                             "outcome": task.outcome if task else "no task", "tasks": len(log.tasks),
                             "derived_from_nav2": bool(task and task.derived),
                             # "wrong plan": it succeeded as the robot counts it, on a plan that missed the request
                             "verdict": verdict(task) if task else "no task",
                             "recovered": any(w.startswith("recovered:") for w in log.warnings)})
            except EventsError as e:
                rows.append({"recording": path.name, "instruction": "", "outcome": f"unreadable: {e}", "tasks": 0})
        if as_json:
            print(json_dumps(rows, indent=2))
            return 0
        table = Table("recording", "tasks", "latest task", "outcome")
        for r in rows:
            shown = r.get("verdict", r["outcome"]) + (" (recovered)" if r.get("recovered") else "")
            table.add_row(safe(r["recording"]), str(r["tasks"]), safe(clip(r["instruction"])), safe(clip(shown)))
        out.print(table)
        return 0

    raise typer.Exit(guarded(body))


@app.command()
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


@app.command()
def chat(
    run: Annotated[Path | None, typer.Argument(help="a rosbag2 folder or ROS 1 .bag")] = None,
    thread: Annotated[str | None, typer.Option(help="resume this conversation")] = None,
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="auto, embedded, ollama[:model] or none")] = "auto",
    checkpoints: Annotated[Path | None, typer.Option(help="SQLite file of conversations")] = None,
    phrase: Annotated[bool | None, typer.Option("--phrase/--no-phrase", help="let the LLM phrase answers")] = None,
    live: Annotated[bool, typer.Option("--live", help="talk with a running `hexar serve` (DDS) instead")] = False,
    domain: Annotated[int | None, typer.Option(help="with --live: DDS domain id [default: ROS_DOMAIN_ID or 0]")] = None,
) -> None:
    """Talk with the robot about a recorded run; follow-up questions keep the thread."""

    def body() -> int:
        from hexar.chat import chat as run_chat
        from hexar.errors import HexarError
        from hexar.inputs import checkpoints_file

        if live:
            from hexar.live.commands import chat_live_command

            return chat_live_command(domain, out)
        if run is None:
            raise HexarError("give a recording, or --live to talk with a running hexar serve")
        checkpoints_file(checkpoints)
        return run_chat(run, thread, llm, out, checkpoints, phrase)

    raise typer.Exit(guarded(body))


@app.command()
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


@app.command()
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
) -> None:
    """Serve a page of the runs: timeline, path, evidence and a chat with the robot."""

    def body() -> int:
        from hexar.inputs import checkpoints_file, port_number
        from hexar.web.server import serve

        port_number(port, lowest=0)  # 0: any free port; the page's address line names the one it got
        checkpoints_file(checkpoints)
        return serve(folder, host, port, llm, checkpoints, live, domain, launch_log)

    raise typer.Exit(guarded(body))


@app.command()
def listen(
    run: Annotated[Path, typer.Argument(help="a rosbag2 folder or ROS 1 .bag")],
    wav: Annotated[list[Path] | None, typer.Option("--wav", help="spoken questions from WAV files, in order")] = None,
    more_wavs: Annotated[list[Path] | None, typer.Argument(help="more WAV files after --wav FILE", show_default=False,
                                                           metavar="[WAV]...")] = None,
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
        from hexar.errors import HexarError
        from hexar.inputs import checkpoints_file
        from hexar.voice.loop import listen as run_listen

        if more_wavs and not wav:
            raise HexarError(f"unexpected argument {more_wavs[0]}: give WAV files after --wav")
        checkpoints_file(checkpoints)
        return run_listen(run, wavs=[*(wav or []), *(more_wavs or [])], mic=mic, speak=speak, out_dir=out_dir,
                          llm=llm, thread=thread, checkpoints=checkpoints, vosk_model=vosk_model,
                          voice=voice, console=out)

    raise typer.Exit(guarded(body))


@app.command()
def serve(
    transport: Annotated[str, typer.Option(help="auto (rclpy if importable), rclpy or dds")] = "auto",
    domain: Annotated[int | None, typer.Option(help="DDS domain id [default: ROS_DOMAIN_ID or 0]")] = None,
    proactive: Annotated[str, typer.Option(help="on a failure: off, publish (on /hexar/answer) or speak (said aloud "
                                           "two at once, then one every --speak-every seconds; all published)"
                                           )] = "publish",
    speak_every: Annotated[float, typer.Option(help="with --proactive speak: say at most one unasked explanation "
                                               "every this many seconds after the first two; 0 says each")] = 10.0,
    mic: Annotated[bool, typer.Option("--mic", help="also take spoken questions from the microphone")] = False,
    wav: Annotated[list[Path] | None, typer.Option("--wav", help="spoken questions from WAV files, in order")] = None,
    tts_topic: Annotated[str | None, typer.Option(help="speak on this std_msgs/String topic (robot TTS)")] = None,
    voice: Annotated[str, typer.Option(help="auto, robot, piper, espeak or none")] = "auto",
    out_dir: Annotated[Path | None, typer.Option("--out", help="also write spoken answers as WAVs here")] = None,
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="none, auto, embedded or ollama[:model]")] = "none",
    duration: Annotated[float | None, typer.Option(help="stop after this many seconds")] = None,
    keep_tasks: Annotated[int, typer.Option(help="keep the current task and this many earlier ones")] = 5,
    horizon: Annotated[float, typer.Option(help="keep this many seconds of robot traffic")] = 900.0,
    quiet: Annotated[bool, typer.Option("--quiet", help="do not print the answers")] = False,
    record: Annotated[Path | None, typer.Option(help="keep a rolling rosbag2 recording of the traffic here")] = None,
    launch_log: Annotated[Path | None, typer.Option(help="follow the newest launch.log in this folder of launch's log "
                                                    "folders [default: ROS_LOG_DIR, else ROS_HOME/log, else "
                                                    "~/.ros/log, when it exists]")] = None,
    follow_launch_log: Annotated[bool, typer.Option(help="read launch's log on this computer (process deaths, "
                                                    "stderr)")] = True,
) -> None:
    """Listen to a running robot: explain failures as they happen, answer questions on /hexar/question."""

    def body() -> int:
        from hexar.live.commands import ServeOptions
        from hexar.live.commands import serve as run_serve

        return run_serve(ServeOptions(
            transport=transport, domain=domain, llm=llm, proactive=proactive, tts_topic=tts_topic, voice=voice,
            mic=mic, wavs=list(wav or []), out_dir=out_dir, duration_s=duration, keep_tasks=keep_tasks,
            horizon_s=horizon, quiet=quiet, record=record, launch_log=launch_log,
            follow_launch_log=follow_launch_log, speak_every_s=speak_every))

    raise typer.Exit(guarded(body))


@app.command()
def replay(
    run: Annotated[Path, typer.Argument(help="a rosbag2 folder or ROS 1 .bag")],
    rate: Annotated[float, typer.Option(help="playback speed, 10 = ten times faster")] = 1.0,
    transport: Annotated[str, typer.Option(help="auto (rclpy if importable), rclpy or dds")] = "auto",
    domain: Annotated[int | None, typer.Option(help="DDS domain id [default: ROS_DOMAIN_ID or 0]")] = None,
    start: Annotated[float, typer.Option(help="skip this many seconds of the recording")] = 0.0,
    clock: Annotated[float, typer.Option(help="also publish the recording's time on /clock at this rate (Hz), "
                                              "like `ros2 bag play --clock`; 0: no /clock")] = 0.0,
) -> None:
    """Publish a recording onto the live topics, like `ros2 bag play`."""

    def body() -> int:
        from hexar.live.commands import replay_command

        return replay_command(run, rate, transport, domain, start, clock)

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
    suite: Annotated[str, typer.Option(help="paper (the 180 cases), real-nav2 (real Nav2 logs from public "
                                       "threads), real-nav2-heldout (threads never tuned on), real-nav2-blind, "
                                       "real-nav2-blind2 ... -blind29 (blind sets), real-modules, "
                                       "real-modules-heldout, -heldout2 ... -heldout36 (MoveIt 2, "
                                       "ros2_control, bring-up); the real-nav2 "
                                       "suites use --out, --runs, --llm, --baseline, --write-baseline, "
                                       "--tolerance")] = "paper",
    cases: Annotated[Path | None, typer.Option(help="your own excerpts, a YAML file in the format of the "
                                               "real-nav2 or real-modules data (their README.md), run with "
                                               "--suite real-nav2 or --suite real-modules")] = None,
) -> None:
    """Reproduce the paper's evaluation: 180 cases x HEXAR and both baselines, graded, tested, plotted."""

    def body() -> int:
        if suite.startswith("real-modules"):
            from hexar.evals.real_modules_cli import real_modules_main

            return real_modules_main(suite, out_dir, runs, llm, out,
                                     others={"--method": method, "--scenario": scenario, "--module": module,
                                             "--kind": kind, "--first": first, "--judge": judge,
                                             "--audit": audit or None, "--baseline": baseline,
                                             "--write-baseline": write_baseline}, cases=cases)
        if suite != "paper":
            from hexar.evals.real_nav2_cli import real_nav2_main

            return real_nav2_main(suite, out_dir, runs, llm, baseline, write_baseline, tolerance, out,
                                  paper_only={"--method": method, "--scenario": scenario, "--module": module,
                                              "--kind": kind, "--first": first, "--judge": judge,
                                              "--audit": audit or None}, cases=cases)
        from hexar.errors import HexarError
        from hexar.evals.cli import EvalOptions, eval_command

        if cases is not None:
            raise HexarError("--cases goes with --suite real-nav2 or --suite real-modules, not the paper's suite")
        opts = EvalOptions(
            out=out_dir, runs=runs, llm=llm, methods=tuple(method or ()), scenarios=tuple(scenario or ()),
            modules=tuple(module or ()), kinds=tuple(kind or ()), first=first, judge=judge, audit=audit,
            baseline=baseline, write_baseline=write_baseline, tolerance=tolerance, seed=seed,
            resimulate=resimulate, figures=figures,
        )
        return eval_command(opts, out)

    raise typer.Exit(guarded(body))


@app.command()
def mcp(
    folder: Annotated[Path, typer.Argument(help="serve the recordings under this folder (read-only)")] = Path("."),
    http: Annotated[bool, typer.Option("--http", help="streamable HTTP instead of stdio")] = False,
    port: Annotated[int, typer.Option(help="HTTP port")] = 8000,
    host: Annotated[str, typer.Option(help="HTTP address to listen on")] = "127.0.0.1",
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="the `ask` tool's LLM: auto, embedded, "
                                     "ollama[:model] or none")] = "auto",
    explainers: Annotated[Path | None, typer.Option(help="a modules.toml registering more explainers")] = None,
    token: Annotated[str | None, typer.Option(envvar="HEXAR_MCP_TOKEN", help="with --http: every request must "
                                              "send Authorization: Bearer TOKEN (required off loopback)")] = None,
) -> None:
    """Serve HEXAR's explainers to any MCP client (Claude Desktop, the mcp inspector): stdio or HTTP."""

    def body() -> int:
        from hexar.inputs import port_number
        from hexar.tools.mcp_server import serve

        if http:
            port_number(port)
        return serve(folder, http, port, host, llm, explainers, token)

    raise typer.Exit(guarded(body))


@app.command()
def triage(
    inputs: Annotated[list[str] | None, typer.Argument(help="folders (nested by robot/date) or globs of recordings")]
    = None,
    out_dir: Annotated[Path, typer.Option("--out", help="results, tables, report, figures")] = Path("triage-out"),
    workers: Annotated[int | None, typer.Option(help="processes [default: the machine's cores]")] = None,
    ray: Annotated[bool, typer.Option("--ray", help="run as Ray tasks, on a local Ray instance unless an address "
                                      "follows (--ray auto, --ray ray://host:10001)")] = False,
    ray_address: Annotated[str | None, typer.Option(help="the Ray cluster to run on (implies --ray)")] = None,
    compare: Annotated[tuple[str, str] | None, typer.Option(help="compare two triage outputs or two day ranges "
                                                            "(YYYY-MM-DD[..YYYY-MM-DD]) of --out")] = None,
    figures: Annotated[bool, typer.Option(help="draw the PNG figures")] = True,
) -> None:
    """Explain every task of many recordings without an LLM: tables, a report of causes, resumable, or on Ray."""

    def body() -> int:
        from hexar.errors import HexarError

        if compare is not None:
            from hexar.fleet.compare import compare as run_compare
            from hexar.fleet.compare import compare_markdown

            text = compare_markdown(run_compare(compare[0], compare[1], out_dir))
            print(text)
            return 0
        if not inputs:
            raise HexarError("give folders or globs of recordings, or --compare A B")
        from hexar.fleet.command import TriageOptions, ray_target, triage_command

        given, where = ray_target(inputs, ray, ray_address)
        if not given:
            raise HexarError("give folders or globs of recordings, or --compare A B")
        return triage_command(TriageOptions(tuple(given), out_dir, workers, where, figures), out)

    raise typer.Exit(guarded(body))


def release_ros_start_mark() -> None:
    """Undo scripts/hexar_ros_lazy.pth's mark, so a Python program that hexar starts (a worker, a robot stand-in)
    runs the ROS wheels' bootstrap as usual; this process re-executes itself if it comes to need rclpy."""
    import os

    if os.environ.pop("_HEXAR_ROS_LAZY", None):
        os.environ.pop("_ROS_WHEELS_BOOTSTRAP_COMPLETE", None)


def main(argv: list[str] | None = None) -> int:
    """Entry point; returns the exit code (usage errors: 2, bad input: 2, success: 0)."""
    release_ros_start_mark()
    try:
        app(args=argv)
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
