"""The ROS 2 stack layers Nav2 (and other) failures come from: a catalogue mined from their sources (catalogue.py,
mining.py), the bring-up problems any explainer can cite (bringup.py: `bringup_findings`), and what single lines of
the stack mean: the dynamic loader stopping a program (loader.py), a command launch could not execute (launched.py),
the middleware keeping a node from the others or a setting of it never applied (middleware.py), a QoS mismatch
(qos.py), a setting rcl, rmw or rclpy refused as it made a node (refused.py), a signal that ended a process
(signals.py), a Python node's uncaught exception (thrown.py)."""

from __future__ import annotations

from hexar.explainers.stack.bringup import BringupFinding, bringup_findings
from hexar.explainers.stack.catalogue import StackCatalogue, StackEntry, stack_catalogue

__all__ = ["BringupFinding", "StackCatalogue", "StackEntry", "bringup_findings", "stack_catalogue"]
