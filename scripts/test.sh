#!/usr/bin/env bash
# Set up and run every check CI runs: ruff, mypy (strict) and the default test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/ruff check .
bash scripts/mypy.sh
# Three test processes (pytest-xdist): most of the live tests' time is the robot's pacing, DDS leases and the
# node's second looks, not CPU, so a 2-core machine runs three at once (README "Two commands"). -n 0 runs one.
.venv/bin/python -m pytest -q -n 3 --dist worksteal "$@"
