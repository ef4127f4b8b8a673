"""Stages the paper's 20 scenarios x 3 instruction variants as rosbag2 recordings of a simulated TIAGo.

The robot publishes what the original does: `/task_info` at task start, each skill start and end, and once for
an invalid plan; the skills write their own topics. Plans come from a simulated planner whose mistakes are
injected for scenarios 1-4, as the paper did. No label or ground truth is ever written into a bag.
"""

from __future__ import annotations

import random
import shutil
import string
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hexar.evals.cases import Scenario, Variant, recording_name, scenarios
from hexar.evals.scenarios import ask_human, nav, pizza, tts
from hexar.evals.scenarios.bag import BagBuilder, SkillResult, Storage, sec_ns

# Room centres in the studio apartment map (metres, map frame).
ROOMS: dict[str, tuple[float, float]] = {"kitchen": (4.2, 2.1), "dining_room": (1.6, 4.4), "living_room": (-1.8, 0.6)}
EPOCH = 1_741_600_800  # 2025-03-10 10:00 UTC: the recordings' wall clock
NAV_SITUATION = {5: "blocked", 6: "joystick", 7: "charging", 8: "poor_localisation", 9: "moving_obstacles"}
SKILL_TIMEOUT = sec_ns(60)  # the task manager aborts a skill after 60 s (hexar_interfaces.md)
Plan = list[tuple[str, dict[str, Any]]]


def normal_plan(v: Variant, variant: int) -> Plan:
    if v.key.startswith("bring"):
        noun = v.object.removeprefix("the ").removeprefix("a ")
        return [
            ("navigate_to_zone", {"location": v.room}),
            ("ask_human_for_help", {"question": f"Could you please put the {noun} on my tray?"}),
            ("navigate_to_zone", {"location": v.home}),
            ("say", {"input": f"Here is your {noun}."}),
        ]
    if v.key == "message":
        return [("navigate_to_zone", {"location": v.room}), ("say", {"input": "Maria, dinner is at eight."})]
    if v.key == "long_message":
        return [("navigate_to_zone", {"location": v.room}), ("say", {"input": tts.long_message(1)})]
    if v.key in {"read_recipe", "read_news"}:
        return [("say", {"input": tts.long_message(variant)})]
    if v.key.startswith("pizza"):
        return [("recommend_pizza", {}), ("say", {"input": "?recommend_pizza.recommended_pizza"})]
    raise ValueError(f"no plan for variant {v.key}")


# Planner mistakes injected for scenarios 1-4, with the validation error the robot's plan check publishes.
def injected_plan(sid: int, v: Variant, variant: int) -> tuple[Plan, str]:
    plan = normal_plan(v, variant) if sid != 4 else []
    if sid == 1:
        wrong = {1: (0, "navigate_to_room"), 2: (1, "ask_for_help"), 3: (1, "speak")}[variant]
        i, name = wrong
        plan[i] = (name, plan[i][1])
        return plan, f"Skill {name} is not a valid skill."
    if sid == 2:
        if variant == 1:
            plan[0] = ("navigate_to_zone", {"location": "kitchen_counter"})
            return plan, "Invalid location kitchen_counter. Valid locations are: kitchen, dining_room, living_room."
        if variant == 2:
            plan[1] = ("ask_human_for_help", {})
            return plan, "Missing mandatory parameter question for skill ask_human_for_help."
        plan[0] = ("navigate_to_zone", {"location": 2})
        return plan, "Location must be a string."
    if sid == 3:
        if variant == 1:
            plan[0] = ("navigate_to_zone", {"location": "dining_room"})
        elif variant == 2:
            plan = [plan[0], plan[1], plan[3]]
        else:
            plan = plan[:1]
        return plan, ""
    if sid == 4:
        action = {1: ("open_window", {"window": "living_room"}), 2: ("water_plants", {"location": "dining_room"}),
                  3: ("wash_dishes", {"location": "kitchen"})}[variant]
        plan = [("navigate_to_zone", {"location": v.room}), action]
        return plan, f"Skill {action[0]} is not a valid skill."
    return normal_plan(v, variant), ""


