"""Spoken questions in (microphone or WAV files, through the voice module's VAD and transcriber) and spoken
answers out (robot TTS over the transport's topic, PAL's /tts action through rclpy, piper, WAV files)."""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

from hexar.live.node import Speaker, Transport


class TopicSpeaker:
    """The robot's TTS node reads std_msgs/String from a topic: one message per utterance."""

    def __init__(self, transport: Transport, topic: str) -> None:
        self.transport, self.topic = transport, topic
        self.name = f"topic:{topic}"

    def say(self, utterances: Sequence[str], turn: str) -> None:
        for text in utterances:
            if text.strip():
                self.transport.publish(self.topic, text)

    def close(self) -> None:
        return None


def make_speakers(transport: Transport, tts_topic: str | None, voice: str, out_dir: Path | None,
                  need_voice: bool) -> list[Speaker]:
    """Where answers are spoken. `voice`: auto (the robot's TTS when there is one, else the loudspeaker when
    something must be spoken), robot, piper, espeak or none; `out_dir`: also WAV files."""
    from hexar.voice.speakers import PlaybackSpeaker, RobotSpeaker, WavSpeaker, robot_tts_available
    from hexar.voice.tts import local_synthesizer

    speakers: list[Speaker] = []
    if out_dir is not None:
        speakers.append(WavSpeaker(local_synthesizer("auto" if voice in {"robot", "none"} else voice), out_dir))
    if voice == "none":
        return speakers
    if tts_topic:
        speakers.append(TopicSpeaker(transport, tts_topic))
    elif transport.name == "rclpy" and voice in {"auto", "robot"} and robot_tts_available():
        speakers.append(RobotSpeaker())  # PAL /tts action (rclpy only; never run here)
    elif voice == "robot":
        from hexar.live.errors import BadOptionError

        raise BadOptionError("--voice robot needs --tts-topic, or rclpy with pal_interaction_msgs")
    elif need_voice and out_dir is None:
        speakers.append(PlaybackSpeaker(local_synthesizer(voice)))
    return speakers


class Ears:
    """Feeds transcribed utterances to `ask` from a thread: the microphone, or WAV files in order."""

    def __init__(self, ask: Callable[[str], None], wavs: Sequence[Path] = (), mic: bool = False,
                 vosk_model: Path | None = None) -> None:
        from hexar.voice.stt import make_transcriber

        self.ask = ask
        self.heard: list[str] = []
        self._source = self._wav_audio(wavs) if wavs else (self._mic_audio() if mic else iter(()))
        self.transcriber = make_transcriber(vosk_model)
        self._thread = threading.Thread(target=self._run, name="hexar-ears", daemon=True)

    @staticmethod
    def _wav_audio(wavs: Sequence[Path]) -> Iterator[Any]:
        from hexar.voice.loop import wav_utterances

        return (audio for _, audio in wav_utterances(wavs))

    @staticmethod
    def _mic_audio() -> Iterator[Any]:
        from hexar.voice.mic import Microphone, open_microphone

        open_microphone()  # fails now, with a clear error, when there is no input device
        return Microphone().utterances()

    def start(self) -> None:
        self._thread.start()

    def join(self, timeout: float | None = None) -> None:
        self._thread.join(timeout)

    def _run(self) -> None:
        from hexar.voice.transcripts import normalise, repair

        for audio in self._source:
            try:
                transcript = self.transcriber.transcribe(audio)
            except Exception as err:  # one bad utterance must not end the node
                print(f"hexar serve: cannot transcribe: {err}", file=sys.stderr)
                continue
            if normalise(transcript):
                question = repair(transcript)
                self.heard.append(question)
                self.ask(question)
            time.sleep(0.01)
