#!/usr/bin/env bash
# mypy cannot follow setuptools' package-dir mapping of an editable install, so check a tree of links that
# has the installed layout (hexar/agent -> agent/, ...).
set -euo pipefail
cd "$(dirname "$0")/.."
tree=$(mktemp -d)
trap 'rm -rf "$tree"' EXIT
mkdir -p "$tree/hexar"
for f in hexar/*.py hexar/py.typed hexar/*.yaml; do ln -s "$PWD/$f" "$tree/hexar/"; done
for d in agent tools explainers prompts voice evals events web live fleet; do ln -s "$PWD/$d" "$tree/hexar/$d"; done
MYPYPATH="$tree" .venv/bin/mypy --config-file pyproject.toml -p hexar
