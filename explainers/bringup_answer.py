"""The answer about the robot's start when the recording had no task and no goal (events/bringup.py derived it).

A start that completed is told plainly as such: what came up (ros2_control's own "Configured and activated",
"Successful initialization of hardware" lines), and each warning on the way named as one that only looks like a
failure. A start the recording does not see complete, with no error on the way, is told as that: what began, that
nothing went wrong that the recording shows, and that it ends before a line says the start completed (every such
start in the spent module sets was a run that went fine: a demo's hardware writing its commands, a driver's check
that passed, a deprecation warning). When the question says the start did not work ("why didn't that work?"), the
person knows an outcome the recording does not show: the answer is then that no line says why. A warning on the way
is quoted, never claimed as the cause, but for one: a controller manager whose clock never started (use_sim_time
with nothing on /clock), told so when asked why the start did not work. A controller that dropped commands because
it was not active is told as that, with what can leave a controller inactive (never activated, its activation not
gone through, deactivated later), none of them claimed; a controller manager still waiting for its robot
description, as explainers/control/description.py reads it. A failed start is the module explainer's ordinary
failure answer (the earliest decisive line); when no line says why and the error is a device
driver's, its candidates are the driver's (`driver_candidates`), not a controller's.
"""

from __future__ import annotations

import re

from hexar.events.bringup import (
    completed,
    control_logger,
    helper_exit,
    moveit_logger,
    names_device,
    names_parameter,
    refused,
    starting,
)
from hexar.events.records import WARN, LogLine
from hexar.events.tasks import SkillRun
from hexar.explainers.base import Evidence, Explanation
from hexar.explainers.logcause import at
from hexar.explainers.module_wording import verbatim

BRING_UP = "bring_up_controllers"
MAX_QUOTED = 3
MAX_WARNED = 2
# what leaves a driver's start failed when its error names no cause: in words no cause pattern reads as a claim
DRIVER_CANDIDATES = ("It may be the driver's settings (the port, address or baud rate it was given), the device itself "
                     "(its cable, its power, or another device on that port), or the access rights to its device "
                     "file.")
PARAMETER_CANDIDATES = ("It may be the value of the parameter it names, or how that value is given to the node (its "
                        "launch or parameter file, the node's name or namespace there).")
# a question that tells the start did not work, or asks what went wrong in it
_FAILURE_WORDS = re.compile(r"n't\b|\b(not|never|fail\w*|wrong|errors?|problems?|broke\w*|crash\w*|stuck|abort\w*|"
                            r"stop\w*)\b", re.I)


def presumes_failure(question: str) -> bool:
    """The question says something did not work ("why didn't that work?", "what went wrong?"), unlike "how did it
    go?" or "what happened?"."""
    return _FAILURE_WORDS.search(question) is not None


def derived_start(run: SkillRun | None) -> bool:
    """The step is a start derived from the logs (not a /task_info step), and it did not fail (it completed, is
    under way, or was stopped first)."""
    return (run is not None and run.skill == BRING_UP and run.params.get("source") == "bringup"
            and run.state in {"succeeded", "running", "canceled"})


