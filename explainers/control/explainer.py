"""The control (ros2_control) component explainer: controller_manager, the spawners, hardware interfaces and the
stock controllers (joint_trajectory_controller first), read from /rosout through the mined ros2_control catalogue.

Causes, by the earliest decisive line (explainers/logcause.py; the spawner's "Failed loading controller" or
"Failed to activate controller" is a symptom of the controller manager's line before it): controller_load_failed,
controller_activation_failed, hardware_failure, tolerance_violated, configuration_error, nominal, and
unexplained_failure (the first error no catalogue explains, quoted with its node and time, and the
candidates). A bring-up or device line before them is cited first, and so is a driver's line whose strerror text
or set-up words state the why (explainers/stated_causes.py). MoveIt's lines in the window (the control explainer
asked by manipulation) are read too, so that its symptoms are recognised as such.

A controller manager that only waited for its robot description (explainers/control/description.py) is read as
the description that never reached it when the recording shows it subscribe first, else told with both readings.

A driver's ERROR that no rule gives a cause, the window's first unexplained error, is read by where the driver
logs it (explainers/control/driver_roles.py) once nothing else decided (no rule, bring-up line or stated cause): its
read()/write() could not exchange with the device, its on_init found its set-up did not fit, its switch callback
would not take the controllers' interfaces. One logged where a driver reads its set-up and starts (on_init alone,
or a line it also logs in write() before anything shows the controllers running) is quoted with that place, and no
cause.
"""

from __future__ import annotations

import re
from typing import ClassVar

from hexar.events.records import LogLine
from hexar.events.tasks import SkillRun
from hexar.explainers.base import Context, Evidence, Explanation
from hexar.explainers.control import clock, gripper, limits, spawners
from hexar.explainers.control.catalogue import REFUSED, catalogue
from hexar.explainers.control.description import description_reading, waited, waiting_answer
from hexar.explainers.control.driver_roles import RoleReading, by_role
from hexar.explainers.control.wording import role_template, template
from hexar.explainers.logcause import Diagnosis, ModuleCatalogue, Reading, at
from hexar.explainers.manipulation.catalogue import catalogue as moveit_catalogue
from hexar.explainers.module_explainer import ModuleExplainer, focus
from hexar.explainers.module_wording import verbatim

CM_NOT_AVAILABLE = re.compile(r"^Controller manager not available\b")  # the spawner's, as its catalogue entry
ACTIVATION = "control.controller_activation_failed"
SKILLS = ("follow_joint_trajectory", "command_gripper", "bring_up_controllers", "pick", "place", "move_arm")


