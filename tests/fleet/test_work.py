"""Fast triage gives the answers slow triage gave: on the 60 simulated recordings, `hexar triage` with two workers
(typestores shared between recordings, metadata read by libyaml, causal queries answered once per process) and the
plain way (rosbags' AnyReader opening every recording afresh, every causal query computed) agree on every task of
every recording: outcome, verdict, explainer, causes, explanation and evidence."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from rosbags.highlevel import AnyReader

from hexar.cli import main
from hexar.events import read_recording, reader
from hexar.explainers.ask_human.causal import CausalModel
from hexar.explainers.base import Context
from hexar.explainers.pizza.explainer import PizzaRecommenderExplainer
from hexar.fleet.command import RESULTS
from hexar.fleet.inputs import expand
from hexar.fleet.work import QUESTION, first_sentence, registry, triage_recording


def _by_recording(results: list[dict[str, Any]]) -> dict[str, tuple[str, list[dict[str, Any]]]]:
    return {r["recording"]: (r["error"], r["rows"]) for r in results}


def test_fast_triage_answers_as_the_plain_way(suite: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "fast"
    assert main(["triage", str(suite), "--out", str(out), "--workers", "2", "--no-figures"]) == 0
    fast = _by_recording([json.loads(line) for line in (out / RESULTS).read_text().splitlines()])

    monkeypatch.setattr(reader, "Reader", AnyReader)
    monkeypatch.setattr(CausalModel, "probability", CausalModel._probability)
    plain = _by_recording([triage_recording(path, rel) for path, rel in expand([str(suite)])])

    assert len(plain) == 60 and sum(len(rows) for _, rows in plain.values()) >= 60
    assert {row["kind"] for _, rows in plain.values() for row in rows} == {"failure", "finding", ""}
    assert fast == plain


# What the pizza explainer's LIME needs (seconds to import), and the causal library the help explainer was built
# from: a fleet that has no pizza recommendation to explain must not pay for them.
HEAVY = ("sklearn", "lime", "pgmpy", "scipy", "statsmodels")
TRIAGE_AND_LIST_MODULES = """
import json, sys
from hexar.cli import main
code = main(["triage", *sys.argv[3:], "--out", sys.argv[2], "--workers", "1", "--no-figures"])
print(json.dumps({"code": code, "heavy": sorted({m.split(".")[0] for m in sys.modules} & set(sys.argv[1].split(",")))}))
"""


def _triage_in_fresh_process(out: Path, recordings: list[Path]) -> tuple[int, list[str], list[dict[str, Any]]]:
    done = subprocess.run([sys.executable, "-c", TRIAGE_AND_LIST_MODULES, ",".join(HEAVY), str(out),
                           *map(str, recordings)],
                          capture_output=True, text=True, timeout=600, check=False)
    got = json.loads(done.stdout.strip().splitlines()[-1])
    rows = [json.loads(line) for line in (out / "tasks.jsonl").read_text().splitlines()]
    return got["code"], got["heavy"], rows


def test_triage_imports_lime_and_sklearn_only_for_a_pizza_recording_to_explain(suite: Path, tmp_path: Path) -> None:
    recordings = sorted(p.parent for p in suite.glob("*/metadata.yaml"))
    pizza = [p for p in recordings if p.name.startswith("bagfile_20_")]
    others = [p for p in recordings if p not in pizza]
    assert len(pizza) == 3 and len(others) == 57

    code, heavy, rows = _triage_in_fresh_process(tmp_path / "others", others)
    assert code == 0 and heavy == []
    assert {r["kind"] for r in rows} == {"failure", "finding", ""}  # the other explainers did run
    assert "pizza_recommender" not in {r["explainer"] for r in rows}

    code, heavy, rows = _triage_in_fresh_process(tmp_path / "pizza", pizza)
    assert code == 0 and {"sklearn", "lime"} <= set(heavy) and "pgmpy" not in heavy
    reg = registry()
    for path, row in zip(pizza, rows, strict=True):
        log = read_recording(path)
        task = next(t for t in log.tasks if t.task_id == row["task_id"])
        direct = PizzaRecommenderExplainer().explain(QUESTION, Context.for_task(log, task, reg))
        # the finding a fleet report lists is LIME's answer, word for word
        assert (row["kind"], row["explainer"], row["causes"]) == ("finding", "pizza_recommender", direct.causes)
        assert row["explanation"] == first_sentence(direct.text) and " because you have " in row["explanation"]
