"""`hexar listen`: spoken question -> transcript -> the agent's thread -> short spoken answer, turn after turn.

The thread lives in the same SQLite checkpoints as `hexar chat`, so a spoken conversation can go on in text.
"""

from __future__ import annotations

import time
from collections.abc import Iterator, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from rich.console import Console

from hexar.agent.context import RunSettings
from hexar.agent.session import Session, default_checkpoints
from hexar.agent.state import SAID_REFUSALS
from hexar.errors import USER_ERRORS
from hexar.safe_text import json_dumps, safe
from hexar.voice.audio import Audio, read_wav
from hexar.voice.errors import NoSpeechError, VoiceError
from hexar.voice.speakers import Speaker, make_speakers
from hexar.voice.stt import Transcriber, make_transcriber
from hexar.voice.transcripts import is_stop, is_thanks, normalise, repair
from hexar.voice.utterances import spoken
from hexar.voice.vad import segments

NOT_UNDERSTOOD = "Sorry, I didn't understand that. Ask me why I did something."
LOG_NAME = "dialogue.jsonl"


@dataclass
class Turn:
    n: int
    source: str
    transcript: str
    question: str = ""  # what the agent was asked: the transcript, repaired
    answer: str = ""
    spoken: list[str] = field(default_factory=list)
    error: str = ""
    route: str = ""
    explainers: list[str] = field(default_factory=list)
    causes: list[str] = field(default_factory=list)
    wav: str = ""
    timings_ms: dict[str, float] = field(default_factory=dict)


def _ms(since: float) -> float:
    return round((time.perf_counter() - since) * 1000, 1)


def wav_utterances(paths: Sequence[Path], notes: list[str] | None = None) -> list[tuple[str, Audio]]:
    """Every utterance in the files, read before any model loads so a bad file fails fast. A silent file among
    others is skipped with a note (one quiet recording should not end the conversation); all silent is an
    error."""
    out: list[tuple[str, Audio]] = []
    for path in paths:
        found = segments(read_wav(path))
        if not found:
            if notes is not None:
                notes.append(f"skipped {path.name}: no speech in it (silent or very quiet)")
            continue
        out += [(path.name if len(found) == 1 else f"{path.name}#{i + 1}", a) for i, a in enumerate(found)]
    if not out:
        which = str(paths[0]) if len(paths) == 1 else f"any of the {len(paths)} files"
        raise NoSpeechError(f"no speech detected in {which}: is it silent or very quiet?")
    return out


def mic_utterances() -> Iterator[tuple[str, Audio]]:
    from hexar.voice.mic import Microphone

    mic = Microphone()
    return (("mic", a) for a in mic.utterances())


def say_answer(result: dict[str, Any]) -> list[str]:
    """The utterances for an agent result; an evidence answer is split on its recorded items."""
    evidence = None
    if result.get("route") == "followup" and result.get("intent") == "deeper":
        evidence = [str(ev.get("item", "")) for ev in result.get("evidence", [])[:3]]
    return spoken(str(result["answer"]), evidence)


