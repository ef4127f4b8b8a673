"""Rebuild the no-LLM router's weights from agent/data/router_examples.yaml (deterministic).

.venv/bin/python scripts/train_router.py [--out agent/data/router_model.json]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from hexar.agent.router_training import export, fit

DEFAULT_OUT = Path(__file__).resolve().parent.parent / "agent" / "data" / "router_model.json"


def dumps(model: dict[str, object]) -> str:
    return json.dumps(model, sort_keys=True, separators=(",", ":")) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT)
    args = parser.parse_args()
    began = time.perf_counter()
    model = export(fit())
    args.out.write_text(dumps(model), encoding="utf-8")
    print(f"fitted {len(model['labels'])} labels in {time.perf_counter() - began:.1f} s -> {args.out}")  # type: ignore[arg-type]


if __name__ == "__main__":
    main()
