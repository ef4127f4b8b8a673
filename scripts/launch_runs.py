"""What scripts/nav2_faults.py, scripts/control_faults.py and scripts/base_faults.py share to run a robot's bring-up
with the real ros2launch and record its console: the runner program, a program installed as a package's executable
(so launch_ros finds it through the ament index), the process kill a fault sends from outside, one run (the launch,
a client from outside it, Ctrl-C two seconds after the client's result), and the data file."""

from __future__ import annotations

import argparse
import json
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

import yaml
from stack_faults import scrub as stack_scrub

RUNNER = """\
import sys
from ros2launch.api import launch_a_launch_file

sys.stdout.reconfigure(line_buffering=True)
sys.exit(launch_a_launch_file(launch_file_path=sys.argv[1], launch_file_arguments=[], noninteractive=True))
"""
# the client programs' goal, sent from outside the launch: what a fault does to a process on the way (as the kernel's
# OOM killer or a person does) goes to every process whose command line holds `pattern`, but the client itself,
# whose own command line names it
HIT = """\
def hit_process(pattern, sig):
    import os
    import signal
    import subprocess
    pids = subprocess.run(['pgrep', '-f', pattern], capture_output=True, text=True).stdout
    for pid in (int(p) for p in pids.split() if int(p) != os.getpid()):
        os.kill(pid, getattr(signal, sig))


def send_goal(node, client, goal, hit, pattern, run_s, result):
    # send goal; hit (PROCESS SIGNAL SECONDS) that long into it to the processes pattern names; wait run_s for the
    # result and cancel the goal then, as a person gives up: the result's future, None without one
    import time
    import rclpy
    sent = client.send_goal_async(goal)
    rclpy.spin_until_future_complete(node, sent, timeout_sec=10.0)
    handle = sent.result()
    if handle is None or not handle.accepted:
        return None
    result['accepted'] = True
    began = time.monotonic()
    done = handle.get_result_async()
    if hit:
        rclpy.spin_until_future_complete(node, done, timeout_sec=float(hit[2]))
        if not done.done():
            hit_process(pattern, hit[1])
            result['hit'] = f'{hit[1]} to {hit[0]} after {hit[2]} s'
    rclpy.spin_until_future_complete(node, done, timeout_sec=run_s)
    result['seconds'] = round(time.monotonic() - began, 1)
    if done.done():
        return done
    rclpy.spin_until_future_complete(node, handle.cancel_goal_async(), timeout_sec=5.0)
    return None
"""


def install(prefix: Path, package: str, executable: str, source: str) -> None:
    """`source` as `package`'s executable under `prefix`, run by this Python, with the package's ament index mark."""
    program = prefix / "lib" / package / executable
    program.parent.mkdir(parents=True, exist_ok=True)
    program.write_text(f"#!{sys.executable}\n{source}", encoding="utf-8")
    program.chmod(0o755)
    index = prefix / "share/ament_index/resource_index/packages" / package
    index.parent.mkdir(parents=True, exist_ok=True)
    index.write_text("", encoding="utf-8")


