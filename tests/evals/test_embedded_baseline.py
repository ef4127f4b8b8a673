"""Prompt regression on the embedded model (slow, opt-in: `pytest -m slow`): one case per scenario, all three
methods, against the committed `evals/baselines/embedded.json`. About 13 minutes on 2 cores."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexar.agent.backends import embedded_available
from hexar.cli import main

ROOT = Path(__file__).resolve().parents[2]
pytestmark = pytest.mark.slow


@pytest.mark.skipif(not embedded_available(), reason="embedded model not installed (scripts/setup.sh --full)")
def test_embedded_sample_matches_its_baseline(suite: Path, tmp_path: Path) -> None:
    code = main(["eval", "--llm", "embedded", "--first", "1", "--runs", str(suite), "--out", str(tmp_path),
                 "--baseline", str(ROOT / "evals" / "baselines" / "embedded.json"), "--no-figures"])
    assert code == 0