def start_answer(explainer: str, prefix: str, run: SkillRun, lines: list[LogLine], t0: int,
                 question: str = "", down: list[LogLine] | None = None) -> Explanation:
    """`lines` are the start's up to where the stack began to shut down, `down` the lines from there on."""
    # the control package's __init__ imports its explainer, which imports the module explainer, which imports this
    from hexar.explainers.control.description import waited

    if run.state == "canceled" and not any(refused(ln) for ln in lines) and waited(lines) is None:
        return _stopped(explainer, prefix, lines, down or [], t0)  # a start stuck on something is told as that
    if run.state == "succeeded" and presumes_failure(question):
        return _started_then(explainer, prefix, lines, t0)
    if run.state == "succeeded":
        warned = [ln for ln in lines if ln.level == WARN][:MAX_WARNED]
        came = [ln for ln in lines if completed(ln)]
        last = came[-1].t if came else t0
        cause = f"{prefix}nominal"
        # a hardware interface that came up is not a controller that did ("were any controllers loaded?")
        controllers = any("controller" in ln.msg.lower() for ln in lines)
        what = "my controllers" if controllers else "my hardware"
        text = (f"Starting my drivers and controllers went fine: nothing went wrong, and {what} came up without any "
                "problem. What came up: " + "; ".join(verbatim(ln) for ln in came[:MAX_QUOTED]) + "." +
                ("" if controllers else " My log names no controller being loaded or started."))
        for w in warned:
            after = "the start completed after it" if w.t <= last else "no error followed it"
            text += f" {verbatim(w)} at {at(w, t0)} is a warning that only looks like a failure: {after}."
        return Explanation(explainer=explainer, text=text, causes=[cause],
                           evidence=[Evidence.of_log(cause, ln) for ln in came[:MAX_QUOTED]],
                           details=[f"{len(came)} line(s) say a part of my start completed, and no error followed."])
    refusal = next((ln for ln in lines if refused(ln)), None)
    if refusal is not None:
        return _refusal_answer(explainer, prefix, refusal, t0)
    waiting = waited(lines)
    if waiting is not None:
        return _waiting_answer(explainer, prefix, lines, waiting, t0)
    # told the start did not work, the one thing the recording shows wrong is a clock that never came; asked how it
    # went, a start cut short after that warning is still under way (a clock often comes a second later)
    clockless = no_clock(lines) if presumes_failure(question) else None
    if clockless is not None:
        return _no_clock_answer(explainer, clockless, t0)
    return _under_way(explainer, prefix, lines, t0, question)


# Python's own words for an interrupted program (its traceback's last line), and launch's for a process that ended
# on a signal (launch/actions/execute_local.py: "process has died [pid %d, exit code %d, cmd '%s']", -2 for SIGINT)
_INTERRUPTED = re.compile(r"\bKeyboardInterrupt\b|\bExternalShutdownException\b")
_SIGNAL_EXIT = re.compile(r"process has died \[pid \d+, exit code -(2|15)\b")


def _stopped(explainer: str, prefix: str, lines: list[LogLine], down: list[LogLine], t0: int) -> Explanation:
    """A start that was stopped (Ctrl-C, a signal) before anything failed: no failure, and what its processes
    printed on the way down (a Python node's KeyboardInterrupt traceback, a death by that signal) said as such."""
    cause = f"{prefix}nominal"
    stop = down[0] if down else None
    said = f"{verbatim(stop)} at {at(stop, t0)}" if stop is not None else "a stop"
    text = (f"Starting my drivers and controllers went fine: my controllers were starting without any problem when "
            f"it was stopped from outside ({said}), and my processes were shut down.")
    helpers = [ln for ln in lines if helper_exit(ln, lines)]
    for ln in helpers:
        m = re.search(r"cmd '([^']*)'", ln.msg)
        text += (f" Before that, {verbatim(ln)} at {at(ln, t0)}: a command launch ran for the set-up"
                 f"{f' ({m[1]})' if m else ''}, not one of my nodes, ended with an error, and my nodes went on after "
                 "it, so it stopped nothing.")
    shown = [ln for ln in lines if ln.level >= WARN and all(ln is not h for h in helpers)][:MAX_WARNED]
    if shown:
        said = "; ".join(f"{verbatim(w)} at {at(w, t0)}" for w in shown)
        text += f" {'The warnings' if len(shown) > 1 else 'The warning'} on the way ({said}) stopped nothing either."
    noisy = [ln for ln in down if _INTERRUPTED.search(ln.msg) or _SIGNAL_EXIT.search(ln.msg)]
    fix = None
    if any(_INTERRUPTED.search(ln.msg) for ln in noisy):
        who = next(ln.name for ln in noisy if _INTERRUPTED.search(ln.msg)) or "a Python node"
        text += (f" The traceback {who} printed on the way down is Python's KeyboardInterrupt, how a Python node "
                 "that does not catch the interrupt ends when Ctrl-C reaches it while it spins, not a failure of "
                 "mine.")
        fix = ("To let the node end quietly, catch the interrupt around its spin (`except (KeyboardInterrupt, "
               "ExternalShutdownException)` around `rclpy.spin(node)`, then shut down), as ROS 2's Python examples "
               "do.")
    elif noisy:
        text += f" {verbatim(noisy[0])} at {at(noisy[0], t0)} is that stop's signal, not a failure."
    return Explanation(explainer=explainer, text=text, causes=[cause], fix=fix,
                       evidence=[Evidence.of_log(cause, ln) for ln in [*([stop] if stop else []), *noisy[:2]]],
                       details=["Launch stopped my processes before any error; no line of my start failed."])


