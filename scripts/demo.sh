#!/usr/bin/env bash
# The main job on the embedded defaults: set up, simulate the paper's 60 runs if missing, answer a question
# about a failed run (the deterministic failure check picks the explainer) and one about a run where nothing
# failed (the in-process model routes the question). No GPU, no network at run time.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --full
SUITE=runs/suite
[ -d "$SUITE/bagfile_20_3" ] || .venv/bin/hexar simulate --out "$SUITE"
.venv/bin/hexar inspect "$SUITE/bagfile_5_1"
.venv/bin/hexar ask "$SUITE/bagfile_5_1" "Why didn't you bring me the coffee?" --llm embedded --verbose
.venv/bin/hexar ask "$SUITE/bagfile_9_1" "Why did it take you so long to bring me the coffee?" --llm embedded --verbose
