"""The live node: a LiveLog fed by a transport, proactive explanations of failures, and questions answered.

One worker thread runs the agent, so answers come out in the order their triggers arrived and the agent's
session (its threads of dialogue) is never used from two threads at once. What waits for it is bounded
(live/jobs.py): a few questions per source and a short queue, so a flood on /hexar/question costs neither
memory nor the next real question's answer.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Literal, Protocol

from hexar.agent.state import SAID_REFUSALS
from hexar.events.errors import EventsError
from hexar.events.records import GoalStatus, TaskUpdate
from hexar.live.jobs import (
    MAX_FAILURES,
    MAX_QUESTIONS,
    SPEAK_BURST,
    SPEAK_EVERY_S,
    SPEAK_STALE_S,
    Bucket,
    Job,
    JobQueue,
    Look,
    RateLimit,
    failure_key,
)
from hexar.live.log import NS, LiveLog
from hexar.live.present import no_task_answer, shape
from hexar.live.recheck import Rechecks
from hexar.live.topics import ANSWER
from hexar.safe_text import finite_with_warnings, json_dumps

Proactive = Literal["off", "publish", "speak"]
FAILURE_QUESTION = "Why did the task fail?"
INVALID_QUESTION = "Why couldn't you do the task?"
KEEP_THREADS = 20
FOLLOW_UP_S = 120.0  # a question without a thread continues the current dialogue only this long after its answer
MAX_QUESTION_JSON = 8 * 1024  # `{"question": ..., "thread": ...}`: a question of MAX_QUESTION characters fits
RECHECK = "recheck-"  # the thread of a second look at an unasked explanation (live/recheck.py)
GOAL_ABORTED = 6  # action_msgs/GoalStatus STATUS_ABORTED: Nav2's "Goal failed"
GOAL_ACTIVE = frozenset({1, 2, 3})  # accepted, executing, canceling


class Transport(Protocol):
    name: str

    def start(self, log: LiveLog, on_record: Callable[[Any], None], on_question: Callable[[str], None]) -> None: ...

    def publish(self, topic: str, text: str) -> None: ...

    def writer_topics(self) -> list[str]: ...

    def close(self) -> None: ...


class Speaker(Protocol):
    name: str

    def say(self, utterances: Sequence[str], turn: str) -> None: ...

    def close(self) -> None: ...


@dataclass
class NodeOptions:
    llm: str = "none"
    proactive: Proactive = "publish"
    # After a failing /task_info update, wait until the robot's clock passed it by `settle_s` (so log lines
    # published a moment later but stamped before the failure are in), at most `settle_wall_s` of our time.
    settle_s: float = 0.2
    settle_wall_s: float = 0.3
    # On a network that has lately delivered records later than that (DDS resending what a lossy link dropped),
    # wait as long after the failure came as they were late (their 90th percentile over the last minute, in this
    # machine's seconds), at most this long. A Fast DDS writer (a ROS 2 robot's default middleware) tells its readers
    # what they missed once every 3 s (WriterTimes::heartbeat_period), so its resends come up to 3 s late; waiting
    # 3.5 s for them was measured (scripts/bench_live_robots.py --netloss 100) to put one or two more first answers
    # of 39 right for 1.5 s more on every answer over that link: the second looks (live/recheck.py) correct them.
    max_settle_s: float = 2.0
    # A failure that comes within `back_within_s` of a dropped robot being heard again, stamped after its hole
    # began, waits (at most max_settle_s) until no resent record has come for `resend_quiet_s`: its resends come
    # behind it, and a first answer given before them named a routine line as the cause.
    back_within_s: float = 5.0
    resend_quiet_s: float = 0.5
    # With proactive "speak": SPEAK_BURST unasked explanations said at once, then one every this many seconds at
    # most (the others published only); 0 says each one. One waiting longer than SPEAK_STALE_S is never said.
    speak_every_s: float = SPEAK_EVERY_S
    phrase: bool | None = None


def short_sentence(answer: str, max_words: int = 25) -> str:
    """The first sentence of an answer, at most `max_words` words: what the robot says unasked."""
    from hexar.voice.utterances import spoken

    said = spoken(answer, max_words=max_words, max_sentences=1, max_total=max_words)
    return said[0] if said else answer


class LiveNode:
    def __init__(self, transport: Transport, log: LiveLog | None = None, options: NodeOptions | None = None,
                 speakers: Sequence[Speaker] = (), on_answer: Callable[[dict[str, Any]], None] | None = None) -> None:
        self.transport = transport
        self.log = log or LiveLog(name=f"live:{transport.name}")
        self.options = options or NodeOptions()
        self.speakers = list(speakers)
        self.on_answer = on_answer
        self.thread: str | None = None  # the current dialogue: a follow-up "why?" continues it
        self.answers = 0
        self.errors = 0
        self._jobs: JobQueue[Job] = JobQueue({"question": MAX_QUESTIONS, "failure": MAX_FAILURES},
                                             first=("stop", "question"))
        every = self.options.speak_every_s
        self._speech = Bucket(SPEAK_BURST, 1.0 / every, time.monotonic()) if every > 0 else None
        self.unspoken = 0  # unasked explanations published but not said (over the rate, or stale)
        self.untold = 0  # failures not explained: their task was gone from the live log by their turn
        self._rechecks: Rechecks[Look] = Rechecks()
        self.corrections = 0
        self._rate = RateLimit()
        self.refused = 0  # questions over a source's rate
        self._last_answer = 0.0
        self._explained: set[str] = set()
        self._active_goals: set[str] = set()  # NavigateToPose goals this node saw before they ended
        self._session: Any = None
        self._threads: list[str] = []
        self._worker: threading.Thread | None = None

    # -- wiring ---------------------------------------------------------------------------------------------

    def start(self) -> None:
        self._session = self._make_session()  # loads the explainers (and a model) before traffic comes in
        self.warm_up()
        self._worker = threading.Thread(target=self._work, name="hexar-node", daemon=True)
        self._worker.start()
        self.transport.start(self.log, self.on_record, self.on_question)

    def _make_session(self) -> Any:
        from hexar.agent.context import RunSettings
        from hexar.agent.session import Session

        settings = RunSettings(recording=Path(self.log.name), llm=self.options.llm, phrase=self.options.phrase)
        return Session(settings, log=self.log.snapshot())

    def warm_up(self) -> None:
        """Pay the first-answer costs now (live/warmup.py), so the first live failure is explained within the
        second."""
        from hexar.live.warmup import warm_up

        warm_up(self._session, FAILURE_QUESTION)

    def stop(self) -> None:
        self._jobs.put(Job("stop"))
        if self._worker is not None:
            self._worker.join(timeout=30.0)
        self.transport.close()
        for speaker in self.speakers:
            speaker.close()

    # -- triggers (transport threads) -----------------------------------------------------------------------

    def on_record(self, record: Any) -> None:
        if self.options.proactive == "off":
            return
        if isinstance(record, GoalStatus):
            self._on_goal_status(record)
            return
        if not isinstance(record, TaskUpdate):
            return
        key = failure_key(record)
        if key is None or key in self._explained:
            return
        self._explained.add(key)
        if len(self._explained) > 10_000:  # bounded like the log; an old key seen again is explained again
            self._explained.clear()
            self._explained.add(key)
        self._jobs.put(Job("failure", task_id=record.task_id, t=record.t,
                           text=INVALID_QUESTION if not record.valid else FAILURE_QUESTION))

    def _on_goal_status(self, status: GoalStatus) -> None:
        """A robot without /task_info: its tasks are derived from Nav2 goals (events/nav_goals.py) and the arm's
        (events/arm_goals.py), and an aborted NavigateToPose, MoveGroup, ExecuteTrajectory or FollowJointTrajectory
        goal is its failure. The derived task is found when the job runs (`_derived_task`)."""
        if status.status in GOAL_ACTIVE:
            if len(self._active_goals) > 10_000:
                self._active_goals.clear()
            self._active_goals.add(status.goal_id)
            return
        key = f"{status.topic}:{status.goal_id}:aborted"  # a Nav2 goal's or an arm goal's (events/arm_goals.py)
        if status.status != GOAL_ABORTED or key in self._explained or self.log.stats()["tasks"]:
            return
        if status.goal_id not in self._active_goals:
            # aborted before this node joined: the transient-local status topic hands a late joiner the last
            # array, with goals that ended up to 15 minutes ago (Humble's result_timeout); the node explains
            # failures as they happen, and answers about older ones when asked
            return
        self._explained.add(key)
        self._jobs.put(Job("failure", t=status.t, text=FAILURE_QUESTION))

    def _derived_task(self, t: int) -> str:
        """The derived task that failed closest to `t` (the aborted status), or "" when there is none."""
        failed = [task for task in self._session.context.log.tasks if task.derived and task.outcome == "failed"]
        if not failed:
            return ""
        return str(min(failed, key=lambda task: abs(task.last_update - t)).task_id)

    def on_question(self, text: str) -> None:
        from hexar.agent.questions import bounded
        from hexar.bounded_json import loads
        from hexar.errors import BadJsonError

        thread = None
        stripped = text[:MAX_QUESTION_JSON].strip()
        if stripped.startswith("{"):  # `{"question": ..., "thread": ...}` from `hexar chat --live`
            try:
                obj = loads(stripped, max_chars=MAX_QUESTION_JSON)
            except BadJsonError:
                obj = None
            if isinstance(obj, dict):
                stripped, thread = str(obj.get("question", "")), obj.get("thread")
        thread_id = str(thread)[:64] if thread else None
        self._enqueue(bounded(stripped), thread_id, thread_id or "/hexar/question")

    def _enqueue(self, question: str, thread: str | None, source: str) -> None:
        if not self._rate.allow(source):
            self.refused += 1
            return
        self._jobs.put(Job("question", text=question, thread=thread))

    def ask(self, question: str) -> None:
        """A question from the microphone or a test, queued like one from /hexar/question (its own source)."""
        from hexar.agent.questions import bounded

        self._enqueue(bounded(question.strip()), None, "microphone")

    # -- the worker -----------------------------------------------------------------------------------------

    def _work(self) -> None:
        while True:
            job = self._jobs.get(timeout=self._rechecks.wait_s())
            for due in self._rechecks.take_due():
                self._run(due)
            if job is None:
                continue
            if job.kind == "stop":
                return
            self._run(job)

    def _run(self, work: Job | Look) -> None:
        try:
            if isinstance(work, Look):
                self._recheck(work)
            else:
                self._answer(work)
        except Exception as err:  # the node keeps answering; the error goes out as an answer and a line
            self.errors += 1
            print(f"hexar serve: {type(err).__name__}: {err}", file=sys.stderr)
            if isinstance(work, Job):
                self._publish({"answer": "", "error": f"{type(err).__name__}: {err}", "trigger": work.kind,
                               "task_id": work.task_id})

    def _answer(self, job: Job) -> None:
        if job.kind == "failure":
            opts = self.options
            self.log.wait_until(job.t + int(opts.settle_s * NS), opts.settle_wall_s)
            # a few records, not one stray line, make a network late; how late is in our seconds, so a recording
            # played ten times faster does not wait ten times longer
            late = min(opts.max_settle_s, self.log.lateness_s(over_s=opts.settle_s, least=3))
            time.sleep(max(0.0, job.received + late - time.monotonic()))
            if self.log.resending(job.t, opts.back_within_s):
                # the failure came as a dropped link came back: what the robot logged before it is resent behind it
                self.log.wait_resends(opts.resend_quiet_s, opts.max_settle_s)
        taken, previous = time.monotonic(), self.thread
        self._session.use_log(self.log.snapshot())
        if job.kind == "failure":
            if not job.task_id:
                job.task_id = self._derived_task(job.t)
            self.thread = self._session.new_thread()
            thread, task = self.thread, job.task_id or None
        else:
            # no thread named: the current dialogue goes on only while it is fresh (a spoken "why?" after an
            # answer), so questions from nowhere do not all pile into one thread for the node's lifetime
            fresh = self.thread is not None and time.monotonic() - self._last_answer < FOLLOW_UP_S
            thread = job.thread or (self.thread if fresh else None) or self._session.new_thread()
            self.thread, task = thread, None
        self._remember(thread)
        try:
            result = dict(self._session.ask(job.text, thread=thread, task=task))
        except EventsError as err:  # no task yet: say so instead of guessing
            if job.kind == "failure":
                # its task is no longer kept (a burst of failures pushed it out of the live log): nothing to tell
                self.untold, self.thread = self.untold + 1, previous
                return
            # a person asked: they hear why there is nothing to explain; the developer's reason stays in "error"
            result = no_task_answer(self._session.context.log.logs, err, thread)
        self._last_answer = time.monotonic()
        shape(result, self._session.context.log.tasks, self.log.contact, self.log.newest)
        result["trigger"] = job.kind
        result["recording"] = self.log.name
        result["latency_ms"] = round((time.monotonic() - job.received) * 1000, 1)
        if job.kind == "failure":
            result["sentence"] = short_sentence(str(result.get("answer", "")))
            result["event_t"] = job.t  # the failing update, on the robot's clock
        self._publish(result)
        told_why = bool(result.get("no_task")) or result.get("intent") in SAID_REFUSALS  # a refusal worth hearing
        speak = bool(self.speakers) and (not result.get("error") or told_why) and (
            job.kind == "question" or (self.options.proactive == "speak" and self._may_speak(job)))
        if speak:
            self._say(result, "question" if job.kind == "question" else "failure")
        if job.kind == "failure" and not result.get("error"):
            now = time.monotonic()
            self._rechecks.add(Look(job, tuple(result.get("causes") or ()), now, taken, spoken=speak,
                                    holes=len(result.get("contact") or ())), 0, now)

    def _may_speak(self, job: Job) -> bool:
        """Whether an unasked explanation is said aloud (NodeOptions.speak_every_s, live/jobs.py SPEAK_*); it is
        published either way."""
        now = time.monotonic()
        if now - job.received > SPEAK_STALE_S or (self._speech is not None and not self._speech.take(now)):
            self.unspoken += 1
            return False
        return True

    def _recheck(self, look: Look) -> None:
        """Look again at an unasked explanation (live/recheck.py): when records stamped before the failure came
        in late since the last look, explain it anew, and publish a correction if the causes changed, or if it now
        knows of a hole in what it heard that the last answer did not tell (the messages a writer no longer kept
        are known lost only when the next one arrives, which a stalled link can bring after the failure)."""
        job, n = look.job, look.n + 1
        if not self.log.late_since(look.since, job.t + int(self.options.settle_s * NS)):
            self._rechecks.add(replace(look, n=n), n, look.answered)
            return
        taken = time.monotonic()
        self._session.use_log(self.log.snapshot())
        thread = f"{RECHECK}{self._session.new_thread()}"  # thrown away unless it becomes the correction's
        try:
            result = dict(self._session.ask(job.text, thread=thread, task=job.task_id or None))
        except EventsError:
            result = {"error": "no task"}
        causes = tuple(result.get("causes") or ())
        shape(result, self._session.context.log.tasks, self.log.contact, self.log.newest)
        holes = len(result.get("contact") or ())
        if result.get("error") or (causes == look.causes and holes <= look.holes):
            self._session.graph.checkpointer.delete_thread(f"{self._session.settings.recording}::{thread}")
        else:
            # the corrected answer's thread becomes the dialogue a "why?" continues
            self._remember(thread)
            self.thread, self._last_answer, self.corrections = thread, time.monotonic(), self.corrections + 1
            result.update(trigger="correction", corrects=list(look.causes), recording=self.log.name, event_t=job.t,
                          sentence=short_sentence(str(result.get("answer", ""))),
                          latency_ms=round((time.monotonic() - job.received) * 1000, 1))
            self._publish(result)
            if look.spoken:
                self._say(result, "correction")
            look = replace(look, causes=causes, holes=holes)
        self._rechecks.add(replace(look, n=n, since=taken), n, look.answered)

    def _remember(self, thread: str) -> None:
        """Keep the checkpoints of the last KEEP_THREADS dialogues only: a node that runs for weeks must not
        collect every conversation it ever had in memory."""
        if thread in self._threads:
            return
        self._threads.append(thread)
        while len(self._threads) > KEEP_THREADS:
            old = self._threads.pop(0)
            self._session.graph.checkpointer.delete_thread(f"{self._session.settings.recording}::{old}")

    def _say(self, result: dict[str, Any], kind: Literal["failure", "question", "correction"]) -> None:
        from hexar.voice.loop import say_answer

        if kind == "question":
            utterances = say_answer(result)
        else:  # unasked: its first sentence
            utterances = [f"Correction: {result['sentence']}" if kind == "correction" else str(result["sentence"])]
        turn = f"answer_{self.answers:03d}"
        for speaker in self.speakers:
            try:
                speaker.say(utterances, turn)
            except Exception as err:  # a TTS that fails must not stop the node from answering
                self.errors += 1
                print(f"hexar serve: cannot speak with {speaker.name}: {err}", file=sys.stderr)

    def _publish(self, result: dict[str, Any]) -> None:
        """Out on /hexar/answer with every recorded string made visible: a dashboard or a robot's TTS reading
        the values gets no escape sequence or bidi override from a hostile log line."""
        self.answers += 1
        clean = dict(finite_with_warnings(result, clean=True))
        result.clear()
        result.update(clean)  # the caller speaks the same, cleaned answer
        self.transport.publish(ANSWER, json_dumps(result, clean=True))
        if self.on_answer is not None:
            self.on_answer(result)
