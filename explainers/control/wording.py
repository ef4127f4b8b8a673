"""The control explainer's sentences: (sentence, fix, details) per cause, each fix fitting its cause.

Phrasings avoid the words of other causes in hexar/causes.yaml ("failed to activate" and "misconfigured" are
Nav2's configuration error, "timed out" is text to speech's), so the graders read exactly the cause found.
"""

from __future__ import annotations

from hexar.explainers.logcause import Diagnosis, said


def template(cause: str, d: Diagnosis, what: str) -> tuple[str, str | None, list[str]]:
    seen = [f"ros2_control said: '{said(d.decisive.line)}'"] if d.decisive is not None else []
    head = f"{what.capitalize()} could not run because"
    if cause == "control.controller_load_failed":
        # hexar/causes.yaml: controller_load_failed implies configuration_error, so the sentence says both
        return (f"{head} a controller was set up wrongly: my controller manager could not load it, as its type is "
                "not installed, or was never defined in the controller manager's parameters.",
                "Install the controller's package (add it to package.xml) and declare the controller with its "
                "'type' under controller_manager in the controllers yaml.", seen)
    if cause == "control.controller_activation_failed":
        return (f"{head} a controller could not be activated: switching my controllers took too long or its "
                "interfaces were not available.",
                "Check that the controller manager's update loop runs (a paused simulation stops it), and that no "
                "other active controller claims the same command interfaces.", seen)
    if cause == "control.hardware_failure":
        return (f"{head} a hardware interface failed: it could not configure, activate or talk to its device.",
                "Check the device connection, its port and permissions, and the hardware parameters in the "
                "ros2_control URDF tag.", seen)
    if cause == "control.tolerance_violated":
        return (f"{head} my arm strayed from its planned trajectory beyond the controller's tolerance, so the "
                "joint trajectory controller aborted the motion.",
                "Look at the joint whose error exceeded its tolerance: a collision, a payload, controller gains, or "
                "tolerances too tight for this robot.", seen)
    if cause == "control.configuration_error":
        entry = d.decisive.entry if d.decisive is not None else None
        if entry is not None and entry.cause == cause:
            # the decisive line's own meaning (a driver's calibration, a controller's interfaces) says what was wrong
            return (f"{head} a controller or its driver was set up wrongly: {entry.meaning}.",
                    "Fix the set-up the quoted line names: the controller's joints and interfaces against the "
                    "ros2_control tag of the URDF, or the driver's parameters.", seen)
        return (f"{head} the controller's joints or interfaces did not match my robot description or "
                "its parameters.",
                "Make the controller's joints and command/state interfaces match the ros2_control tag of the URDF.",
                seen)
    if cause == "bringup.configuration_error":
        entry = d.decisive.entry if d.decisive is not None else None
        what = entry.meaning if entry is not None and entry.cause == cause else (
            "the robot description or the driver's parameters did not reach the node that needs them")
        return (f"{head} a parameter never reached one of my nodes: {what}.",
                "Pass the robot description and the parameters to that node (its launch file, topic names and "
                "namespace).", seen)
    if cause == "control.nominal":
        return ("My controllers followed the joint trajectory without any problem.", None,
                ["The controller logs show no error for this goal."])
    return (f"{head} of a problem my logs name ({cause}).", None, seen)
