"""The ask-human-for-help component explainer: a causal model of the skill's state machine, learned from
simulated executions, queried for counterfactuals."""

from __future__ import annotations

from hexar.explainers.ask_human.explainer import AskHumanForHelpExplainer

__all__ = ["AskHumanForHelpExplainer"]
