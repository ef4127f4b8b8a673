"""The ROS 2 stack layers Nav2 (and other) failures come from: a catalogue mined from their sources (catalogue.py),
the bring-up problems any explainer can cite (bringup.py: `bringup_findings`), and the dynamic loader's words when it
stops a program (loader.py)."""

from __future__ import annotations

from hexar.explainers.stack.bringup import BringupFinding, bringup_findings
from hexar.explainers.stack.catalogue import StackCatalogue, StackEntry, stack_catalogue

__all__ = ["BringupFinding", "StackCatalogue", "StackEntry", "bringup_findings", "stack_catalogue"]
