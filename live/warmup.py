"""The live node's warm-up: the first-answer costs paid before traffic comes in."""

from __future__ import annotations

import json
from typing import Any

from hexar.events import contract as c
from hexar.events.records import StatusRecord
from hexar.events.task_info import parse_task_info
from hexar.live.log import NS, LiveLog


def warm_up(session: Any, question: str) -> None:
    """Pay the first-answer costs now (pgmpy's causal model, the pizza tree, each explainer's first call): one
    `question` per module on a made-up log of failed tasks, answered and thrown away."""
    from hexar.explainers.ask_human.explainer import shipped_model
    from hexar.explainers.pizza.recommender import default_recommender

    shipped_model().p_success({})  # imports pgmpy's inference and builds its engine
    default_recommender()
    warm = LiveLog(name="warm-up")
    for i, skill in enumerate(("navigate_to_zone", "ask_human_for_help", "say", "recommend_pizza")):
        step = {"skill": skill, "params": {}, "status": "failed", "error_msg": "The skill has been aborted"}
        raw = json.dumps({"instruction": "warm up", "task_id": f"warm{i}", "task_status": "valid",
                          "task_error_msg": "", "skill_sequence": [step]})
        update = parse_task_info((i + 3) * NS, raw)
        if skill == "ask_human_for_help":  # a detection failure makes the causal search run once
            for j, (key, value) in enumerate((("InitialState", "True"), ("DetectState", "True"),
                                              ("person_detected", "True"), ("person_std_rms", "0.9"),
                                              ("detection_stable", "False"), ("SkillFailed", "True"))):
                warm.add(StatusRecord((i + 2) * NS + j, c.EPISODIC_MEMORY, 0, c.ASK_HUMAN_STATUS_NAME, key, "",
                                      (("Module name", "skill_ask_human_for_help"), (key, value))))
        if update is not None:
            warm.add(update)
            session.use_log(warm.snapshot())
            thread = session.ask(question, task=update.task_id)["thread"]
            session.graph.checkpointer.delete_thread(f"{session.settings.recording}::{thread}")
