"""Questions of round 53's blind set 14 that the answers got wrong, asked again of real consoles written as
recordings: an either-or question answered with no bare yes or no."""

from __future__ import annotations

from pathlib import Path

from hexar.agent.overview import confirmed, yes_or_no
from hexar.causes import BENIGN
from tests.agent.helpers import converse, real_nav2_run


def test_an_either_or_question_gets_no_bare_yes_or_no(tmp_path: Path) -> None:
    run = real_nav2_run("jzt-custom-docking-plugin-goal-succeeded-mux-timeouts", tmp_path / "run")
    either, whether = converse(run, "Are the mux timeouts after the goal succeeded harmless or do I need to fix "
                                    "something?", "Did you reach the goal or not?")
    assert str(either["answer"]).startswith("I reached my goal without any problem.")
    assert str(whether["answer"]).startswith("Yes. I reached my goal")  # "or not" still asks one thing
    assert confirmed("were you charging or was the joystick on?", {"navigation.charging"}, BENIGN) == ""
    assert confirmed("were you charging?", {"navigation.charging"}, BENIGN) == "Yes."
    assert yes_or_no("did you finish or did you give up?", "succeeded") == ""
