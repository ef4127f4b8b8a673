"""Send `hexar serve --transport dds` SIGUSR1 three times, 0.2 s apart, then SIGTERM, and count the serves that did
not survive it (killed by a signal) or did not print the stacks and end with exit 0; over many runs.

    python scripts/stress_sigusr1.py [--python PY] [--runs 40] [--first-domain 150]

Round 44 measured faulthandler's all-threads dump (the code before live/stacks.py) on Python 3.13.0: 4 of 40 serves
died with SIGSEGV; live/stacks.py: 0 of 40 on 3.13.0 and on 3.11.7.
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time

# Cyclone on loopback with unicast discovery, as the live tests set it (tests/live/conftest.py)
LOOPBACK = ('<General><Interfaces><NetworkInterface address="127.0.0.1"/></Interfaces>'
            "<AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>auto</ParticipantIndex>"
            '<MaxAutoParticipantIndex>60</MaxAutoParticipantIndex><Peers><Peer address="127.0.0.1"/></Peers>'
            "</Discovery>")


def one(python: str, domain: int, env: dict[str, str], cwd: str) -> str:
    """'ok', 'crash' (ended by a signal, or gone before SIGTERM) or 'bad' (no stacks, or a non-zero exit)."""
    serve = subprocess.Popen([python, "-m", "hexar", "serve", "--transport", "dds", "--domain", str(domain),
                              "--no-follow-launch-log", "--llm", "none"], stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True, env=env, cwd=cwd)
    assert serve.stderr is not None
    serve.stderr.readline()  # "hexar serve: listening ..."
    for _ in range(3):
        serve.send_signal(signal.SIGUSR1)
        time.sleep(0.2)
    time.sleep(0.5)
    alive = serve.poll() is None
    if alive:
        serve.send_signal(signal.SIGTERM)
    _, err = serve.communicate(timeout=30)
    if not alive or serve.returncode < 0:
        return "crash"
    return "ok" if serve.returncode == 0 and "most recent call first" in err else "bad"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--python", default=sys.executable, help="the interpreter of the venv HEXAR is installed in")
    parser.add_argument("--runs", type=int, default=40)
    parser.add_argument("--first-domain", type=int, default=150)
    args = parser.parse_args()
    env = dict(os.environ, CYCLONEDDS_URI=LOOPBACK)
    counts = {"ok": 0, "crash": 0, "bad": 0}
    with tempfile.TemporaryDirectory() as cwd:
        for i in range(args.runs):
            got = one(args.python, args.first_domain + i % 50, env, cwd)
            counts[got] += 1
            if got != "ok":
                print(f"run {i}: {got}", flush=True)
    print(f"{args.runs} serves, SIGUSR1 x3 each: {counts['crash']} crashed, {counts['bad']} without stacks or exit 0")
    return 0 if counts["ok"] == args.runs else 1


if __name__ == "__main__":
    sys.exit(main())
