"""The Nav2 message catalogue: every entry well-formed, roles across distros and namespaces, the literal
prefilter never hiding a match, and real lines of several distros read the same way."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from hexar.causes import vocabulary
from hexar.explainers.navigation.catalogue import Entry, catalogue

CORPUS = Path(__file__).resolve().parents[3] / "evals" / "data" / "real_nav2" / "corpus.yaml"
KINDS = {"begin", "succeeded", "failed", "canceled", "progress", "recovery", "replan", "clear", "disturbance",
         "cause", "info", "plan_failed"}


def test_every_entry_is_well_formed() -> None:
    cat = catalogue()
    ids = [e.id for e in cat.entries]
    assert len(ids) == len(set(ids))
    for e in cat.entries:
        re.compile(e.raw)
        assert e.cause is None or e.cause in vocabulary(), e.id
        assert e.kind in KINDS and e.strength in {"strong", "weak"}, e.id
        assert e.distros and set(e.distros) <= set(cat.distros), e.id
        assert e.source and e.meaning, e.id
        assert e.kind != "cause" or e.cause is not None, e.id


@pytest.mark.parametrize(("logger", "role"), [
    ("controller_server", "controller_server"), ("robot1.controller_server", "controller_server"),
    ("/robot1/controller_server", "controller_server"), ("recoveries_server", "behavior_server"),
    ("behavior_server", "behavior_server"), ("bt_navigator_navigate_to_pose_rclcpp_node", "bt_navigator"),
    ("robot1.bt_navigator_navigate_through_poses_rclcpp_node", "bt_navigator"),
    ("controller_server_rclcpp_node", "controller_server"), ("DWBLocalPlanner", "controller_server"),
    ("global_costmap.global_costmap", "costmap"), ("robot1.local_costmap.local_costmap", "costmap"),
    ("nav2_costmap_2d", "costmap"), ("lifecycle_manager_navigation", "lifecycle_manager"),
    ("tf2_buffer", "tf"), ("transformPoseInTargetFrame", "tf"), ("BehaviorTreeEngine", "bt_navigator"),
    ("docking_server", "docking_server"), ("my_own_node", None),
])
def test_roles_across_distros_and_namespaces(logger: str, role: str | None) -> None:
    assert catalogue().role(logger) == role


def _corpus_messages() -> list[str]:
    if not CORPUS.is_file():
        pytest.skip("the real-Nav2 corpus is not in this checkout")
    out = []
    for excerpt in yaml.safe_load(CORPUS.read_text("utf-8")):
        for line in str(excerpt["lines"]).splitlines():
            out.append(line.split("]: ", 1)[-1])
    return out


def _slow_match(msg: str) -> Entry | None:
    hits = [e for e in catalogue().entries if e.pattern.search(msg)]
    return next((e for e in hits if e.cause is not None), hits[0] if hits else None)


def test_the_literal_prefilter_never_hides_a_match() -> None:
    messages = [
        *_corpus_messages(),
        "GridBased: failed to create plan with tolerance 0.50.", "Goal failed", "Navigation failed",
        "Goal failed error_code:104 error_msg:'Failed to make progress'", "Attempting spin",
        "Goal Coordinates of(5.000000, 1.000000) was in lethal cost", "Optimizer fail to compute path",
        "Min velocities are higher than max velocities!",
        "\x1b[34m\x1b[1mFailed to bring up all requested nodes. Aborting bringup.\x1b[0m\x1b[0m",
    ]
    for msg in messages:
        assert catalogue().match(msg) == _slow_match(msg.replace("\x1b[34m\x1b[1m", "").replace("\x1b[0m", "")), msg


@pytest.mark.parametrize(("msg", "cause", "kind"), [
    # shared reference nav2_log_messages.md (humble/jazzy format strings) and corpus excerpts
    ("The goal sent to the planner is off the global costmap. Planning will always fail to this goal.",
     "navigation.goal_unreachable", "cause"),
    ("Goal Coordinates of(-105.918845, 39.251424) was outside bounds", "navigation.goal_unreachable", "cause"),
    ("Start Coordinates of(0.000000, 3.000000) was outside bounds", "navigation.off_costmap", "cause"),
    ("AMCL cannot publish a pose or update the transform. Please set the initial pose...",
     "navigation.poor_localisation", "cause"),
    ("Collision Ahead - Exiting DriveOnHeading", "navigation.collision_ahead", "cause"),
    ("Robot to stop due to FootprintApproach polygon", "navigation.collision_ahead", "cause"),
    ("No valid trajectories out of 360! ", "navigation.controller_failure", "disturbance"),
    ("Failed to make progress", None, "progress"),
    ("Begin navigating from current location to (-2.04, -1.17)", None, "begin"),
    ("Navigation succeeded", None, "succeeded"),
    # ros-navigation/navigation2 nav2_velocity_smoother/src/velocity_smoother.cpp (main): its format strings
    ("Positive values set of deceleration! These should be negative to slow down!",
     "navigation.configuration_error", "cause"),
    ("Invalid feedback_type, options are OPEN_LOOP and CLOSED_LOOP.", "navigation.configuration_error", "cause"),
    ("Velocity message contains NaNs or Infs! Ignoring as invalid!", "navigation.controller_failure", "cause"),
])
def test_real_wordings(msg: str, cause: str | None, kind: str) -> None:
    entry = catalogue().match(msg)
    assert entry is not None and entry.cause == cause and entry.kind == kind


def test_sizes_cover_every_distro() -> None:
    sizes = catalogue().sizes()
    assert set(sizes) == {"foxy", "galactic", "humble", "iron", "jazzy", "kilted", "rolling"}
    assert all(sum(roles.values()) >= 40 for roles in sizes.values())
    assert sizes["jazzy"].get("docking_server", 0) > 0 and "docking_server" not in sizes["foxy"]


def test_a_message_hard_wrapped_onto_indented_lines_reads_as_the_one_line_message() -> None:
    from hexar.explainers.stack.catalogue import stack_catalogue

    # blind5 indoor-nav-sim (NavFn, navfn_planner.cpp) and mirte (legacy_inflation_layer.cpp), wrapped as pasted
    navfn = ("Failed to create a plan from potential when a legal\n        potential was found. This shouldn't "
             "happen.")
    entry = stack_catalogue().match(navfn)
    assert entry is not None and entry == stack_catalogue().match(" ".join(navfn.split()))
    assert entry.package == "nav2_navfn_planner"
    inflation = ("The configured inflation radius (0.150) is smaller than the computed inscribed\nradius (0.150) "
                 "of your footprint, it is highly recommended to set inflation\nradius to be at least as big as the "
                 "inscribed radius to avoid collisions")
    found = stack_catalogue().match(inflation)
    assert found is not None and found.cause == "stack.configuration_error"
    # a message whose first line already matches keeps that reading (its later lines are another message's)
    assert catalogue().match("Failed to make progress\nPassing new path to controller.") == \
        catalogue().match("Failed to make progress")
