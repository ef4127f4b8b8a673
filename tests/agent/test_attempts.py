""""Did you try again?": the tries the robot's modules logged while a step ran (Nav2's failed plans and recoveries,
MoveIt's planning requests, a step started again), counted from the recording, on the simulated runs and on
/task_info runs written with rosbags from real log strings."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.followups import content_kind
from hexar.evals.scenarios.arm import simulate_arm_suite
from hexar.evals.scenarios.bag import BagBuilder
from hexar.events import read_recording
from tests.agent.helpers import converse

T0 = 1_741_600_000_000_000_000
S = 1_000_000_000


@pytest.fixture(scope="module")
def arm(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("arm")
    simulate_arm_suite(out, only=lambda s, v: v == 1 and s in {"nominal", "out_of_reach"})
    return out


@pytest.mark.parametrize("question", ["did you try again?", "how many times did you try?", "did you give up?",
                                      "how many attempts were there", "did you try to go around it?",
                                      "how many times did it replan?", "how many recoveries were there?"])
def test_questions_about_trying_again(question: str) -> None:
    assert content_kind(question) == "tried"


@pytest.mark.parametrize("question", ["can you try again?", "try again", "why did you stop?", "did you talk to maria?",
                                      "Why did you give up so quickly?", "why did you try again?"])
def test_not_questions_about_trying_again(question: str) -> None:
    assert content_kind(question) != "tried"


def test_a_blocked_path_counts_its_failed_plans_and_recoveries(suite: Path) -> None:
    run = suite / "bagfile_5_1"
    logs = read_recording(run).logs
    failed_plans = sum(1 for ln in logs if ln.msg.startswith("Planning algorithm GridBased failed to generate"))
    recoveries = [ln.msg.split()[-1] for ln in logs if ln.name == "behavior_server" and ln.msg.startswith("Running ")]
    assert failed_plans > 1 and sorted(recoveries) == ["backup", "spin", "spin", "wait"]
    first, tried, why = converse(run, "why didn't you bring me the coffee?", "did you try again?", "why?")
    assert "blocked my path" in str(first["answer"])
    assert str(tried["answer"]).startswith(f"Yes. For step 1 (to go to the kitchen), my planner failed to find a path "
                                           f"{failed_plans} times, I ran 4 recoveries (2 spins, a wait and a backup)")
    assert str(tried["answer"]).endswith("but none of it got it done, so the step failed."), tried["answer"]
    assert "[behavior_server] INFO Running spin" in str(why["answer"]) or "Received request" in str(why["answer"])


@pytest.mark.parametrize("question", ["how many times did you try?", "how many times did it replan?"])
def test_how_many_times_is_not_answered_yes_or_no(suite: Path, question: str) -> None:
    (answer,) = converse(suite / "bagfile_5_1", question)
    assert str(answer["answer"]).startswith("For step 1 (to go to the kitchen), my planner failed to find a path")


def test_one_failed_pick_is_one_try_and_a_clean_run_needed_none(arm: Path) -> None:
    from hexar.evals.scenarios.arm import arm_recording_name

    (failed,) = converse(arm / arm_recording_name("out_of_reach", 1), "did you try again?")
    assert str(failed["answer"]) == ("No. My recording shows one try at step 2 (to pick up the cup): it failed, and "
                                     "I did not start it again after that."), failed["answer"]
    (clean,) = converse(arm / arm_recording_name("nominal", 1), "did you try again?")
    assert clean["answer"] == "I didn't need to: every step of my plan that started went through at the first try."


def test_a_plan_never_started_had_nothing_to_try(suite: Path) -> None:
    (answer,) = converse(suite / "bagfile_1_1", "did you try again?")
    assert answer["answer"] == "No: none of my plan's steps started, so there was nothing to try again."


def _retried_pick(tmp_path: Path) -> Path:
    """A pick that MoveIt planned twice (its first plan failed) and the plan ran twice before it went through."""
    b = BagBuilder()
    plan = [("pick", {"object": "mug"})]

    def publish(t: int, status: str) -> None:
        b.task_info(t, {"instruction": "Pick up the mug", "task_id": "T1", "task_status": "valid",
                        "task_error_msg": "", "skill_sequence": [{"skill": s, "params": p, "status": status,
                                                                  "error_msg": ""} for s, p in plan]})

    publish(T0, "waiting")
    publish(T0 + S, "Running")
    for k in range(2):
        t = T0 + (2 + 4 * k) * S
        b.log(t, "moveit.ros.move_group.move_action_capability", 20,
              "Combined planning and execution request received for MoveGroup action. Forwarding to planning and "
              "execution pipeline.")
        if k == 0:
            b.log(t + S, "moveit.ompl_planning.model_based_planning_context", 40,
                  "Unable to solve the planning problem")
    publish(T0 + 4 * S, "failed")
    publish(T0 + 5 * S, "Running")
    publish(T0 + 9 * S, "succeeded")
    return b.write(tmp_path / "pick")


def test_a_step_started_again_and_planned_twice(tmp_path: Path) -> None:
    (answer,) = converse(_retried_pick(tmp_path), "did you try again?")
    assert answer["answer"] == ("Yes. For step 1 (to pick up the mug), I started it twice and I asked my motion "
                                "planner for a plan twice, and the step went through in the end."), answer["answer"]


def _still_driving(tmp_path: Path) -> Path:
    """A trip still under way when the recording stops 40 s later, its planner failing once in Jazzy's words."""
    b = BagBuilder()
    plan = [("navigate_to_zone", {"location": "kitchen"}), ("say", {"input": "Here you are."})]

    def publish(t: int, first: str) -> None:
        b.task_info(t, {"instruction": "Go to the kitchen", "task_id": "T1", "task_status": "valid",
                        "task_error_msg": "", "skill_sequence": [
                            {"skill": s, "params": p, "status": st, "error_msg": ""}
                            for (s, p), st in zip(plan, [first, "waiting"], strict=True)]})

    publish(T0, "waiting")
    publish(T0 + S, "Running")
    b.log(T0 + 5 * S, "planner_server", 30, 'GridBasedplugin failed to plan from (1.00, 1.00) [q: 0.00, 0.00, -0.00, '
          '1.00] (yaw: -0.00) to (-1.50, 1.50) [q: 0.00, 0.00, 0.00, 1.00] (yaw: 0.00): "Failed to create plan with '
          'tolerance of: 0.500000"')
    b.log(T0 + 41 * S, "controller_server", 20, "Passing new path to controller.")
    return b.write(tmp_path / "driving")


