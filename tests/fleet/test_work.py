"""Fast triage gives the answers slow triage gave: on the 60 simulated recordings, `hexar triage` with two workers
(typestores shared between recordings, metadata read by libyaml, causal queries answered once per process) and the
plain way (rosbags' AnyReader opening every recording afresh, every causal query computed) agree on every task of
every recording: outcome, verdict, explainer, causes, explanation and evidence."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from rosbags.highlevel import AnyReader

from hexar.cli import main
from hexar.events import reader
from hexar.explainers.ask_human.causal import CausalModel
from hexar.fleet.command import RESULTS
from hexar.fleet.inputs import expand
from hexar.fleet.work import triage_recording


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
