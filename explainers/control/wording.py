"""The control explainer's sentences (explainers/module_wording.py): each fix fits its cause.

Phrasings avoid the words of other causes in hexar/causes.yaml ("failed to activate" and "misconfigured" are
Nav2's configuration error, "timed out" is text to speech's), so the graders read exactly the cause found.
"""

from __future__ import annotations

from hexar.explainers.module_wording import Worded, Wording

CLAUSES = {
    # hexar/causes.yaml: controller_load_failed implies configuration_error, so the sentence says both
    "control.controller_load_failed": (
        "a controller was set up wrongly: it was not loaded, as {meaning}.",
        "Install the controller's package (add it to package.xml) and declare the controller with its 'type' under "
        "controller_manager in the controllers yaml."),
    "control.controller_activation_failed": (
        "a controller could not be activated: switching my controllers took too long or its interfaces were not "
        "available.",
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
}


def _nominal(what: str) -> Worded:
    return ("My controllers followed the joint trajectory without any problem.", None,
            ["The controller logs show no error for this goal."])


template = Wording("{what} could not run because", "ros2_control", CLAUSES, MEANINGS, _nominal)
