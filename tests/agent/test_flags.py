""""Were you charging?", "was someone using the joystick?": the recorded flag decides yes or no; where the failure
was that flag, its explainer's answer says so; a recording without the flag cannot say no."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.followups import content_kind
from hexar.agent.session import Session
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import contract as c
from hexar.events.records import clock
from tests.agent.helpers import one_step_task

T0 = sec_ns(1_741_600_000)


def _ask(run: Path, question: str) -> dict[str, object]:
    return dict(Session(RunSettings(recording=run, llm="none")).ask(question))


@pytest.mark.parametrize(("question", "kind"), [
    ("were you charging?", "flag"), ("Were you plugged in?", "flag"), ("were you docked", "flag"),
    ("was someone using the joystick?", "flag"), ("were you in manual mode?", "flag"),
    ("was the joystick on?", "flag"),
    ("why were you charging?", None), ("what is a joystick?", None),
])
def test_flag_questions_are_told_apart(question: str, kind: str | None) -> None:
    assert content_kind(question) == kind


def test_a_flag_that_stayed_off_is_no_and_the_failure_follows(suite: Path) -> None:
    blocked = _ask(suite / "bagfile_5_1", "Were you charging?")
    assert blocked["answer"] == ("No: my charging flag (/power/is_charging) stayed off while I worked on your "
                                 'request "Bring me a coffee from the kitchen". I couldn\'t reach the kitchen because '
                                 "something blocked my path and I found no other way around it.")
    assert any(e["topic"] == c.IS_CHARGING for e in blocked["evidence"])  # type: ignore[union-attr]
    fine = _ask(suite / "bagfile_10_1", "was someone using the joystick?")
    assert fine["answer"] == ('No: my joystick priority flag (/joy_priority) stayed off while I worked on your request '
                              '"Bring me a coffee from the kitchen".')


def test_the_flag_that_stopped_me_is_yes_with_the_failure(suite: Path) -> None:
    charged = _ask(suite / "bagfile_7_1", "were you plugged in?")
    assert str(charged["answer"]).startswith("Yes. I couldn't reach the kitchen because I was plugged into my charger")
    assert charged["causes"] == ["navigation.charging"]


def test_a_flag_on_during_a_task_that_went_well_is_yes_with_when(tmp_path: Path) -> None:
    b = BagBuilder()
    b.flag(T0, c.IS_CHARGING, True)
    b.flag(T0 + sec_ns(6), c.IS_CHARGING, False)
    one_step_task(b, T0, 5, "Say hello", "say", {"input": "Hello"})
    run = b.write(tmp_path / "run")
    said = _ask(run, "Were you charging?")
    off = clock(T0 + sec_ns(6)).split(".")[0]
    assert said["answer"] == (f"Yes: my charging flag (/power/is_charging) was on from when I began, until {off} "
                              'UTC, while I worked on your request "Say hello".')


def test_no_flag_recorded_is_no_answer(tmp_path: Path) -> None:
    from hexar.evals.real_nav2 import corpus, write_recording

    excerpt = next(e for e in corpus() if e.outcome == "failed")
    said = _ask(write_recording(excerpt, tmp_path / "run", task=False), "were you charging?")
    assert str(said["answer"]).startswith("I can't tell: my recording holds no charging flag (/power/is_charging) "
                                          "for the navigation goal.")


@pytest.mark.parametrize("question", ["What is your speed limit?", "how fast can you go?",
                                      "what was your maximum speed?"])
def test_the_speed_limit_is_the_published_setting(suite: Path, question: str) -> None:
    from hexar.events import read_recording

    assert content_kind(question) == "limit"
    log = read_recording(suite / "bagfile_8_1")
    published = {r.get("max_vel_x") for r in log.statuses[c.DIAGNOSTICS] if r.get("max_vel_x")}
    assert len(published) == 1  # one limit through the run
    said = _ask(suite / "bagfile_8_1", question)
    assert said["answer"] == (f"My speed limit was {float(published.pop()):.2f} m/s while I worked on your request "
                              '"Bring me a coffee from the kitchen" (max_vel_x on /diagnostics).')
    assert content_kind("how fast were you going?") == "fast"  # the speeds driven, not the limit


def test_a_speed_limit_changed_during_the_task_is_told_with_when(tmp_path: Path) -> None:
    b = BagBuilder()
    for k, limit in enumerate(("0.50", "0.50", "0.30")):
        b.status(T0 + sec_ns(3 * k), c.DIAGNOSTICS, "controller_server", "velocity limits",
                 [("max_vel_x", limit), ("max_vel_theta", "1.00")])
    one_step_task(b, T0, 4, "Go to the kitchen", "navigate_to_zone", {"location": "kitchen"})
    said = _ask(b.write(tmp_path / "run"), "what is your speed limit?")
    changed = clock(T0 + sec_ns(6)).split(".")[0]
    assert said["answer"] == ('My speed limit changed while I worked on your request "Go to the kitchen": 0.50 m/s '
                              f"at first, then 0.30 m/s at {changed} UTC (max_vel_x).")


def test_a_speed_limit_published_only_after_the_task_is_not_its_limit(tmp_path: Path) -> None:
    b = BagBuilder()
    one_step_task(b, T0, 2, "Go to the kitchen", "navigate_to_zone", {"location": "kitchen"})
    b.status(T0 + sec_ns(9), c.DIAGNOSTICS, "controller_server", "velocity limits", [("max_vel_x", "0.40")])
    said = _ask(b.write(tmp_path / "run"), "what is your speed limit?")
    assert said["answer"] == (f"I can't tell: my speed limit (max_vel_x on /diagnostics) was first published at "
                              f"{clock(T0 + sec_ns(9)).split('.')[0]} UTC, after your request \"Go to the kitchen\" "
                              "ended; it was 0.40 m/s then.")
    assert said["enough_information"] is False


@pytest.mark.parametrize(("question", "kind"), [
    ("what's your battery level?", "battery"), ("was your battery low?", "battery"),
    ("did you run out of battery?", "battery"), ("were you low on power?", "battery"),
    ("were you charging?", "flag"),
])
def test_battery_questions_are_told_apart(question: str, kind: str) -> None:
    assert content_kind(question) == kind


def test_the_battery_level_is_not_read_and_the_charging_flag_is_told(suite: Path, tmp_path: Path) -> None:
    from hexar.evals.scenarios.bag import TYPESTORE

    said = _ask(suite / "bagfile_7_1", "was your battery low?")
    assert said["answer"] == ("I can't tell my battery level: my recording holds no battery state "
                              "(sensor_msgs/msg/BatteryState). My charging flag (/power/is_charging) was on from when "
                              'I began, while I worked on your request "Bring me a coffee from the kitchen".')
    assert said["enough_information"] is False
    # a robot that records its battery: the topic is named, and that HEXAR does not read it
    ty = TYPESTORE.types
    b = BagBuilder()
    one_step_task(b, T0, 2, "Go to the kitchen", "navigate_to_zone", {"location": "kitchen"})
    header = ty["std_msgs/msg/Header"](stamp=ty["builtin_interfaces/msg/Time"](sec=T0 // 10**9, nanosec=0),
                                       frame_id="battery")
    import numpy as np

    state = ty["sensor_msgs/msg/BatteryState"](
        header=header, voltage=24.1, temperature=30.0, current=-1.2, charge=10.0, capacity=20.0,
        design_capacity=20.0, percentage=0.5, power_supply_status=2, power_supply_health=1,
        power_supply_technology=3, present=True, cell_voltage=np.array([], dtype=np.float32),
        cell_temperature=np.array([], dtype=np.float32), location="base", serial_number="")
    for k in range(3):
        b.raw(T0 + sec_ns(k), "/battery_state", "sensor_msgs/msg/BatteryState", state)
    held = _ask(b.write(tmp_path / "run"), "what's your battery level?")
    assert held["answer"] == ("I can't tell my battery level: my recording holds /battery_state (3 messages), but I do "
                              "not read its sensor_msgs/msg/BatteryState.")
