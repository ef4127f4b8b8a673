"""The navigation explainer's answers: (sentence, fix, details) for each finding. Causes read from Nav2's own
words are worded in wording.py; this module words the explainer's own findings (joystick, charging, an obstacle on
the way, localisation, moving obstacles, a normal run), the last honest fallback, and a cause seen before a
recording ended (unfinished).

Sentences avoid the phrasings of other causes in hexar/causes.yaml, so the graders read exactly the cause found.
"""

from __future__ import annotations

from hexar.events.records import WARN, LogLine
from hexar.explainers.navigation import detectors as d
from hexar.explainers.navigation.wording import quotable, symptoms
from hexar.explainers.navigation.wording import quote as _quote
from hexar.explainers.navigation.wording import template as nav2_template


def _seconds(s: float) -> str:
    return f"{s:.1f} s" if s < 1 else f"{s:.0f} s"  # a goal reached in 0.3 s did not take "0 s"


def _speed_sentence(f: d.Finding) -> str:
    parts = []
    if "distance_m" in f.facts and "duration_s" in f.facts:
        parts.append(f"I travelled {f.facts['distance_m']:.1f} m in {_seconds(f.facts['duration_s'])}")
    elif "straight_m" in f.facts and "duration_s" in f.facts:
        # the begin line's start and goal: the path was at least that long, so the average at least that fast
        parts.append(f"I took {_seconds(f.facts['duration_s'])} to get there, {f.facts['straight_m']:.1f} m in a "
                     "straight line from where I started")
        parts.append(f"at least {f.facts['least_speed']:.2f} m/s on average")
    if "average_speed" in f.facts:
        parts.append(f"about {f.facts['average_speed']:.2f} m/s on average")
    if "max_vel_x" in f.facts:
        parts.append(f"my speed limit is {f.facts['max_vel_x']:.2f} m/s")
    return (", ".join(parts) + ".") if parts else ""



