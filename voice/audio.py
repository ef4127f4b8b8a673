"""Mono audio in memory, WAV reading and writing, resampling."""

from __future__ import annotations

import io
import wave
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from hexar.voice.errors import AudioFormatError

Samples = npt.NDArray[np.float32]
ASR_RATE = 16_000  # what both recognisers expect


@dataclass(frozen=True)
class Audio:
    """Mono samples in [-1, 1] at `rate` Hz."""

    samples: Samples
    rate: int

    @property
    def seconds(self) -> float:
        return len(self.samples) / self.rate

    def resampled(self, rate: int) -> Audio:
        if rate == self.rate:
            return self
        from math import gcd

        from scipy.signal import resample_poly

        g = gcd(rate, self.rate)
        out = resample_poly(self.samples, rate // g, self.rate // g)
        return Audio(np.asarray(out, dtype=np.float32), rate)

    def int16(self) -> npt.NDArray[np.int16]:
        return np.asarray(np.clip(self.samples, -1.0, 1.0) * 32767.0, dtype=np.int16)


def silence(seconds: float, rate: int) -> Audio:
    return Audio(np.zeros(round(seconds * rate), dtype=np.float32), rate)


def concat(parts: list[Audio], gap_s: float = 0.35) -> Audio:
    """Join utterances with a short pause, at the first part's rate."""
    if not parts:
        raise ValueError("nothing to join")
    rate = parts[0].rate
    pieces: list[Samples] = []
    for i, part in enumerate(parts):
        if i:
            pieces.append(silence(gap_s, rate).samples)
        pieces.append(part.resampled(rate).samples)
    return Audio(np.concatenate(pieces), rate)


def _pcm_to_float(raw: bytes, width: int) -> Samples:
    if width == 1:  # 8-bit WAV is unsigned
        return (np.frombuffer(raw, dtype=np.uint8).astype(np.float32) - 128.0) / 128.0
    if width == 2:
        return np.frombuffer(raw, dtype="<i2").astype(np.float32) / 32768.0
    if width == 3:
        b = np.frombuffer(raw, dtype=np.uint8).reshape(-1, 3).astype(np.int32)
        v = b[:, 0] | (b[:, 1] << 8) | (b[:, 2] << 16)
        v = np.where(v >= 1 << 23, v - (1 << 24), v)
        return v.astype(np.float32) / float(1 << 23)
    if width == 4:
        return (np.frombuffer(raw, dtype="<i4").astype(np.float64) / float(1 << 31)).astype(np.float32)
    raise AudioFormatError(f"unsupported WAV sample width: {width * 8} bits")


def decode_wav(data: bytes, name: str = "audio") -> Audio:
    """Integer PCM WAV (8/16/24/32-bit, any channel count) to mono float audio."""
    try:
        with wave.open(io.BytesIO(data), "rb") as w:
            channels, width, rate = w.getnchannels(), w.getsampwidth(), w.getframerate()
            raw = w.readframes(w.getnframes())
    except (wave.Error, EOFError) as err:
        # wave only reads integer PCM: ADPCM, mu-law and float WAVs end up here as "unknown format"
        detail = str(err)
        if "unknown format" in detail:
            detail = f"{detail}; only integer PCM WAV is supported (convert with: sox IN -b 16 OUT.wav)"
        raise AudioFormatError(f"{name}: not a readable WAV file ({detail})") from err
    if channels < 1 or rate <= 0:
        raise AudioFormatError(f"{name}: bad WAV header ({channels} channels, {rate} Hz)")
    samples = _pcm_to_float(raw[: len(raw) - len(raw) % (width * channels)], width)
    if channels > 1:
        samples = samples.reshape(-1, channels).mean(axis=1).astype(np.float32)
    return Audio(samples, rate)


def read_wav(path: Path) -> Audio:
    from hexar.errors import InputFileError
    from hexar.inputs import read_bytes_arg
    from hexar.safe_text import visible

    try:
        data = read_bytes_arg(path, "--wav")
    except InputFileError as err:
        raise AudioFormatError(str(err)) from err
    return decode_wav(data, visible(str(path)))


def write_wav(path: Path, audio: Audio) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    with wave.open(str(path), "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(audio.rate)
        w.writeframes(audio.int16().tobytes())
    return path