@dataclass
class Robot:
    """The simulated TIAGo executing one recording."""

    b: BagBuilder
    rng: random.Random
    sid: int
    variant: int
    t: int
    pos: tuple[float, float]
    moved: bool = False
    navigations: int = 0
    log: list[str] = field(default_factory=list)
    # the arm's fetch task (evals/scenarios/arm.py): its pick step's situation, and its first trip's
    arm_situation: str = "nominal"
    first_navigation: str | None = None

    def task_id(self) -> str:
        return "".join(self.rng.choice(string.ascii_letters + string.digits) for _ in range(16))

    def publish(self, task_id: str, instruction: str, plan: Plan, statuses: list[tuple[str, str]],
                valid: bool = True, error: str = "") -> None:
        self.b.task_info(self.t, {
            "instruction": instruction,
            "task_id": task_id,
            "task_status": "valid" if valid else "invalid",
            "task_error_msg": error,
            "skill_sequence": [
                {"skill": s, "params": p, "status": st, "error_msg": em}
                for (s, p), (st, em) in zip(plan, statuses, strict=True)
            ],
        })

    def run_task(self, instruction: str, plan: Plan, error: str = "") -> bool:
        task_id = self.task_id()
        statuses = [("waiting", "")] * len(plan)
        if error:
            self.publish(task_id, instruction, plan, statuses, valid=False, error=error)
            self.t += sec_ns(self.rng.uniform(0.3, 0.8))
            return False
        self.publish(task_id, instruction, plan, list(statuses))
        for i, (skill, params) in enumerate(plan):
            self.t += sec_ns(self.rng.uniform(0.05, 0.3))
            statuses[i] = ("Running", "")
            self.publish(task_id, instruction, plan, list(statuses))
            result = self.execute(skill, params)
            self.t = max(self.t, result.end) + sec_ns(self.rng.uniform(0.05, 0.2))
            if result.succeeded:
                statuses[i] = ("succeeded", "")
            else:
                statuses[i] = ("failed", result.error_msg or "The skill has been aborted")
            self.publish(task_id, instruction, plan, list(statuses))
            if not result.succeeded:
                return False
        return True

    def execute(self, skill: str, params: dict[str, Any]) -> SkillResult:
        if skill == "navigate_to_zone":
            return self.navigate(str(params["location"]))
        if skill == "say":
            text = str(params["input"])
            if text.startswith("?recommend_pizza"):
                text = f"I recommend a {self.log[-1]}." if self.log else "I recommend a pizza."
            return tts.simulate_say(self.b, self.rng, self.t, text)
        if skill == "ask_human_for_help":
            return self.ask_for_help(str(params.get("question", "")))
        if skill in {"pick", "place"}:
            from hexar.evals.scenarios.arm import simulate_arm

            situation = self.arm_situation if skill == "pick" else "nominal"
            return simulate_arm(self.b, self.rng, self.t, skill, str(params.get("object", "")), situation,
                                wall_clock_s=self.t / 1e9)
        if skill == "recommend_pizza":
            available = pizza.scenario_ingredients(self.variant, self.rng)
            result = pizza.simulate_recommend_pizza(self.b, self.rng, self.t, available)
            from hexar.explainers.pizza.recommender import default_recommender

            self.log.append(default_recommender().recommend(available))
            return result
        raise ValueError(f"the simulated robot has no skill {skill}")

    def navigate(self, location: str, situation: str | None = None) -> SkillResult:
        self.navigations += 1
        if situation is None and self.navigations == 1 and self.first_navigation is not None:
            situation = self.first_navigation
        if situation is None:
            situation = NAV_SITUATION.get(self.sid, "nominal") if self.navigations == 1 else "nominal"
        goal = ROOMS[location]
        mark = len(self.b.messages)
        result = nav.simulate_navigation(self.b, self.rng, self.t, self.pos, goal, situation,  # type: ignore[arg-type]
                                         goal_label=location)
        if result.end - self.t > SKILL_TIMEOUT:
            result = self._time_out(mark, self.t + SKILL_TIMEOUT)
        if result.succeeded:
            self.pos = goal
            self.moved = True
        return result

    def _time_out(self, mark: int, deadline: int) -> SkillResult:
        """The task manager cancels a navigation that outlives the skill timeout: Nav2 stops where it was."""
        added = self.b.messages[mark:]
        del self.b.messages[mark:]
        self.b.messages.extend(m for m in added if m[0] <= deadline)
        t = deadline + sec_ns(self.rng.uniform(0.01, 0.05))
        self.b.log(t, "bt_navigator", 20, "[navigate_to_pose] [ActionServer] Client requested to cancel the goal. "
                   "Cancelling.")
        self.b.log(t + sec_ns(0.02), "controller_server", 20, "Goal was canceled. Stopping the robot.")
        self.b.log(t + sec_ns(0.05), "bt_navigator", 20, "Goal canceled")
        return SkillResult(t + sec_ns(0.1), False, "The skill has timed out")

    def ask_for_help(self, question: str) -> SkillResult:
        if 11 <= self.sid <= 18:
            cond = ask_human.scenario_conditions(self.sid, self.rng)
        else:
            cond = ask_human.scenario_conditions(0, self.rng)
        person = (self.pos[0] + cond.person_distance * 0.8, self.pos[1] + cond.person_distance * 0.6)

        def approach(t: int) -> SkillResult:
            situation = "blocked" if cond.navigation_failure else "nominal"
            return nav.simulate_navigation(self.b, self.rng, t, self.pos, person, situation,  # type: ignore[arg-type]
                                           skill_logger="skill_navigate_to_pose", goal_label="the person")

        return ask_human.simulate_ask_human(self.b, self.rng, self.t, cond, question=question, navigate=approach)