def _started_then(explainer: str, prefix: str, lines: list[LogLine], t0: int) -> Explanation:
    """Asked why something did not work, where the only task the logs give is a start that completed: the start is
    told as it went, and what failed after it is said to be beyond what the logs show (a teleop's commands that never
    matched the controller's topic leave no line), never that nothing went wrong."""
    came = [ln for ln in lines if completed(ln)]
    warned = [ln for ln in lines if ln.level == WARN and ln.t > (came[-1].t if came else t0)][:1]
    cause = f"{prefix}unexplained_failure"
    seen = (f" After it, the first warning was {verbatim(warned[0])} at {at(warned[0], t0)}, which healthy robots "
            "print too." if warned else "")
    return Explanation(
        explainer=explainer, causes=[cause], confidence=0.3,
        evidence=[Evidence.of_log(cause, ln) for ln in [*came[-1:], *warned]],
        text="My drivers and controllers started: " + "; ".join(verbatim(ln) for ln in came[:MAX_QUOTED])
             + ". My logs do not show what did not work after that: no error names it, and no goal of my "
             f"controllers is in them.{seen}",
        fix="Check what was asked of the robot after its start (a command that never reached a controller, on a "
            "topic or of a message type it does not listen to, leaves no line), and record its goals or commands.",
        details=[f"{len(came)} line(s) say a part of my start completed, and no error followed."])


# controller_manager.cpp:3401-3403@jazzy (3409-3411@master), in update(): a WARN throttled to once a second while the
# node's clock has not started, which "can happen with use_sim_time=true until the /clock is received" (its comment)
NO_CLOCK = "No clock received, using time argument instead!"


def no_clock(lines: list[LogLine]) -> LogLine | None:
    """The controller manager's last no-clock warning when nothing came up after it: its clock never started."""
    said = next((ln for ln in reversed(lines) if ln.msg.strip().startswith(NO_CLOCK)), None)
    if said is None or any(completed(ln) and ln.t >= said.t for ln in lines):
        return None
    return said


def _no_clock_answer(explainer: str, line: LogLine, t0: int) -> Explanation:
    """A start whose controller manager never had a clock: on simulated time it waits for /clock, which nothing sent."""
    from hexar.explainers.control.description import BRINGUP

    return Explanation(
        explainer=explainer, causes=[BRINGUP], confidence=0.6, evidence=[Evidence.of_log(BRINGUP, line)],
        text="Starting my drivers and controllers did not complete as far as my recording shows, and what it shows "
             "wrong is that my controller manager never received a clock: it runs on simulated time (use_sim_time) "
             "and nothing published /clock to it, so my controllers could not run on time. The line that says so: "
             f"{verbatim(line)} at {at(line, t0)}.",
        fix="Bridge the simulator's clock to ROS (ros_gz_bridge's /clock, or the simulator's ROS clock plugin), or "
            "set use_sim_time to false where no simulator runs.",
        details=["controller_manager.cpp:3401-3403@jazzy: warned while its clock had not started, and no line says "
                 "a controller came up after it."])


def _under_way(explainer: str, prefix: str, lines: list[LogLine], t0: int, question: str) -> Explanation:
    """A start with no error that the recording does not see complete. MoveIt's own lines with none of
    ros2_control's (moveit_servo starting) are the arm's motion software starting."""
    began = next((ln for ln in lines if starting(ln)), lines[0])
    arm = moveit_logger(began.name) and not any(control_logger(ln.name) or completed(ln) for ln in lines)
    what, verb = ("my arm's motion software (MoveIt)", "was") if arm else ("my drivers and controllers", "were")
    # a warning said again (Servo's singularity warning, once per check) is quoted once
    warned = list({(w.name, w.msg): w for w in reversed(lines) if w.level == WARN}.values())[::-1][:MAX_WARNED]
    shown = "" if began in warned else f" ({verbatim(began)} at {at(began, t0)})"
    if presumes_failure(question):
        text = (f"My logs do not show why: the recording shows me starting {what}{shown}, and no line reports an "
                "error or a failure. It ends before any line says the start completed.")
        for w in warned:
            text += (f" On the way, {verbatim(w)} at {at(w, t0)} is a warning; healthy robots print many, so my "
                     "logs do not show whether it stopped the start.")
        return Explanation(explainer=explainer, text=text, causes=[], confidence=0.3,
                           evidence=[Evidence.of_log("warning", w) for w in warned],
                           fix="Record the whole start (from launch on) to see whether it completed.")
    cause = "manipulation.nominal" if arm else f"{prefix}nominal"
    text = (f"Nothing went wrong that my recording shows: {what} {verb} starting without any problem{shown}, and "
            "no line reports an error or a failure. The recording ends before any line says the start completed.")
    for w in warned:
        text += f" {verbatim(w)} at {at(w, t0)} is a warning, and no error followed it."
    last = max(ln.t for ln in lines)
    return Explanation(explainer=explainer, text=text, causes=[cause], confidence=0.5,
                       evidence=[Evidence.of_log(cause, began), *(Evidence.of_log("warning", w) for w in warned)],
                       details=[f"{len(lines)} line(s) from {at(began, t0)} to {(last - t0) / 1e9:.1f} s, none at "
                                "ERROR or FATAL."],
                       fix="Record the whole start (from launch on) to see it complete.")


