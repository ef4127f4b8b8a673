"""The bodies of `hexar serve` and `hexar replay` (hexar/cli_robot.py holds only their typer signatures)."""

from __future__ import annotations

import os
import signal
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

from hexar.live.errors import BadOptionError
from hexar.live.node import NodeOptions, Proactive, Transport
from hexar.safe_text import json_dumps, safe

TRANSPORTS = ("auto", "dds", "rclpy")
PROACTIVE = ("off", "publish", "speak")
VOICES = ("auto", "robot", "piper", "espeak", "none")

if TYPE_CHECKING:
    from hexar.live.launch_log import LaunchLogFollower


def domain_id(value: int | None) -> int:
    """--domain, else ROS_DOMAIN_ID (what ROS 2 nodes on the robot use), else 0."""
    if value is not None:
        return value
    env = os.environ.get("ROS_DOMAIN_ID", "").strip()
    if not env:
        return 0
    if not env.isdigit():
        raise BadOptionError(f"ROS_DOMAIN_ID={env!r} is not a number")
    return int(env)


def dds_available() -> bool:
    """Whether the cyclonedds binding is installed (CPython 3.14 has no wheel of it)."""
    from hexar.live.ros import importable

    return importable("cyclonedds")


def pick_transport(kind: str, prefer: str = "rclpy") -> str:
    """The transport for --transport `kind`; `auto` is `prefer` where it is installed, else the other one.
    `hexar serve` prefers rclpy (a node the ROS graph lists); the page and the live chat prefer DDS, where they
    create no endpoint beyond their own, and use rclpy where cyclonedds is missing."""
    if kind not in TRANSPORTS:
        raise BadOptionError(f"unknown transport {kind!r}: use auto, dds or rclpy")
    if kind != "auto":
        return kind
    from hexar.live.ros import rclpy_available

    have = {"rclpy": rclpy_available(), "dds": dds_available()}
    other = "dds" if prefer == "rclpy" else "rclpy"
    return prefer if have[prefer] or not have[other] else other


def make_transport(kind: str, domain: int | None, tts_topic: str | None, record: Path | None = None) -> Transport:
    if tts_topic is not None and not tts_topic.startswith("/"):
        raise BadOptionError(f"--tts-topic must be an absolute ROS topic such as /tts_text, not {tts_topic!r}")
    chosen, domain = pick_transport(kind), domain_id(domain)
    recorder = None
    if record is not None:
        from hexar.live.recorder import RollingRecorder

        recorder = RollingRecorder(record)
    if chosen == "rclpy":
        from hexar.live.ros import RclpyTransport

        return RclpyTransport(domain, tts_topic=tts_topic, recorder=recorder)
    from hexar.live.dds import DdsTransport

    return DdsTransport(domain, tts_topic=tts_topic, recorder=recorder)


@dataclass
class ServeOptions:
    transport: str = "auto"
    domain: int | None = None
    llm: str = "none"
    proactive: str = "publish"
    tts_topic: str | None = None
    voice: str = "auto"
    mic: bool = False
    wavs: list[Path] = field(default_factory=list)
    out_dir: Path | None = None
    vosk_model: Path | None = None
    duration_s: float | None = None
    keep_tasks: int = 5
    horizon_s: float = 900.0
    quiet: bool = False
    record: Path | None = None
    # launch's log folders on this computer (live/launch_log.py); None: where launch writes them, if it exists
    launch_log: Path | None = None
    follow_launch_log: bool = True
    # with proactive speak: one unasked explanation said every this many seconds at most, after two at once; 0: each
    speak_every_s: float = 10.0


