"""The default microphone as a stream of utterances (sounddevice, only imported when listening live)."""

from __future__ import annotations

import importlib
import queue
from collections.abc import Iterator
from typing import Any

import numpy as np

from hexar.voice.audio import Audio, Samples
from hexar.voice.errors import MicrophoneError
from hexar.voice.vad import Segmenter, VadSettings

INSTALL = "pip install sounddevice, and the PortAudio library (apt-get install libportaudio2)"


def open_microphone() -> tuple[Any, int]:
    """The sounddevice module and the default input device's sample rate; MicrophoneError when there is none."""
    try:
        sd: Any = importlib.import_module("sounddevice")
    except (ImportError, OSError) as err:  # OSError: the package is there but libportaudio is not
        raise MicrophoneError(f"no microphone support: {INSTALL}") from err
    try:
        info = sd.query_devices(kind="input")
    except Exception as err:  # PortAudioError, ValueError: no default input device
        raise MicrophoneError(f"no microphone found ({err}); use --wav FILE") from err
    if not info or int(info.get("max_input_channels", 0)) < 1:
        raise MicrophoneError("no microphone found; use --wav FILE")
    return sd, int(info.get("default_samplerate") or 16_000)


class Microphone:
    """Listens until a pause ends an utterance, hands it over, and forgets what it heard meanwhile (the
    answer being spoken) before listening again."""

    def __init__(self, settings: VadSettings | None = None, forget_while_busy: bool = True) -> None:
        self._sd, self.rate = open_microphone()
        self.settings = settings or VadSettings()
        self.forget_while_busy = forget_while_busy
        self._q: queue.Queue[Samples] = queue.Queue()

    def _callback(self, indata: Any, frames: int, time: Any, status: Any) -> None:
        self._q.put(np.asarray(indata[:, 0], dtype=np.float32).copy())

    def _drain(self) -> None:
        while True:
            try:
                self._q.get_nowait()
            except queue.Empty:
                return

    def utterances(self) -> Iterator[Audio]:
        seg = Segmenter(self.rate, self.settings)
        try:
            stream = self._sd.InputStream(samplerate=self.rate, channels=1, dtype="float32",
                                          blocksize=seg.frame * 4, callback=self._callback)
        except Exception as err:  # PortAudioError when the device cannot be opened
            raise MicrophoneError(f"cannot open the microphone: {err}") from err
        with stream:
            while True:
                try:
                    # a timeout keeps Ctrl-C responsive while nobody speaks
                    block = self._q.get(timeout=0.5)
                except queue.Empty:
                    continue
                for utterance in seg.feed(block):
                    yield utterance
                    if self.forget_while_busy:
                        self._drain()
                        seg.reset()
                        break
