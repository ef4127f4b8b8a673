#!/usr/bin/env bash
# Run the README's test command again on a newer Python, in a fresh clone of this checkout's HEAD (committed work
# only): bash scripts/newer_python.sh [python3.13] [pytest options...]
# A fresh Debian machine is Debian 13 with Python 3.13, while this project's machines and CI have 3.11; two things
# that passed on 3.11 failed there (setup's compile step, whose worker processes start by forkserver from 3.12 on,
# and a tool's description, whose docstring 3.13 dedents when it compiles it). Without that Python on PATH the
# check is skipped, and one line says so. pyenv's installed versions count too, selected or not.
set -euo pipefail
cd "$(dirname "$0")/.."
want="${1:-python3.13}"
find_python() {
  "$want" -c 'import sys; print(sys.executable)' 2>/dev/null && return
  # pyenv's shims run only the versions it has selected: ask it for an installed one of that minor version (its root
  # found from where pyenv itself is, so that a run with another HOME finds it too)
  local pyenv v minor="${want#python}"
  pyenv="$(command -v pyenv)" || return 1
  export PYENV_ROOT="${PYENV_ROOT:-$(cd "$(dirname "$(readlink -f "$pyenv")")/.." && pwd)}"
  v="$("$pyenv" versions --bare 2>/dev/null | grep -xE "${minor//./\\.}(\.[0-9]+)?" | sort -V | tail -1)"
  [ -n "$v" ] && PYENV_VERSION="$v" "$pyenv" which "$want" 2>/dev/null
}
if ! exe="$(find_python)"; then
  echo "$want was found neither on PATH nor by pyenv: the check on a newer Python is skipped"
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
