"""Where a spoken answer goes: the robot's own TTS (ROS 2), the local loudspeaker, or WAV files."""

from __future__ import annotations

import importlib
import importlib.util
import os
import shutil
import subprocess
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Protocol

from hexar.voice.audio import Audio, concat, write_wav
from hexar.voice.errors import SpeakerError
from hexar.voice.tts import Synthesizer

TTS_ACTION_ENV = "HEXAR_TTS_ACTION"  # action server name, default /tts (pal_interaction_msgs/action/Tts)
TTS_TOPIC_ENV = "HEXAR_TTS_TOPIC"  # or a std_msgs/String topic some other TTS node speaks from
WORDS_PER_MINUTE = 150


class Speaker(Protocol):
    name: str

    def say(self, utterances: Sequence[str], turn: str) -> None:
        """Speak the utterances in order; `turn` names the turn (a file name for WAV output)."""
        ...

    def close(self) -> None: ...


class WavSpeaker:
    """Writes each turn's utterances, joined by short pauses, to DIR/<turn>.wav."""

    def __init__(self, synth: Synthesizer, out_dir: Path) -> None:
        self.synth, self.out_dir = synth, out_dir
        self.name = f"wav:{synth.name}"
        self.written: list[Path] = []
        try:
            out_dir.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise SpeakerError(f"cannot write answers to {out_dir}: {err.strerror or err}") from err

    def say(self, utterances: Sequence[str], turn: str) -> None:
        parts = [self.synth.synthesize(u) for u in utterances if u.strip()]
        if parts:
            self.written.append(write_wav(self.out_dir / f"{turn}.wav", concat(parts)))

    def close(self) -> None:
        return None


class PlaybackSpeaker:
    """Plays on the default output device (sounddevice), else through aplay or sox's play."""

    def __init__(self, synth: Synthesizer) -> None:
        self.synth = synth
        self.name = f"local:{synth.name}"
        self._sd: Any = None
        self._player = ""
        try:
            sd: Any = importlib.import_module("sounddevice")
            sd.query_devices(kind="output")
            self._sd = sd
        except Exception:  # no package, no PortAudio library (OSError) or no device (PortAudioError)
            player = shutil.which("aplay") or shutil.which("play")
            if player is None:
                raise SpeakerError("no audio output device and no aplay/play: use --out DIR to write WAVs") from None
            self._player = player

    def say(self, utterances: Sequence[str], turn: str) -> None:
        for text in utterances:
            if text.strip():
                self._play(self.synth.synthesize(text))

    def _play(self, audio: Audio) -> None:
        if self._sd is not None:
            self._sd.play(audio.samples, audio.rate)
            self._sd.wait()
            return
        with tempfile.TemporaryDirectory() as tmp:
            wav = write_wav(Path(tmp) / "say.wav", audio)
            cmd = [self._player, "-q", str(wav)]
            try:
                subprocess.run(cmd, check=True, capture_output=True, timeout=120)
            except (subprocess.CalledProcessError, subprocess.TimeoutExpired, OSError) as err:
                raise SpeakerError(f"cannot play audio with {self._player}: {err}") from err

    def close(self) -> None:
        return None


def robot_tts_available() -> bool:
    """rclpy and the PAL message package (or a configured topic) are importable: we are on the robot."""
    if importlib.util.find_spec("rclpy") is None:
        return False
    return bool(os.environ.get(TTS_TOPIC_ENV)) or importlib.util.find_spec("pal_interaction_msgs") is not None


class RobotSpeaker:  # pragma: no cover -- needs rclpy and a running /tts server, neither installable here
    """The robot speaks: one `/tts` goal (`rawtext.text`, `rawtext.lang_id`) per utterance, waiting for each,
    so no utterance runs into the TTS timeout. Or one std_msgs/String per utterance on HEXAR_TTS_TOPIC."""

    def __init__(self, action: str | None = None, topic: str | None = None, lang_id: str = "en_GB",
                 timeout_s: float = 20.0) -> None:
        try:
            self._rclpy: Any = importlib.import_module("rclpy")
        except ImportError as err:
            raise SpeakerError("the robot's TTS needs rclpy (source your ROS 2 setup)") from err
        self.lang_id, self.timeout_s = lang_id, timeout_s
        self._owns_context = not self._rclpy.ok()
        if self._owns_context:
            self._rclpy.init()
        self._node = self._rclpy.create_node("hexar_voice")
        topic = topic or os.environ.get(TTS_TOPIC_ENV)
        self._pub: Any = None
        self._client: Any = None
        if topic:
            string_msg: Any = importlib.import_module("std_msgs.msg").String
            self._pub, self._string = self._node.create_publisher(string_msg, topic, 10), string_msg
            self.name = f"robot:topic:{topic}"
            return
        action = action or os.environ.get(TTS_ACTION_ENV, "/tts")
        try:
            self._tts: Any = importlib.import_module("pal_interaction_msgs.action").Tts
        except ImportError as err:
            self.close()
            raise SpeakerError("pal_interaction_msgs is not installed: set HEXAR_TTS_TOPIC or use --out") from err
        action_client: Any = importlib.import_module("rclpy.action").ActionClient
        self._client = action_client(self._node, self._tts, action)
        if not self._client.wait_for_server(timeout_sec=5.0):
            self.close()
            raise SpeakerError(f"no TTS action server at {action}")
        self.name = f"robot:action:{action}"

    def say(self, utterances: Sequence[str], turn: str) -> None:
        for text in utterances:
            if not text.strip():
                continue
            if self._pub is not None:
                self._pub.publish(self._string(data=text))
                # nothing reports when a topic-driven TTS is done: wait about as long as the words take
                time.sleep(len(text.split()) * 60.0 / WORDS_PER_MINUTE + 0.3)
                continue
            goal = self._tts.Goal()
            goal.rawtext.text, goal.rawtext.lang_id = text, self.lang_id
            sent = self._client.send_goal_async(goal)
            self._rclpy.spin_until_future_complete(self._node, sent, timeout_sec=5.0)
            handle = sent.result()
            if handle is None or not handle.accepted:
                raise SpeakerError("the robot's TTS rejected the utterance")
            done = handle.get_result_async()
            self._rclpy.spin_until_future_complete(self._node, done, timeout_sec=self.timeout_s + 5.0)

    def close(self) -> None:
        self._node.destroy_node()
        if self._owns_context and self._rclpy.ok():
            self._rclpy.shutdown()


def make_speakers(speak: bool, out_dir: Path | None, voice: str = "auto") -> list[Speaker]:
    """`--speak`: the robot's TTS when on a robot, else the loudspeaker; `--out DIR`: WAV files. Both may be set."""
    from hexar.voice.tts import local_synthesizer

    speakers: list[Speaker] = []
    synth: Synthesizer | None = None
    if out_dir is not None:
        synth = local_synthesizer("auto" if voice == "robot" else voice)
        speakers.append(WavSpeaker(synth, out_dir))
    if speak:
        if voice in {"auto", "robot"} and robot_tts_available():
            speakers.append(RobotSpeaker())
        elif voice == "robot":
            raise SpeakerError("the robot's TTS needs rclpy and pal_interaction_msgs (or HEXAR_TTS_TOPIC)")
        else:
            speakers.append(PlaybackSpeaker(synth or local_synthesizer(voice)))
    return speakers