class ControlExplainer(ModuleExplainer):
    """Explains the robot's controllers and hardware interfaces (ros2_control)."""

    name: ClassVar[str] = "control"
    skills: ClassVar[tuple[str, ...]] = SKILLS
    prefix: ClassVar[str] = "control."
    module_words: ClassVar[str] = "my controllers"  # a mobile base has them too: nothing says whose
    description: ClassVar[str] = (
        "Explains the robot's motor controllers and hardware interfaces (ros2_control): why a controller could "
        "not be loaded or activated, why the hardware interface failed, why a joint trajectory was aborted "
        "(tolerance violated), and whether a trajectory was followed fine. Use it for questions about the "
        "controllers, joints, motors or hardware."
    )

    # resource_manager.cpp:68@jazzy logs it whenever a hardware component's lifecycle transition does not reach its
    # target state: on_configure/on_activate of the plugin decided, and a device out of reach and a set-up that
    # does not fit the robot (its parameters, a real robot's driver started where mock hardware was meant) end alike
    ambiguous: ClassVar[dict[str, str]] = {
        "hardware_interface.failed_to_hardware": (
            "It may be either: its device could not be reached, or its set-up does not fit this robot (its "
            "parameters, or the driver of a real robot started without one where mock components were meant)."),
    }

    candidates: ClassVar[str] = ("It may be a controller's settings (its parameters, joints or interfaces), its "
                                 "hardware interface's settings, or its device.")

    def candidates_of(self, first: LogLine | None) -> str:
        # spawner.py (controller_manager/scripts, :120@foxy) gives up after waiting for the controller manager's
        # services ("Waiting for '/controller_manager' node to exist" before it): no controller was ever asked
        # for, so a controller's settings cannot be why; what hosts the controller manager can
        if first is not None and CM_NOT_AVAILABLE.search(first.msg):
            return ("My spawners waited for my controller manager, which never appeared, so no controller was "
                    "loaded at all. It may be that what runs it (ros2_control_node, or a simulator's ros2_control "
                    "plugin such as gz_ros2_control) was not started or is missing, died as it started, or runs "
                    "under another name or namespace than the spawners looked for.")
        return self.candidates

    def decided(self, lines: list[LogLine], context: Context) -> Explanation | None:
        # spawners that asked for a controller manager that is not there loaded nothing, whatever else came up
        # (a start derived from the log would otherwise read the hardware's start as a bring-up that went fine)
        # the controller manager says which clock it runs on as it starts, before any window of a goal
        stalled = clock.stalled([ln for ln in context.log.logs if ln.t <= context.window[1]])
        if stalled is not None:
            return clock.answer(self.name, stalled)
        told = gripper.open_goal(self.name, context.task, context.log.logs, context.window[1])
        if told is not None:
            return told
        run = focus(context, self.skills)
        beyond = limits.beyond_limits(lines) if run is not None and run.state == "failed" else None
        if beyond is not None:
            return limits.answer(self.name, beyond, self._what(run))
        found = spawners.other_manager(lines)
        if found is not None:
            return spawners.answer(self.name, found)
        if not spawners.gave_up(lines):
            # a goal refused by a controller left inactive: its configure came at the start, before the goal's window
            inactive = spawners.never_activated(lines) or (spawners.never_activated(
                [ln for ln in context.log.logs if ln.t <= context.window[1]]) if run is not None else None)
            return spawners.inactive_answer(self.name, inactive) if inactive is not None else None
        # the robot description that came after the spawners gave up may lie after a window that ends with them
        early = spawners.gave_up_early([*lines, *self.lines_after(context)])
        return spawners.early_answer(self.name, early, lines[0].t) if early is not None else None

    def catalogues(self) -> list[ModuleCatalogue]:
        return [catalogue(), moveit_catalogue()]

    def reason_before(self, context: Context, d: Diagnosis) -> Diagnosis:
        """The trajectory controller refused the goal as not active, and before the goal (at the controllers' start)
        the controller manager said why it could not activate it: that line is kept as the first support."""
        if d.cause != ACTIVATION or d.decisive is None or d.decisive.entry is None or d.decisive.entry.id != REFUSED:
            return d
        # the controller manager's reason, not the spawner's "Failed to activate" that follows from it
        why = [r for r in self.readings_before(context) if r.cause == ACTIVATION
               and (r.entry is None or (r.entry.id != REFUSED and r.entry.kind != "symptom"))]
        if why and all(r.line is not why[0].line for r in d.support):
            d.support = [why[0], *d.support][:3]
        return d

    def refine(self, readings: list[Reading]) -> list[Reading]:
        return description_reading(readings)

    def words(self, cause: str, d: Diagnosis, what: str) -> tuple[str, str | None, list[str]]:
        if isinstance(d.decisive, RoleReading) and d.decisive.cause == cause:
            worded = role_template(cause, d, what, d.decisive.note)
            if worded is not None:
                return worded
        return template(cause, d, what)

    def _compose(self, context: Context, d: Diagnosis, readings: list[Reading], run: SkillRun | None
                 ) -> Explanation:
        waiting = waited([r.line for r in readings]) if d.cause is None and d.unknown is None else None
        if waiting is not None and d.outcome == "failed":
            what = self._what(run)
            return waiting_answer(self.name, f"{self.prefix}unexplained_failure", f"{what[:1].upper()}{what[1:]} "
                                  "failed, but my control logs do not show a cause I know.", waiting,
                                  context.task.created)
        placed = _placed(d, readings)
        if placed is None:
            return super()._compose(context, d, readings, run)
        if placed.role is not None and placed.role.cause is not None:
            # the first unexplained error is a driver's, and where it is logged tells what failed
            d.cause, d.decisive, d.unknown, d.support = placed.role.cause, placed, None, []
            d.symptoms = [r for r in d.symptoms if r.line.t >= placed.line.t][:2]
            return super()._compose(context, d, readings, run)
        # a driver's error whose place tells no cause (set-up or device): quoted with its place, none claimed
        line, meaning = placed.line, placed.note
        cause = f"{self.prefix}unexplained_failure"
        what = self._what(run)
        head = (f"{what[:1].upper()}{what[1:]} failed" if d.outcome == "failed"
                else f"The recording ends before {self.module_words} finished; on the way a driver reported an error")
        return Explanation(
            explainer=self.name, causes=[cause], evidence=[Evidence.of_log(cause, line)], confidence=0.4,
            text=f"{head}, but my control logs do not show a cause I know: {verbatim(line)} at "
                 f"{at(line, context.task.created)}; {meaning}. It may be that set-up (the ros2_control tag of my "
                 f"robot description, or a file the line names) or the device it starts.",
            fix="Check what the quoted line names against the driver's documentation; the driver's lines before it "
                "and its device's own status tell which.",
            details=["The line's place in the driver's source tells where it failed, not why."])


def _placed(d: Diagnosis, readings: list[Reading]) -> RoleReading | None:
    """The first unexplained error read by its role, when it is a driver's line the catalogue places and nothing
    decided before (no rule, no bring-up line, no stated cause, no words of its own that leave candidates open)."""
    if d.cause is not None or d.unknown is None or d.outcome == "succeeded" or d.candidates:
        return None
    index = next((i for i, r in enumerate(readings) if r.line is d.unknown), None)
    return by_role(readings[index], readings[:index]) if index is not None else None
