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
config=pyproject.toml
# cyclonedds has no wheel for CPython 3.14 (the lock installs it only below): there the modules written against its
# types cannot be checked, and mypy is told so; every other module is checked as everywhere.
if ! .venv/bin/python -c 'import cyclonedds' 2>/dev/null; then
  echo "mypy: cyclonedds is not installed for this Python; live/dds.py, live/msgs.py and live/graph_info.py are checked where it is"
  config="$tree/mypy.ini"
  .venv/bin/python - "$config" <<'PY'
import sys, tomllib
mypy = tomllib.load(open("pyproject.toml", "rb"))["tool"]["mypy"]
ini = lambda v: ",".join(v) if isinstance(v, list) else str(v)
lines = ["[mypy]", *(f"{k} = {ini(v)}" for k, v in mypy.items() if k != "overrides")]
for o in mypy.get("overrides", []):
    lines += [f"[mypy-{ini(o['module'])}]", *(f"{k} = {ini(v)}" for k, v in o.items() if k != "module")]
lines += ["[mypy-cyclonedds.*]", "ignore_missing_imports = True",
          "[mypy-hexar.live.dds,hexar.live.msgs,hexar.live.graph_info]", "ignore_errors = True"]
open(sys.argv[1], "w").write("\n".join(lines) + "\n")
PY
fi
MYPYPATH="$tree" .venv/bin/mypy --config-file "$config" -p hexar
