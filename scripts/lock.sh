#!/usr/bin/env bash
# Regenerate requirements.lock: every package (with sha256 hashes) that setup.sh installs, for every extra the
# README's commands use, resolved for CPython 3.11+ on any platform (markers fork a version where one Python needs
# another). Run it after changing a dependency in pyproject.toml or to take newer versions on purpose, then run
# `bash scripts/test.sh` and commit the lock with the change it belongs to.
# llama-cpp-python is built from source by setup.sh --full (version pinned there); its own dependencies are locked.
set -euo pipefail
cd "$(dirname "$0")/.."
tool="$(mktemp -d)"
trap 'rm -rf "$tool"' EXIT
python3 -m venv "$tool"
"$tool/bin/python" -m pip install -q "uv==0.13.9"
"$tool/bin/uv" pip compile pyproject.toml scripts/lock-build.in \
  --extra dev --extra voice --extra live --extra ros --extra mcp --extra fleet --extra embedded \
  --no-emit-package llama-cpp-python --generate-hashes --universal --python-version 3.11 \
  --custom-compile-command "bash scripts/lock.sh" -o requirements.lock "$@"