def _waiting_answer(explainer: str, prefix: str, lines: list[LogLine], waiting: LogLine, t0: int) -> Explanation:
    """A start held up by a controller manager still waiting for its robot description (explainers/control/
    description.py): the description that never arrived when the recording shows the manager subscribe first, else
    both readings and no cause. Either way the start could not complete, so "why didn't that work?" is answered by
    this finding rather than by a plan that looks right."""
    from hexar.explainers.control.description import BRINGUP, MEANING, never_arrived, waiting_answer

    if never_arrived(lines, waiting):
        return Explanation(
            explainer=explainer, causes=[BRINGUP], confidence=0.7, evidence=[Evidence.of_log(BRINGUP, waiting)],
            text=f"Starting my drivers and controllers could not complete because a parameter never reached one of "
                 f"my nodes: {MEANING}. The line that says so: {verbatim(waiting)} at {at(waiting, t0)}.",
            fix="Start robot_state_publisher with the robot description, in the controller manager's namespace.",
            details=["controller_manager.cpp:759-777@jazzy: it subscribed, then warned once a second, and no "
                     "'Received robot description from topic.' followed."])
    return waiting_answer(explainer, f"{prefix}unexplained_failure", "Starting my drivers and controllers had not "
                          "completed, and my control logs do not show a cause I know.", waiting, t0)


def _refusal_answer(explainer: str, prefix: str, line: LogLine, t0: int) -> Explanation:
    """diff_drive_controller's refusal: it makes its command subscription when configured and accepts commands only
    once activated (diff_drive_controller.cpp:466@jazzy), so it was configured but not active when they came."""
    who = line.name or "a controller"
    # no "refused": that word is a person's refusal in hexar/causes.yaml
    text = (f"My controller {who} dropped the commands it was sent: {verbatim(line)} at {at(line, t0)}. It had been "
            "configured (it only listens for commands after that) but it was not active when they came. Either "
            "nothing activated it (a spawner that left it inactive or did not run), its activation did not go "
            "through, or it had been deactivated before (a deactivated controller drops commands the same way); my "
            "logs do not show why it was not active.")
    # the commands did fail, for a reason no line gives: the honest partial cause, so that "why didn't that work?"
    # is answered by this finding rather than by a plan that looks right
    cause = f"{prefix}unexplained_failure"
    return Explanation(explainer=explainer, text=text, causes=[cause], confidence=0.4,
                       evidence=[Evidence.of_log(cause, line)],
                       details=["That line's source: ros2_controllers diff_drive_controller.cpp:466@jazzy "
                                "(its command callback while subscriber_is_active_ is false)."],
                       fix=f"See whether {who} is active (`ros2 control list_controllers`), activate it (its spawner "
                           "without --inactive), and read the controller manager's lines of its activation.")


def driver_candidates(run: SkillRun | None, first: LogLine | None) -> str:
    """The candidates of a derived start that failed at a device driver's error (not one of ros2_control's lines);
    "" otherwise (the module's own candidates fit)."""
    if run is None or run.skill != BRING_UP or run.params.get("source") != "bringup" or first is None:
        return ""
    if control_logger(first.name) or completed(first):
        return ""  # ros2_control's own line: the module's candidates (a controller's or hardware's settings) fit
    return PARAMETER_CANDIDATES if names_parameter(first) and not names_device(first) else DRIVER_CANDIDATES