def record(s: Scenario, variant: int, seed: int = 0) -> BagBuilder:
    """Everything the robot publishes during one scenario instance."""
    rng = random.Random(seed * 10_000 + s.id * 10 + variant)
    v = s.variants[variant - 1]
    b = BagBuilder()
    start = sec_ns(EPOCH + s.id * 3600 + variant * 600 + rng.uniform(0, 30))
    home = ROOMS[v.home]
    robot = Robot(b, rng, s.id, variant, start + sec_ns(rng.uniform(3, 6)), home)
    if s.id in {1, 2, 3, 4}:
        plan, error = injected_plan(s.id, v, variant)
    else:
        plan, error = normal_plan(v, variant), ""
    ok = robot.run_task(v.instruction, plan, error)
    if not ok:
        # The robot's own recovery: go back to where it started and say it could not do the task.
        robot.t += sec_ns(rng.uniform(1.0, 2.0))
        recovery: Plan = []
        if robot.moved or robot.pos != home:
            recovery.append(("navigate_to_zone", {"location": v.home}))
        recovery.append(("say", {"input": "Sorry, I could not complete the task."}))
        robot.run_task("", recovery)
    end = robot.t + sec_ns(rng.uniform(2, 4))
    nav.simulate_robot_state(b, rng, start, end, joystick=s.id == 6, charging=s.id == 7,
                             pose=(home[0], home[1], 0.0))
    return b


def simulate_suite(out: Path, storage: Storage = "sqlite3", seed: int = 0,
                   only: Callable[[int, int], bool] | None = None) -> list[Path]:
    """Write the 60 recordings as `out/bagfile_<scenario>_<variant>/`."""
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for s in scenarios():
        for variant in range(1, len(s.variants) + 1):
            if only is not None and not only(s.id, variant):
                continue
            path = out / recording_name(s.id, variant)
            if path.exists():
                shutil.rmtree(path)
            record(s, variant, seed).write(path, storage)
            written.append(path)
    return written
