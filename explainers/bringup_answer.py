"""The answer about the robot's start when the recording had no task and no goal (events/bringup.py derived it).

A start that completed is told plainly as such: what came up (ros2_control's own "Configured and activated",
"Successful initialization of hardware" lines), and each warning on the way named as one that only looks like a
failure. A start the recording does not see complete is told as that: what began, that no error followed, and that
the logs do not show what came of it; a warning on the way is quoted, never claimed as the cause. A failed start is
the module explainer's ordinary failure answer (the earliest decisive line), so it is not here.
"""

from __future__ import annotations

from hexar.events.bringup import completed, starting
from hexar.events.records import WARN, LogLine
from hexar.events.tasks import SkillRun
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.logcause import at

BRING_UP = "bring_up_controllers"
MAX_QUOTED = 3


def derived_start(run: SkillRun | None) -> bool:
    """The step is a start derived from the logs (not a /task_info step), and it did not fail."""
    return (run is not None and run.skill == BRING_UP and run.params.get("source") == "bringup"
            and run.state in {"succeeded", "running"})


def start_answer(explainer: str, prefix: str, run: SkillRun, lines: list[LogLine], t0: int) -> Explanation:
    from hexar.explainers.module_explainer import verbatim  # the module explainer asks this module first

    warned = [ln for ln in lines if ln.level == WARN][:2]
    if run.state == "succeeded":
        came = [ln for ln in lines if completed(ln)]
        last = came[-1].t if came else t0
        cause = f"{prefix}nominal"
        text = ("Starting my drivers and controllers went fine: nothing went wrong, and my controllers came up "
                "without any problem. What came up: " + "; ".join(verbatim(ln) for ln in came[:MAX_QUOTED]) + ".")
        for w in warned:
            after = "the start completed after it" if w.t <= last else "no error followed it"
            text += f" {verbatim(w)} at {at(w, t0)} is a warning that only looks like a failure: {after}."
        return Explanation(explainer=explainer, text=text, causes=[cause],
                           evidence=[Evidence.of_log(cause, ln) for ln in came[:MAX_QUOTED]],
                           details=[f"{len(came)} line(s) say a part of my start completed, and no error followed."])
    began = next((ln for ln in lines if starting(ln)), lines[0])
    text = (f"The recording shows me starting my drivers and controllers ({verbatim(began)} at {at(began, t0)}), "
            "but it ends before any line says the start completed. It shows no error, so my logs do not show what "
            "came of the start.")
    for w in warned:
        text += (f" On the way, {verbatim(w)} at {at(w, t0)} is a warning; healthy robots print many, so my logs "
                 "do not show whether it stopped the start.")
    return Explanation(explainer=explainer, text=text, causes=[], confidence=0.3,
                       evidence=[Evidence.of_log("warning", w) for w in warned],
                       fix="Record the whole start (from launch on) to see whether it completed.")
