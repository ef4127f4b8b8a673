"""WAV reading (and its clear errors) and the energy VAD that makes one utterance one question."""

from __future__ import annotations

import struct
import wave
from pathlib import Path

import numpy as np
import pytest

from hexar.voice.audio import Audio, concat, read_wav, silence, write_wav
from hexar.voice.errors import AudioFormatError
from hexar.voice.vad import Segmenter, segments

RATE = 16_000


def tone(seconds: float, amp: float = 0.3, hz: float = 220.0, rate: int = RATE) -> Audio:
    t = np.arange(round(seconds * rate)) / rate
    return Audio((amp * np.sin(2 * np.pi * hz * t)).astype(np.float32), rate)


def test_round_trip(tmp_path: Path) -> None:
    a = tone(0.5)
    b = read_wav(write_wav(tmp_path / "a.wav", a))
    assert b.rate == RATE and len(b.samples) == len(a.samples)
    assert np.max(np.abs(b.samples - a.samples)) < 1e-3


@pytest.mark.parametrize("width", [1, 2, 3, 4])
def test_integer_pcm_widths_and_stereo(tmp_path: Path, width: int) -> None:
    x = tone(0.2, amp=0.5).samples
    scale = {1: 127, 2: 32767, 3: 8_388_607, 4: 2_147_483_647}[width]
    ints = np.round(x * scale).astype(np.int64)
    stereo = np.repeat(ints, 2)
    if width == 1:
        raw = (stereo + 128).astype(np.uint8).tobytes()
    else:
        raw = b"".join(int(v).to_bytes(width, "little", signed=True) for v in stereo)
    with wave.open(str(tmp_path / "s.wav"), "wb") as w:
        w.setnchannels(2)
        w.setsampwidth(width)
        w.setframerate(RATE)
        w.writeframes(raw)
    got = read_wav(tmp_path / "s.wav")
    assert len(got.samples) == len(x)
    assert np.max(np.abs(got.samples - x)) < 0.02


def test_not_a_wav(tmp_path: Path) -> None:
    bad = tmp_path / "question.wav"
    bad.write_text("why did you stop?")
    with pytest.raises(AudioFormatError, match="not a readable WAV"):
        read_wav(bad)


def test_float_or_adpcm_wav_is_refused_clearly(tmp_path: Path) -> None:
    for fmt, name in ((3, "float.wav"), (2, "adpcm.wav")):
        data = b"\0" * 64
        fmt_chunk = struct.pack("<HHIIHH", fmt, 1, RATE, RATE * 4, 4, 32)
        body = (b"WAVE" + b"fmt " + struct.pack("<I", len(fmt_chunk)) + fmt_chunk
                + b"data" + struct.pack("<I", len(data)) + data)
        (tmp_path / name).write_bytes(b"RIFF" + struct.pack("<I", len(body)) + body)
        with pytest.raises(AudioFormatError, match="only integer PCM"):
            read_wav(tmp_path / name)


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(AudioFormatError, match="no such file"):
        read_wav(tmp_path / "nope.wav")


def test_two_utterances_make_two_segments() -> None:
    audio = concat([silence(0.5, RATE), tone(1.0), silence(1.2, RATE), tone(0.8), silence(0.6, RATE)], gap_s=0)
    found = segments(audio)
    assert len(found) == 2
    assert 0.9 < found[0].seconds < 1.6 and 0.7 < found[1].seconds < 1.4


def test_short_pauses_stay_in_one_utterance() -> None:
    words = [tone(0.3) for _ in range(5)]
    assert len(segments(concat(words, gap_s=0.3))) == 1


def test_silence_and_clicks_are_not_speech() -> None:
    assert segments(silence(2.0, RATE)) == []
    noise = Audio((np.random.default_rng(0).normal(0, 0.002, RATE * 2)).astype(np.float32), RATE)
    assert segments(noise) == []
    click = concat([silence(1.0, RATE), tone(0.06), silence(1.0, RATE)], gap_s=0)
    assert segments(click) == []


def test_streaming_segmenter_calibrates_on_room_noise() -> None:
    rng = np.random.default_rng(1)
    room = lambda s: Audio(rng.normal(0, 0.01, round(s * RATE)).astype(np.float32), RATE)  # noqa: E731
    speech = Audio(tone(1.0).samples + room(1.0).samples, RATE)
    stream = concat([room(1.0), speech, room(1.5), speech, room(1.5)], gap_s=0).samples
    seg = Segmenter(RATE)
    found = []
    for i in range(0, len(stream), 1024):  # blocks as a microphone delivers them
        found += seg.feed(stream[i:i + 1024])
    found += seg.flush()
    assert len(found) == 2
