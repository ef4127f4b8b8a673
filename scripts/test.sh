#!/usr/bin/env bash
# Set up and run every check CI runs: ruff, mypy (strict) and the default test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/ruff check .
bash scripts/mypy.sh
.venv/bin/python -m pytest -q "$@"