def run_launch(launch: Path, prefix: Path, work: Path, launch_path: list[Path], client: tuple[str, list[str]],
               result_file: Path, timeout_s: float) -> tuple[str, dict[str, Any]]:
    """Launch `launch` with `prefix` on the ament path, run the client program (its source, its arguments) from
    outside it, Ctrl-C the launch two seconds after the client ends: the console and the result the client wrote."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_DOMAIN_ID", "PYTHONPATH"))}
    env["AMENT_PREFIX_PATH"] = os.pathsep.join((str(prefix), env.get("AMENT_PREFIX_PATH", "")))
    env["PYTHONPATH"] = os.pathsep.join([*map(str, launch_path), os.environ.get("PYTHONPATH", "")])
    env["ROS_HOME"] = str(work / ".ros")
    env["RCUTILS_COLORIZED_OUTPUT"] = "0"
    env["ROS_DOMAIN_ID"] = str(220 + os.getpid() % 12)  # away from other ROS traffic (and tests) on this computer
    (work / "ros2_launch.py").write_text(RUNNER, encoding="utf-8")
    (work / "client.py").write_text(client[0], encoding="utf-8")
    # a shell runs a command started with & with SIGINT ignored, and the launch would inherit that and never hear
    # its Ctrl-C: its console would end in the SIGKILL a minute later instead of the stack's shutdown
    with subprocess.Popen([sys.executable, "ros2_launch.py", str(launch)], cwd=work, env=env, text=True,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True,
                          preexec_fn=_default_sigint) as proc:
        sender = subprocess.run([sys.executable, "client.py", *client[1]], cwd=work, env=env, capture_output=True,
                                text=True, timeout=timeout_s, check=False)
        time.sleep(2.0)
        proc.send_signal(signal.SIGINT)
        try:
            out, _ = proc.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            out, _ = proc.communicate()
    result = json.loads(result_file.read_text()) if result_file.exists() else {"error": sender.stderr[-500:]}
    return out, result


def _default_sigint() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)


Runner = Callable[[Any, Path, list[Path]], tuple[str, dict[str, Any]]]


def arguments(doc: str | None) -> argparse.ArgumentParser:
    """The options every fault script takes: --out, --only, --launch-path, --names."""
    parser = argparse.ArgumentParser(description=(doc or "").splitlines()[0])
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--only", nargs="*", default=None, help="only these fault ids")
    parser.add_argument("--launch-path", type=Path, nargs="*", default=[],
                        help="folders holding launch, launch_ros, ros2launch and osrf_pycommon, if not installed")
    parser.add_argument("--names", nargs="*", default=[], help="LOCAL=FIXED folder names to replace in the output")
    return parser


def scrub(text: str, work: Path, names: list[tuple[str, str]]) -> str:
    """The console as stack_faults.scrub leaves it (no ANSI colours or trailing blanks, the work folder and this
    Python's folders fixed), with the other folders `names` gives and launch's log folder's host name fixed too."""
    out = stack_scrub(text, work)
    for local, fixed in names:
        out = out.replace(local, fixed)
    return re.sub(r"(\d{4}(?:-\d+){6})-" + re.escape(socket.gethostname()) + r"-(\d+)", r"\1-robot-\2", out)


def runs(faults: Sequence[Any], args: argparse.Namespace, run: Runner) -> Iterator[tuple[Any, str, dict[str, Any]]]:
    """Each fault `args.only` keeps, run in a folder of its own: the fault, its console scrubbed, its result."""
    names = sorted((tuple(n.split("=", 1)) for n in args.names), key=lambda pair: -len(pair[0]))
    for fault in faults:
        if args.only and fault.id not in args.only:
            continue
        with tempfile.TemporaryDirectory() as tmp:
            began = time.monotonic()
            text, result = run(fault, Path(tmp), [p.absolute() for p in args.launch_path])
            lines = scrub(text, Path(tmp), names)  # type: ignore[arg-type]
        print(f"{fault.id}: {result} {len(lines.splitlines())} lines {time.monotonic() - began:.0f} s", flush=True)
        yield fault, lines, result


def kept(fault_id: str, outcome: str, cause: str, nominal: str) -> bool:
    """A run with no fault that failed has no cause to grade: it is left out, and said so."""
    print(f"{fault_id}: {outcome} {cause}", flush=True)
    if outcome == "failed" and cause == nominal:
        print(f"{fault_id}: a run with no fault failed, so no cause is known: left out", flush=True)
        return False
    return True


def write_set(out: Path, header: str, entries: list[dict[str, Any]]) -> None:
    """The data file: its header, then the kept runs as YAML."""
    body = yaml.safe_dump(entries, sort_keys=False, allow_unicode=True, width=120)
    out.write_text(header + "\n" + body, encoding="utf-8")