class Dialogue:
    """One spoken conversation over one recording."""

    def __init__(self, session: Session, transcriber: Transcriber, speakers: Sequence[Speaker],
                 thread: str | None = None, console: Console | None = None, log_dir: Path | None = None) -> None:
        self.session, self.transcriber, self.speakers = session, transcriber, list(speakers)
        self.thread = thread or session.new_thread()
        self.console = console or Console(highlight=False)
        self.log = (log_dir / LOG_NAME) if log_dir is not None else None
        self.turns: list[Turn] = []

    def _say(self, utterances: list[str], turn: Turn) -> None:
        started = time.perf_counter()
        for speaker in self.speakers:
            speaker.say(utterances, f"turn_{turn.n:02d}")
            written = getattr(speaker, "written", None)
            if written and written[-1].stem == f"turn_{turn.n:02d}":
                turn.wav = str(written[-1])
        turn.timings_ms["speech"] = _ms(started)

    def hear(self, source: str, audio: Audio) -> Turn | None:
        """One utterance: None when it held no words; a turn whose transcript `is_stop` ends the dialogue."""
        started = time.perf_counter()
        transcript = self.transcriber.transcribe(audio)
        if not normalise(transcript):
            return None
        turn = Turn(n=len(self.turns) + 1, source=source, transcript=transcript,
                    timings_ms={"audio": round(audio.seconds * 1000, 1), "transcribe": _ms(started)})
        turn.question = repair(transcript)
        heard = safe(transcript)
        if turn.question != transcript:
            heard += f" [dim](as: {safe(turn.question)})[/dim]"
        self.console.print(f"[bold]you:[/bold] {heard}")
        if is_stop(transcript):
            turn.answer = "You're welcome." if is_thanks(transcript) else "Goodbye."
            turn.spoken = [turn.answer]
        else:
            started = time.perf_counter()
            try:
                result = self.session.ask(turn.question, thread=self.thread)
            except USER_ERRORS as err:  # a question the agent cannot take is one turn, not the end of the talk
                result = {"error": str(err), "route": "none", "explainers": [], "causes": [], "answer": ""}
            except Exception as err:  # nor is a bug in one answer
                result = {"error": f"internal error, please report it: {type(err).__name__}: {err}",
                          "route": "none", "explainers": [], "causes": [], "answer": ""}
            turn.timings_ms["answer"] = _ms(started)
            turn.error, turn.route = str(result["error"]), str(result["route"])
            turn.explainers, turn.causes = list(result["explainers"]), list(result["causes"])
            # a question off the robot's topic was understood: it hears why it gets no explanation
            heard_right = not turn.error or result.get("intent") in SAID_REFUSALS
            turn.answer = str(result["answer"]) if heard_right else NOT_UNDERSTOOD
            turn.spoken = say_answer(result) if heard_right else [NOT_UNDERSTOOD]
        if turn.error:
            self.console.print(f"[yellow]{safe(turn.error)}[/yellow]")
        self.console.print(f"[bold cyan]HEXAR:[/bold cyan] {safe(turn.answer, keep_newlines=True)}")
        self._say(turn.spoken, turn)
        self.turns.append(turn)
        if self.log is not None:
            with self.log.open("a", encoding="utf-8") as f:
                f.write(json_dumps({"thread": self.thread, **asdict(turn)}) + "\n")
        return turn

    def run(self, utterances: Iterator[tuple[str, Audio]] | Sequence[tuple[str, Audio]]) -> int:
        heard = False
        for source, audio in utterances:
            turn = self.hear(source, audio)
            if turn is None:
                continue
            heard = True
            if is_stop(turn.transcript):
                break
        if not heard:
            raise NoSpeechError("heard sounds but no words: speak closer to the microphone or check the file")
        return 0


def listen(run: Path, wavs: Sequence[Path] | None = None, mic: bool = False, speak: bool = False,
           out_dir: Path | None = None, llm: str = "auto", thread: str | None = None,
           checkpoints: Path | None = None, vosk_model: Path | None = None, voice: str = "auto",
           console: Console | None = None) -> int:
    """The `hexar listen` command; returns the exit code. Bad input raises a VoiceError (or another HexarError)."""
    console = console or Console(highlight=False)
    if wavs and mic:
        raise VoiceError("give --wav FILE... or --mic, not both")
    if not speak and out_dir is None:
        speak = True
    # cheap checks first: a bad file or missing microphone should not wait for the models to load
    source: Iterator[tuple[str, Audio]] | list[tuple[str, Audio]]
    notes: list[str] = []
    if out_dir is not None:
        from hexar.inputs import output_dir

        output_dir(out_dir, "--out")
    if wavs:
        source = wav_utterances(wavs, notes)
    else:
        from hexar.voice.mic import open_microphone

        open_microphone()
        source = mic_utterances()
    transcriber = make_transcriber(vosk_model)
    speakers = make_speakers(speak, out_dir, voice)
    try:
        session = Session(RunSettings(recording=run, llm=llm), checkpoints=checkpoints or default_checkpoints())
        dialogue = Dialogue(session, transcriber, speakers, thread, console, out_dir)
        task = session.context.log.task()
        console.print(f"[bold]{safe(run.name)}[/bold]: task \"{safe(task.instruction)}\" ({safe(task.outcome)}); "
                      f"backend {session.backend.name}; speech {transcriber.name} -> "
                      f"{', '.join(s.name for s in speakers)}; thread {dialogue.thread}")
        for note in notes:
            console.print(f"[yellow]{safe(note)}[/yellow]")
        console.print("[dim]Ask why I did something; say \"stop\" or \"thank you\" to end. "
                      f"Continue in text with: hexar chat {safe(str(run))} --thread {safe(dialogue.thread)}[/dim]")
        return dialogue.run(source)
    finally:
        for speaker in speakers:
            speaker.close()
