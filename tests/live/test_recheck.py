"""The node's second looks at its unasked explanations (live/recheck.py) and the job queue's wait."""

from __future__ import annotations

import threading
import time

from hexar.live.jobs import Job, JobQueue
from hexar.live.recheck import AFTER_S, MAX_WAITING, Rechecks


def test_looks_come_due_in_time_order_and_end_after_the_last() -> None:
    looks: Rechecks[str] = Rechecks()
    now = time.monotonic()
    assert looks.wait_s() is None
    assert looks.add("later", 1, now) and looks.add("sooner", 0, now - AFTER_S[0])
    assert looks.take_due() == ["sooner"]
    wait = looks.wait_s()
    assert wait is not None and AFTER_S[1] - 0.5 < wait <= AFTER_S[1]
    assert not looks.add("none", len(AFTER_S), now)  # no look after the last
    assert len(looks) == 1


def test_a_burst_of_failures_keeps_the_looks_due_first() -> None:
    looks: Rechecks[int] = Rechecks()
    now = time.monotonic() - 100.0
    for i in range(MAX_WAITING + 5):
        looks.add(i, 0, now + i)
    assert len(looks) == MAX_WAITING and looks.dropped == 5
    assert looks.take_due() == list(range(MAX_WAITING))


def test_the_queue_wait_ends_with_a_job_or_the_timeout() -> None:
    jobs: JobQueue[Job] = JobQueue({})
    start = time.monotonic()
    assert jobs.get(timeout=0.1) is None and time.monotonic() - start >= 0.1
    threading.Timer(0.05, jobs.put, (Job("question", text="why?"),)).start()
    got = jobs.get(timeout=5.0)
    assert got is not None and got.text == "why?"


def test_a_question_goes_before_waiting_unasked_explanations() -> None:
    jobs: JobQueue[Job] = JobQueue({}, first=("stop", "question"))
    for i in range(5):
        jobs.put(Job("failure", task_id=f"t{i}"))
    jobs.put(Job("question", text="why?"))
    got = [jobs.get(timeout=0.1) for _ in range(6)]
    assert [j.kind if j else None for j in got] == ["question"] + ["failure"] * 5
    assert [j.task_id for j in got[1:] if j] == [f"t{i}" for i in range(5)]  # the rest in the order they came
