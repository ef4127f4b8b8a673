"""The control explainer's sentences (explainers/module_wording.py): each fix fits its cause.

Phrasings avoid the words of other causes in hexar/causes.yaml ("failed to activate" and "misconfigured" are
Nav2's configuration error, "timed out" is text to speech's), so the graders read exactly the cause found.
"""

from __future__ import annotations

from hexar.explainers.logcause import Diagnosis, said
from hexar.explainers.module_wording import Worded, Wording

CLAUSES = {
    # hexar/causes.yaml: controller_load_failed implies configuration_error, so the sentence says both
    "control.controller_load_failed": (
        "a controller was set up wrongly: it was not loaded, as {meaning}.",
        "Install the controller's package (add it to package.xml) and declare the controller with its 'type' under "
        "controller_manager in the controllers yaml."),
    "control.controller_activation_failed": (
        "a controller could not be activated: {meaning}.",
        "Check that the controller manager's update loop runs (a paused simulation stops it), and that no other "
        "active controller claims the same command interfaces."),
    "control.hardware_failure": (
        "a hardware interface failed: it could not configure, activate or talk to its device.",
        "Check the device connection, its port and permissions, and the hardware parameters in the ros2_control "
        "URDF tag."),
    "control.tolerance_violated": (
        "my arm strayed from its planned trajectory beyond the controller's tolerance, so the joint trajectory "
        "controller aborted the motion.",
        "Look at the joint whose error exceeded its tolerance: a collision, a payload, controller gains, or "
        "tolerances too tight for this robot."),
    "control.configuration_error": (
        "a controller or its driver was set up wrongly: {meaning}.",
        "Fix the set-up the quoted line names: the controller's joints and interfaces against the ros2_control tag "
        "of the URDF, or the driver's parameters."),
    "bringup.configuration_error": (
        "a parameter never reached one of my nodes: {meaning}.",
        "Pass the robot description and the parameters to that node (its launch file, topic names and "
        "namespace)."),
}
MEANINGS = {
    "control.controller_load_failed": "its type is not installed, or was never defined in the controller manager's "
                                      "parameters",
    "control.configuration_error": "its joints or interfaces did not match my robot description or its parameters",
    "bringup.configuration_error": "the robot description or the driver's parameters did not reach the node that "
                                   "needs them",
    "control.controller_activation_failed": "switching my controllers took too long or its interfaces were not "
                                            "available",
}


def _nominal(what: str) -> Worded:
    return ("My controllers followed the joint trajectory without any problem.", None,
            ["The controller logs show no error for this goal."])


# joint_trajectory_controller's checks of a goal it has just received (explainers/control/catalogue.py INVALID)
REJECTED = ("the trajectory sent did not fit the controller, which rejected the goal before it started",
            "the trajectory they were sent did not fit the controller, which rejected the goal before it started: "
            "{meaning}.",
            "Send a trajectory the controller takes: its joint names, the times and values of its points as the quoted "
            "line asks (the controller's 'joints' parameter lists the joints it takes).")

template = Wording("{what} could not run because", "ros2_control", CLAUSES, MEANINGS, _nominal,
                   by_meaning={"control.configuration_error": REJECTED},
                   notes_only=frozenset({"control.controller_activation_failed"}),
                   # the arm was moving when it strayed: the step ran, and was cut short
                   heads={"control.tolerance_violated": "{what} could not go on because"})


# A driver's error read by the callback it is logged in (explainers/control/driver_roles.py): the clause says what
# the role supports and no more; a device error's line names the device, not what made it fail.
ROLE_CLAUSES = {
    "control.hardware_failure": (
        "a hardware interface failed: {meaning}. Its line tells that the device failed, not why.",
        "The device's own error report tells more (its controller's fault log or error codes, its status lights), "
        "and so do its connection, power and state at that time."),
    "control.configuration_error": (
        "a controller or its driver was set up wrongly: {meaning}.",
        "Fix the ros2_control tag of the robot description (the hardware parameters, joints and interfaces the "
        "quoted line names) to what this driver expects."),
    "bringup.configuration_error": (
        "a parameter never reached my driver: {meaning}.",
        "Set the parameter the quoted line names in the ros2_control tag of the robot description (or in the "
        "launch arguments that fill it in)."),
    "control.controller_activation_failed": (
        "a controller could not be activated: {meaning}.",
        "Activate only controllers whose command interfaces this driver accepts together (the quoted line names "
        "the combination it would not take)."),
}


def role_template(cause: str, d: Diagnosis, what: str, meaning: str) -> Worded | None:
    """(sentence, fix, details) of a cause found by a driver line's role; None for a cause without such words."""
    if cause not in ROLE_CLAUSES or d.decisive is None:
        return None
    clause, fix = ROLE_CLAUSES[cause]
    head = f"{what} could not run because"
    return (f"{head[:1].upper()}{head[1:]} {clause.format(meaning=meaning)}", fix,
            [f"My driver said: '{said(d.decisive.line)}'"])