def test_a_step_still_under_way_is_timed_to_the_recordings_end_and_its_tries_counted(tmp_path: Path) -> None:
    run = _still_driving(tmp_path)
    long, tried = converse(run, "how long did it take?", "did you try again?")
    assert "was not over when the recording ends, 41 s after it began" in str(long["answer"]), long["answer"]
    assert str(long["answer"]).endswith("Step 1 (to go to the kitchen) had run for 40 s when the recording ends.")
    assert tried["answer"] == ("Yes. For step 1 (to go to the kitchen), my planner failed to find a path once, and "
                               "the step was still going when the recording ends."), tried["answer"]


def test_a_fix_asked_after_the_tries_of_a_run_that_did_not_fail_is_its_findings(suite: Path) -> None:
    """A slow trip that got there: after "did you try again?", "what should I check?" is about why it was slow,
    not "nothing went wrong"."""
    first, tried, fix = converse(suite / "bagfile_8_1", "what happened?", "did you try again?", "what should I check?")
    assert "not sure where I was on my map" in str(first["answer"])
    assert str(tried["answer"]).startswith("I didn't need to")
    assert "relocalise" in str(fix["answer"]) and "Nothing went wrong" not in str(fix["answer"]), fix["answer"]


def test_a_nodes_own_retries_are_quoted_as_tries(tmp_path: Path) -> None:
    """A lifecycle manager that retried a transition once and then gave up (a real console): its own lines are the
    tries, not "one try"."""
    from tests.agent.helpers import converse, real_module_run

    run = real_module_run("kilted-lifecycle-transition-label-misspelt", tmp_path / "run")
    (how_many,) = converse(run, "How many times did it retry before giving up?")
    text = str(how_many["answer"])
    assert text.startswith("For step 1 (to bring up my drivers and controllers), my log tells of trying again (")
    assert '"active of /base_driver failed (state inactive), retrying in 1 s"' in text
    assert '"active of /base_driver failed twice, state inactive; giving up"' in text and "one try" not in text


def test_whether_recoveries_ran_is_a_count_of_tries(tmp_path: Path) -> None:
    from tests.agent.helpers import real_nav2_run

    assert content_kind("Did any recovery behaviors run before the goal was finally failed?") == "tried"
    assert content_kind("Which recovery behaviors ran, and did any of them succeed?") == "tried"
    run = real_nav2_run("kilted-nav2-start-in-wall", tmp_path / "run")
    (ran,) = converse(run, "Did any recovery behaviors run before the goal was finally failed?")
    assert "I ran 4 recoveries (2 spins, a wait and a backup)" in str(ran["answer"])


def test_a_named_node_trying_again_is_a_question_of_tries(tmp_path: Path) -> None:
    """"How many times did lifecycle_manager try to configure /base_driver before giving up?": its own retry lines,
    not one line counted."""
    from tests.agent.helpers import real_module_run

    assert content_kind("How many times did lifecycle_manager try to configure /base_driver before giving up?") == \
        "tried"
    run = real_module_run("kilted-lifecycle-configure-raises", tmp_path / "run")
    (tries,) = converse(run, "How many times did lifecycle_manager try to configure /base_driver before giving up?")
    assert '"configure of /base_driver failed (state unconfigured), retrying in 1 s"' in str(tries["answer"])
    assert '"configure of /base_driver failed twice, state unconfigured; giving up"' in str(tries["answer"])