def serve(opts: ServeOptions) -> int:
    """Run the node until Ctrl-C (or `duration_s`); answers are also printed, one JSON line each."""
    if opts.proactive not in PROACTIVE:
        raise BadOptionError(f"unknown --proactive {opts.proactive!r}: use off, publish or speak")
    if opts.voice not in VOICES:
        raise BadOptionError(f"unknown --voice {opts.voice!r}: use {', '.join(VOICES)}")
    if opts.mic and opts.wavs:
        raise BadOptionError("give --mic or --wav FILE..., not both")
    if opts.keep_tasks < 1 or not opts.horizon_s > 0:  # also nan
        raise BadOptionError("--keep-tasks must be at least 1 and --horizon above 0")
    if opts.duration_s is not None and not opts.duration_s > 0:
        raise BadOptionError(f"--duration must be above 0 seconds, not {opts.duration_s}")
    if not 0 <= opts.speak_every_s < float("inf"):  # also nan
        raise BadOptionError(f"--speak-every must be 0 (say each) or more seconds, not {opts.speak_every_s}")
    ears_wanted = opts.mic or bool(opts.wavs)
    from hexar.live.stacks import stacks_on_request

    # handlers before the node exists: a signal during start-up still ends it through node.stop()
    with stacks_on_request(), _stop_on_signals() as stop:
        return _run(opts, stop, ears_wanted)


def _run(opts: ServeOptions, stop: threading.Event, ears_wanted: bool) -> int:
    from hexar.live.limits import Limits
    from hexar.live.log import LiveLog
    from hexar.live.node import LiveNode
    from hexar.live.speech import Ears, make_speakers

    transport = make_transport(opts.transport, opts.domain, opts.tts_topic, opts.record)
    node: LiveNode | None = None
    try:
        speakers = make_speakers(transport, opts.tts_topic, opts.voice, opts.out_dir,
                                 need_voice=ears_wanted or opts.proactive == "speak")
        log = LiveLog(Limits(keep_tasks=opts.keep_tasks, horizon_s=opts.horizon_s), name=f"live:{transport.name}")
        printed = threading.Lock()

        def show(result: dict[str, Any]) -> None:
            if not opts.quiet:
                with printed:
                    print(json_dumps(result), flush=True)

        proactive = cast(Proactive, opts.proactive)
        options = NodeOptions(llm=opts.llm, proactive=proactive, speak_every_s=opts.speak_every_s)
        node = LiveNode(transport, log, options, speakers=speakers, on_answer=show)
        ears = Ears(node.ask, opts.wavs, opts.mic, opts.vosk_model) if ears_wanted else None
        node.start()
    except BaseException:
        if node is not None:
            node.stop()  # closes the transport too
        else:
            transport.close()
        raise
    if ears is not None:
        ears.start()
    print(f"hexar serve: listening over {transport.name}; answers on /hexar/answer; writes only "
          f"{', '.join(transport.writer_topics())}", file=sys.stderr, flush=True)
    follower = _launch_follower(opts)
    try:
        started = time.monotonic()
        deadline = None if opts.duration_s is None else started + opts.duration_s
        heard_checked = False
        while not stop.is_set() and (deadline is None or time.monotonic() < deadline):
            stop.wait(0.2)
            if follower is not None:
                log.extend(follower.poll())
            if not heard_checked and time.monotonic() - started >= SILENT_HINT_S:
                heard_checked = True  # once: a robot heard by then needs no hint, and the loop no more checks
                if not log.stats()["received"]:
                    print(silent_hint(transport.name, getattr(transport, "domain_id", opts.domain)),
                          file=sys.stderr, flush=True)
    except KeyboardInterrupt:
        pass
    finally:
        node.stop()
        stats = log.stats()
        print(f"hexar serve: received {stats['received']} records ({stats['duplicates']} duplicates, "
              f"{stats['truncated']} cut long lines, {stats['clock_jumps']} clock jumps); {node.answers} answers "
              f"({node.corrections} corrections, {node.unspoken} unasked not said aloud), {node.untold} failures "
              f"whose task was gone by their turn, {node.errors} errors; lost contact {log.contact.stats()['gaps']} "
              "times", file=sys.stderr, flush=True)
    return 0


SILENT_HINT_S = 10.0  # DDS discovery on a working network takes well under a second (2 s announcements at most)


