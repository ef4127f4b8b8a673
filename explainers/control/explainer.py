"""The control (ros2_control) component explainer: controller_manager, the spawners, hardware interfaces and the
stock controllers (joint_trajectory_controller first), read from /rosout through the mined ros2_control catalogue.

Causes, by the earliest decisive line (explainers/logcause.py; the spawner's "Failed loading controller" or
"Failed to activate controller" is a symptom of the controller manager's line before it): controller_load_failed,
controller_activation_failed, hardware_failure, tolerance_violated, configuration_error, nominal, and
unexplained_failure (the first error no catalogue explains, quoted with its node and time, and the
candidates). A bring-up or device line before them is cited first, and so is a driver's line whose strerror text
or set-up words state the why (explainers/stated_causes.py). MoveIt's lines in the window (the control explainer
asked by manipulation) are read too, so that its symptoms are recognised as such.
"""

from __future__ import annotations

from typing import ClassVar

from hexar.explainers.control.catalogue import catalogue
from hexar.explainers.control.wording import template
from hexar.explainers.logcause import Diagnosis, ModuleCatalogue
from hexar.explainers.manipulation.catalogue import catalogue as moveit_catalogue
from hexar.explainers.module_explainer import ModuleExplainer

SKILLS = ("follow_joint_trajectory", "bring_up_controllers", "pick", "place", "move_arm")


class ControlExplainer(ModuleExplainer):
    """Explains the robot's controllers and hardware interfaces (ros2_control)."""

    name: ClassVar[str] = "control"
    skills: ClassVar[tuple[str, ...]] = SKILLS
    prefix: ClassVar[str] = "control."
    module_words: ClassVar[str] = "my arm controllers"
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

    def catalogues(self) -> list[ModuleCatalogue]:
        return [catalogue(), moveit_catalogue()]

    def words(self, cause: str, d: Diagnosis, what: str) -> tuple[str, str | None, list[str]]:
        return template(cause, d, what)
