#!/usr/bin/env bash
# Run the README's test command again on a newer Python, in a fresh clone of this checkout's HEAD (committed work
# only): bash scripts/newer_python.sh [python3.13] [pytest options...]
# A fresh Debian machine is Debian 13 with Python 3.13, while this project's machines and CI have 3.11; two things
# that passed on 3.11 failed there (setup's compile step, whose worker processes start by forkserver from 3.12 on,
# and a tool's description, whose docstring 3.13 dedents when it compiles it). Without that Python on PATH the
# check is skipped, and one line says so.
set -euo pipefail
cd "$(dirname "$0")/.."
want="${1:-python3.13}"
if ! exe="$(command -v "$want" >/dev/null && "$want" -c 'import sys; print(sys.executable)' 2>/dev/null)"; then
  echo "$want is not on PATH: the check on a newer Python is skipped"
  exit 0
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
git clone -q "$PWD" "$work/hexar"
# setup.sh makes its virtual environment with `python3`: the chosen interpreter under that name
mkdir "$work/bin"
ln -s "$exe" "$work/bin/python3"
echo "the tests again on $("$exe" -V)"
cd "$work/hexar"
PATH="$work/bin:$PATH" bash scripts/test.sh "${@:2}"
