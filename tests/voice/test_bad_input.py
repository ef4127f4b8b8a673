"""Bad input to `hexar listen`: one line on stderr and exit code 2, before any model is loaded."""

from __future__ import annotations

import sys
import types
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from hexar.cli_guard import guarded
from hexar.voice.audio import Audio, silence, write_wav
from hexar.voice.errors import MicrophoneError, NoSpeechError, TranscriberError
from hexar.voice.loop import listen
from hexar.voice.stt import VoskTranscriber, make_transcriber

RUN = Path("no_such_recording")


def exit_code(capsys: pytest.CaptureFixture[str], **kwargs: Any) -> tuple[int, str]:
    code = guarded(lambda: listen(RUN, out_dir=Path("unused"), llm="none", **kwargs))
    err = capsys.readouterr().err.strip()
    return code, err


def speechlike(tmp_path: Path) -> Path:
    t = np.arange(16_000) / 16_000
    return write_wav(tmp_path / "q.wav", Audio((0.3 * np.sin(2 * np.pi * 200 * t)).astype(np.float32), 16_000))


def test_no_sounddevice(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setitem(sys.modules, "sounddevice", None)  # import fails as if not installed
    code, err = exit_code(capsys, mic=True)
    assert code == 2
    assert err.startswith("ERROR: no microphone support: pip install sounddevice") and "\n" not in err


def test_no_input_device(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    fake = types.ModuleType("sounddevice")

    def query_devices(kind: str | None = None) -> Any:
        raise ValueError("No input device matching ''")

    fake.query_devices = query_devices  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "sounddevice", fake)
    code, err = exit_code(capsys, mic=True)
    assert code == 2
    assert err.startswith("ERROR: no microphone found") and "\n" not in err


def test_silent_wav(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    wav = write_wav(tmp_path / "silence.wav", silence(2.0, 16_000))
    code, err = exit_code(capsys, wavs=[wav])
    assert code == 2
    assert err == f"ERROR: no speech detected in {wav}: is it silent or very quiet?"


def test_every_wav_silent(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    quiet = [write_wav(tmp_path / f"s{i}.wav", silence(1.0, 16_000)) for i in range(2)]
    code, err = exit_code(capsys, wavs=quiet)
    assert (code, err) == (2, "ERROR: no speech detected in any of the 2 files: is it silent or very quiet?")


def test_wav_files_without_the_flag(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from hexar.cli import main

    code = main(["listen", str(RUN), str(speechlike(tmp_path)), "--llm", "none"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and err.startswith("ERROR: unexpected argument") and "after --wav" in err


def test_not_a_wav(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "q.mp3"
    bad.write_bytes(b"ID3\x03\x00" + b"\0" * 100)
    code, err = exit_code(capsys, wavs=[bad])
    assert code == 2
    assert err.startswith(f"ERROR: {bad}: not a readable WAV file")


def test_wav_and_mic_together(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, err = exit_code(capsys, wavs=[speechlike(tmp_path)], mic=True)
    assert (code, err) == (2, "ERROR: give --wav FILE... or --mic, not both")


def test_missing_vosk_model(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, err = exit_code(capsys, wavs=[speechlike(tmp_path)], vosk_model=tmp_path / "vosk-model-small-en-us")
    assert code == 2
    assert err.startswith("ERROR: vosk model folder not found") and "--vosk-model DIR" in err


def test_vosk_model_from_environment(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("HEXAR_VOSK_MODEL", str(tmp_path / "gone"))
    with pytest.raises(TranscriberError, match="vosk model folder not found"):
        make_transcriber()
    (tmp_path / "empty").mkdir()
    with pytest.raises(TranscriberError, match="is not a vosk model"):
        VoskTranscriber(tmp_path / "empty")


def test_errors_are_hexar_errors() -> None:
    from hexar.errors import USER_ERRORS

    for cls in (MicrophoneError, NoSpeechError, TranscriberError):
        assert issubclass(cls, USER_ERRORS)
