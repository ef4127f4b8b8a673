"""Rebuild the ask-human-for-help causal model from simulated executions (deterministic for a given seed).

.venv/bin/python scripts/train_ask_human.py [--n 3000] [--seed 11] [--out explainers/ask_human/model.json]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from hexar.evals.scenarios.ask_human import training_executions
from hexar.explainers.ask_human.causal import MODEL_FILE, TRAINING_N, TRAINING_SEED, CausalModel

DEFAULT_OUT = Path(__file__).resolve().parent.parent / "explainers" / "ask_human" / MODEL_FILE


def build(n: int = TRAINING_N, seed: int = TRAINING_SEED) -> CausalModel:
    return CausalModel.fit(training_executions(n, seed), seed=seed)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=TRAINING_N, help="simulated executions (at least 1000)")
    parser.add_argument("--seed", type=int, default=TRAINING_SEED)
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT)
    args = parser.parse_args()
    if args.n < 1000:
        parser.error("--n must be at least 1000 for every failure mode to be seen often enough")
    began = time.perf_counter()
    model = build(args.n, args.seed)
    model.save(args.out)
    took = time.perf_counter() - began
    print(f"fitted on {args.n} executions (seed {args.seed}) in {took:.1f} s -> {args.out}")


if __name__ == "__main__":
    main()
