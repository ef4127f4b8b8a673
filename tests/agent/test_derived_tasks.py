"""A task HEXAR derived from a recording's own lines (no /task_info) has no plan of the robot's to fault: the
question goes to the explainers of its steps, never to the planner's "my plan looks right"."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.backends import Backend
from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.claims import ALL_FINE, read_claims
from hexar.events.records import WARN
from tests.agent.helpers import CountingModel
from tests.explainers.helpers import write_lines

# controller_manager's warning when no /clock came (ros2_control controller_manager.cpp@jazzy); a pull request of
# xarm_ros2 (#114) quotes it as the only line of a Gazebo launch without a clock bridge
NO_CLOCK = (0.0, "controller_manager", WARN, "No clock received, using time argument instead! Check your node's "
            "clock configuration (use_sim_time parameter) and if a valid clock source is available")


@pytest.mark.parametrize("question", ["Why didn't that work?", "How did it go?"])
def test_a_start_derived_from_its_lines_is_answered_by_control_not_the_planner(tmp_path: Path, question: str) -> None:
    log = write_lines(tmp_path, [NO_CLOCK])
    assert log.task().derived
    session = Session(RunSettings(recording=log.path, llm="none", phrase=False),
                      backend=Backend("counting", CountingModel()))
    result = session.ask(question)
    assert result["explainers"] == ["control"], result
    assert "plan" not in result["answer"] and "No clock received" in result["answer"]
    fine = ALL_FINE in read_claims(result["answer"]).affirmed
    assert fine is (question == "How did it go?")