def silent_hint(transport: str, domain: int | None) -> str:
    """What to check when nothing at all came from the robot: the settings that keep two ROS 2 computers apart."""
    return (f"hexar serve: nothing heard from a robot in {SILENT_HINT_S:.0f} s (over {transport}, domain {domain}). "
            "Check that the robot uses the same ROS_DOMAIN_ID, that its ROS_AUTOMATIC_DISCOVERY_RANGE is not "
            "LOCALHOST or OFF, and, where multicast does not reach this computer (many Wi-Fi networks), set "
            "ROS_STATIC_PEERS to the robot's address here.")


def _launch_follower(opts: ServeOptions) -> LaunchLogFollower | None:
    """The follower of launch's log on this computer, announced on stderr; None when it is off or there is none."""
    from hexar.live.launch_log import follower

    found = follower(opts.launch_log, opts.horizon_s) if opts.follow_launch_log else None
    if found is None:
        return None
    if not found.root.is_dir():
        print(f"hexar serve: no launch log folder at {found.root} yet; following it once launch makes it",
              file=sys.stderr, flush=True)
    print(f"hexar serve: following launch's log under {found.root}", file=sys.stderr, flush=True)
    return found


@contextmanager
def _stop_on_signals() -> Iterator[threading.Event]:
    """SIGTERM and SIGINT end the command through its normal path, so the transport closes its DDS participant
    (a ROS 2 node left to the interpreter's exit aborts, and Fast DDS leaves its shared memory behind). The
    previous handlers come back afterwards (the CLI also runs inside tests)."""
    stop = threading.Event()
    if threading.current_thread() is not threading.main_thread():
        yield stop  # signals reach the main thread only; a caller elsewhere stops by other means
        return
    previous = {sig: signal.signal(sig, lambda *_: stop.set()) for sig in (signal.SIGTERM, signal.SIGINT)}
    try:
        yield stop
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)


def replay_command(run: Path, rate: float, transport: str, domain: int | None, start_s: float,
                   clock_hz: float = 0.0) -> int:
    from hexar.events.reader import resolve_path
    from hexar.live.replay import DdsReplayer, check_start, replay

    resolve_path(run)  # a missing or wrong path fails before DDS starts
    if not rate > 0:
        raise BadOptionError(f"--rate must be above 0, not {rate}")
    if not start_s >= 0:  # also nan
        raise BadOptionError(f"--start must be 0 or more seconds, not {start_s}")
    if not clock_hz >= 0:
        raise BadOptionError(f"--clock must be 0 (off) or a rate in Hz, not {clock_hz}")
    check_start(run, start_s)
    writer: Any
    if pick_transport(transport) == "rclpy":
        from hexar.live.ros import RclpyReplayer

        writer = RclpyReplayer(domain_id(domain))
    else:
        writer = DdsReplayer(domain_id(domain))
    try:
        with _stop_on_signals() as stop:
            stats = replay(run, writer, rate=rate, start_s=start_s, should_stop=stop.is_set, clock_hz=clock_hz)
    finally:
        writer.close()
    skipped = f"; not replayed: {', '.join(stats.skipped_topics)}" if stats.skipped_topics else ""
    unheard = (f"; no reader had matched {', '.join(stats.unmatched_topics)} when it began"
               if stats.unmatched_topics else "")
    print(f"replayed {stats.published} messages of {run.name} in {stats.seconds:.1f} s{skipped}{unheard}")
    return 0


def chat_live_command(domain: int | None, console: Any, transport: str = "auto") -> int:
    """`hexar chat --live`: lines from the terminal to the running node, its answers printed."""
    from hexar.live.chat_live import PROMPT_HELP, chat_live

    def show(result: dict[str, Any]) -> None:
        tag = {"failure": "unasked", "correction": "correction"}.get(str(result.get("trigger")), "HEXAR")
        console.print(f"[bold cyan]{tag}:[/bold cyan] {safe(result.get('answer') or result.get('error'))}")

    def lines() -> Any:
        while True:
            try:
                yield input("you> ")
            except EOFError:
                return

    chosen, domain = pick_transport(transport, prefer="dds"), domain_id(domain)
    console.print(f"[dim]{PROMPT_HELP}[/dim]")
    return chat_live(domain, lines(), show, transport=chosen)
