"""Energy-based voice-activity segmentation: one utterance (speech followed by a pause) is one question."""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import numpy as np

from hexar.voice.audio import Audio, Samples


@dataclass(frozen=True)
class VadSettings:
    frame_s: float = 0.03
    margin_db: float = 10.0  # speech is this far above the noise floor
    floor_db: float = -50.0  # quieter than this is never speech, whatever the noise
    end_silence_s: float = 0.8  # a pause this long ends the utterance; pauses between words are shorter
    min_speech_s: float = 0.25  # shorter bursts are clicks or coughs
    pad_s: float = 0.2  # kept around the speech so the recogniser hears the word onsets
    max_utterance_s: float = 20.0


def frame_db(frame: Samples) -> float:
    rms = float(np.sqrt(np.mean(np.square(frame, dtype=np.float64)))) if len(frame) else 0.0
    return max(-100.0, 20.0 * float(np.log10(rms + 1e-10)))


class Segmenter:
    """Streaming: feed samples as they come, get finished utterances back.

    With no `threshold_db` the first half second calibrates the noise floor and a floor tracker follows it
    (quickly down, slowly up) so a fan switched on mid-session does not become endless speech.
    """

    def __init__(self, rate: int, settings: VadSettings | None = None, threshold_db: float | None = None) -> None:
        self.rate = rate
        self.s = settings or VadSettings()
        self.frame = max(1, round(self.s.frame_s * rate))
        self._fixed = threshold_db
        self._noise: float | None = None
        self._calib: list[float] = []
        self._rest: Samples = np.zeros(0, dtype=np.float32)
        self._pre: deque[Samples] = deque(maxlen=max(1, round(self.s.pad_s / self.s.frame_s)))
        self._cur: list[Samples] = []
        self._voiced = 0
        self._quiet = 0

    def threshold(self) -> float:
        if self._fixed is not None:
            return self._fixed
        return max(self.s.floor_db, (self._noise if self._noise is not None else -100.0) + self.s.margin_db)

    def _track(self, db: float, speech: bool) -> None:
        if self._fixed is not None:
            return
        if self._noise is None:
            self._calib.append(db)
            if len(self._calib) * self.s.frame_s >= 0.5:
                self._noise = float(np.median(self._calib))
            return
        if db < self._noise:
            self._noise = db
        else:
            self._noise += (0.002 if speech else 0.03) * (db - self._noise)

    def feed(self, samples: Samples) -> list[Audio]:
        data = np.concatenate([self._rest, samples.astype(np.float32, copy=False)])
        done: list[Audio] = []
        n = len(data) // self.frame
        for i in range(n):
            seg = self._step(data[i * self.frame:(i + 1) * self.frame])
            if seg is not None:
                done.append(seg)
        self._rest = data[n * self.frame:]
        return done

    def flush(self) -> list[Audio]:
        seg = self._finish() if self._cur else None
        self._rest = np.zeros(0, dtype=np.float32)
        return [seg] if seg is not None else []

    def reset(self) -> None:
        """Forget audio heard so far (the robot's own voice while it was speaking)."""
        self._rest = np.zeros(0, dtype=np.float32)
        self._pre.clear()
        self._cur, self._voiced, self._quiet = [], 0, 0

    def _step(self, frame: Samples) -> Audio | None:
        db = frame_db(frame)
        speech = db > self.threshold() and (self._noise is not None or self._fixed is not None)
        self._track(db, speech)
        if not self._cur:
            if speech:
                self._cur = [*self._pre, frame]
                self._voiced, self._quiet = 1, 0
            else:
                self._pre.append(frame)
            return None
        self._cur.append(frame)
        if speech:
            self._voiced += 1
            self._quiet = 0
        else:
            self._quiet += 1
        ended = self._quiet * self.s.frame_s >= self.s.end_silence_s
        if ended or len(self._cur) * self.s.frame_s >= self.s.max_utterance_s:
            return self._finish()
        return None

    def _finish(self) -> Audio | None:
        pad = round(self.s.pad_s / self.s.frame_s)
        keep = len(self._cur) - max(0, self._quiet - pad)
        frames, voiced = self._cur[:keep], self._voiced
        self._cur, self._voiced, self._quiet = [], 0, 0
        self._pre.clear()
        if voiced * self.s.frame_s < self.s.min_speech_s:
            return None
        return Audio(np.concatenate(frames), self.rate)


def file_threshold(audio: Audio, settings: VadSettings | None = None) -> float:
    """A fixed threshold for a whole recording: above its quiet parts, below its loud ones."""
    s = settings or VadSettings()
    frame = max(1, round(s.frame_s * audio.rate))
    dbs = [frame_db(audio.samples[i:i + frame]) for i in range(0, len(audio.samples) - frame + 1, frame)]
    if not dbs:
        return 0.0
    quiet, loud = float(np.percentile(dbs, 10)), float(np.percentile(dbs, 95))
    return max(s.floor_db, min(quiet + s.margin_db, loud - 12.0))


def segments(audio: Audio, settings: VadSettings | None = None) -> list[Audio]:
    """The utterances in a recording, in order; empty when it holds no speech."""
    seg = Segmenter(audio.rate, settings, threshold_db=file_threshold(audio, settings))
    return [*seg.feed(audio.samples), *seg.flush()]
