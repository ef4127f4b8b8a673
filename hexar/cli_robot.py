"""The commands beside a running robot: `listen` (spoken dialogue), `serve` (the live node) and `replay` (a
recording played onto the live topics). Their bodies are in hexar.voice and hexar.live."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from hexar.cli_guard import guarded, out


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