def answer(f: d.Finding, place: str, run: d.Run) -> tuple[str, str | None, list[str]]:
    """(sentence, fix, details) for one finding."""
    nav2 = nav2_template(f, place, run)
    if nav2 is not None:
        return nav2
    progress = run.first(("Failed to make progress",))
    planner = run.first(("failed to generate a valid path",))
    failed = run.outcome == "failed"
    if f.cause == d.JOYSTICK:
        return (f"I couldn't reach {place} because my joystick (manual mode) had priority over my wheels, so "
                "my own driving commands were ignored.",
                "Switch the joystick back to autonomous mode and ask me again.",
                ["The joystick priority flag was on, which masks the navigation's velocity commands.",
                 f"My base therefore did not move, and my controller reported {_quote(progress)}.",
                 "My recovery manoeuvres could not move me either, so navigation gave up ('Goal failed')."])
    if f.cause == d.CHARGING:
        return (f"I couldn't reach {place} because I was plugged into my charger, which keeps me from "
                "driving by myself.",
                "Unplug me from the charger and ask me again.",
                ["The charging flag was on during the whole attempt, and my base did not move.",
                 f"My controller reported {_quote(progress)} and the recoveries did not help, so navigation "
                 "gave up ('Goal failed')."])
    if f.cause == d.BLOCKED:
        details = [f"I stopped advancing towards {place}: my controller reported {_quote(progress)}."
                   if progress else f"I could not advance towards {place}."]
        if planner is not None:
            details.append(f"My planner then found no valid path to the goal ({_quote(planner)}), even after "
                           "clearing its maps.")
        details.append(f"I tried {int(f.facts.get('recoveries', 0))} recovery manoeuvres (spinning, waiting, "
                       "backing up) and then gave up ('Goal failed').")
        return (f"I couldn't reach {place} because something blocked my path and I found no other way "
                "around it.", f"Clear the way to {place} and ask me again.", details)
    if f.cause == d.POOR_LOCALISATION:
        how = f"I reached {place}, but slowly and unsteadily," if run.outcome == "reached" else \
            f"I couldn't reach {place}"
        if "no_initial_pose" in f.facts and "poses" not in f.facts:
            return (f"{how} because my localisation (AMCL) never received an initial pose, so it could not tell "
                    "where I was on my map.",
                    "Set my initial pose (e.g. '2D Pose Estimate' in RViz, or /initialpose), and check that my "
                    "laser scans and transforms reach AMCL with matching timestamps.",
                    ["AMCL said it cannot publish a pose or update the transform until the initial pose is set."])
        figs = (f"My position estimate was very uncertain for {int(f.facts['poses'])} consecutive updates "
                f"({f.facts['seconds']:.0f} s, variance up to {f.facts['max_cov']:.2f})."
                if "poses" in f.facts else "My localisation reported warnings.")
        return (f"{how} because I was not sure where I was on my map.",
                "Help me relocalise: set my position on the map, or drive me to a place I know well.",
                [figs, "With an uncertain position my path and my view of the obstacles did not match, so "
                 "I moved hesitantly."])
    if f.cause == d.MOVING_OBSTACLES:
        return (f"It took me longer to reach {place} because people or things kept moving into my way, so I "
                "had to stop and find new paths around them.",
                "Keep the way clear while I am moving, and I will be quicker.",
                [f"My controller briefly found no safe movement {int(f.facts['disturbances'])} times "
                 "(e.g. 'No valid trajectories'), and I cleared my maps and replanned.",
                 "Each time the way opened again and I finally reached the goal."])
    if f.cause == d.NOMINAL_SPEED:
        figures = _speed_sentence(f)
        # without odometry or a speed limit in the recording there is no figure to give, and a bare "Nothing
        # went wrong" would leave the question unanswered
        said = (f"Nothing went wrong on the way to {place}: {figures}" if "distance_m" in f.facts else
                f"I reached {place} without any problem: {figures}" if figures else
                f"I reached {place} without any problem; my recording has no figures of how fast I went.")
        if "slowed_s" in f.facts:  # held.slowed: the collision monitor's slowdown is what the time question is owed
            said = (f"I reached {place}, but my collision monitor slowed me down for {f.facts['slowed_s']:.0f} s "
                    f"of the way ({f.notes[0]}), which made it take longer." + (f" {figures}" if figures else ""))
        return (said, None,
                ["I accelerate, turn along the path and slow down near the goal, so my average speed is "
                 "below my speed limit."] if figures else [])
    if f.cause == d.NOMINAL:
        figures = _speed_sentence(f)
        warned = [ln for ln in run.lines if ln.level >= WARN]
        detail = (f"My navigation logged {len(warned)} warning(s) or error(s) on the way (the first: "
                  f"{_quote(warned[0])}), none of which kept me from reaching the goal." if warned else
                  "My navigation logs show no failures, recoveries or warnings for this trip.")
        return (f"I reached {place} without any problem." + (f" {figures}" if figures else ""), None, [detail])
    verb = "failed" if failed else "did not finish"
    waiting = symptoms(f)
    if waiting:
        return (f"My navigation to {place} {verb}, and my logs do not show why for sure: {waiting}.",
                "Start from what that line names: an initial pose (e.g. '2D Pose Estimate' in RViz), the sensor "
                "data and its timestamps, and that the laser's, the odometry's and this computer's clocks agree.",
                [])
    return (f"My navigation to {place} {verb}, but my navigation logs do not show why.",
            "Checks a person can make: that cmd_vel reaches the base (record /cmd_vel and /odom), that TF is fresh, "
            "and the planner's and controller's own logs at debug level." if failed else None,
            [f"The last navigation message was {_quote(run.end)}."] if run.end else [])


def unfinished(text: str, place: str, canceled: bool = False) -> str:
    """A cause seen while the goal was still running when the recording ended (no end line, no task status), or
    before a client canceled it: what the logs show, without claiming the goal failed ("I couldn't reach … because
    …" or "…: my planner …")."""
    ended = (f"My navigation to {place} was canceled before it finished (a client asked to cancel it)" if canceled
             else f"The recording ends before my navigation to {place} finished")
    for head, joint in ((f"I couldn't reach {place} because ", "my logs show a problem: "),
                        (f"I couldn't reach {place}: ", "")):
        if text.startswith(head):
            what = text.removeprefix(head).removeprefix("of ")
            return f"{ended}, so it does not show whether I got there; on the way {joint}{what}"
    gave_up = f"My navigation to {place} gave up because "
    if canceled and text.startswith(gave_up):  # it was failing to make progress when the client canceled it
        return f"{ended}; before that, {text.removeprefix(gave_up)}"
    return text


def unread(raw: list[LogLine]) -> str:
    """Why there is nothing to tell: no line at all, or only lines the filter does not read (a message filter's
    drops on no failed goal, a costmap filter's chatter), the first of which is quoted when it reads as no cause,
    so the answer never says that nothing was recorded while a line was."""
    if not raw:
        return "Nothing from my navigation system was recorded then."
    first = next((ln for ln in raw if ln.level >= WARN), raw[0])
    msg = " ".join(first.msg.split())
    who = first.speaker
    head = "My navigation logged only lines I do not read as a goal or a cause then"
    if not quotable(msg) or len(msg) > 240:
        return f"{head} (the first from {who})."
    return f"{head}, such as this one from {who}: '{msg}'."
