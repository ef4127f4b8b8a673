"""Real console output of the ROS 2 stack installed here (rclpy, rcl and Fast DDS of ROS 2 Kilted from PyPI, and the
Cyclone DDS core through `cyclonedds`), each run with one fault a robot's bring-up meets in the field: a params file
rcl cannot read, a remap or log level it cannot parse, a parameter of the wrong type, a middleware the environment
names but the install lacks, a domain id past DDS's port range, a discovery setting or peer that cannot work, a network
interface that is not there, a DDS profile that does not load, a node that died of an exception.

Every fault is run for real and its output kept as printed, with two exceptions that keep this machine out of the
file: ANSI colours are removed (as a paste shows them), and this machine's folders (the virtual environment, the
work folder) are replaced by fixed names. The cause of each excerpt is the fault injected, written here before any
output was read. Writes real_modules-format excerpts (evals/data/real_modules/README.md) to --out.

    .venv/bin/python scripts/stack_faults.py --out FILE.yaml
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import sysconfig
import tempfile
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from importlib.metadata import version
from pathlib import Path

import yaml

NODE = """\
import sys
import rclpy
from rclpy.node import Node

rclpy.init(args=sys.argv)
node = Node('scan_filter')
node.declare_parameter('scan_rate', 10)
node.get_logger().info(f"filtering scans at {node.get_parameter('scan_rate').value} Hz")
if '--crash' in sys.argv:
    def tick() -> None:
        ranges: list[float] = []
        node.get_logger().info(f'closest obstacle {min(ranges)} m')
    node.create_timer(0.05, tick)
    rclpy.spin(node)
rclpy.spin_once(node, timeout_sec=0.2)
node.destroy_node()
rclpy.shutdown()
"""

CYCLONE = """\
from cyclonedds.domain import DomainParticipant
DomainParticipant(0)
print('participant created')
"""

BAD_FLOW = "scan_filter:\n  ros__parameters:\n    ignore_sectors: [30, 60\n    scan_rate: 10\n"
BEFORE = "scan_filter:\n  scan_rate: 10\n  ros__parameters:\n    scan_rate: 10\n"
WRONG_TYPE = "scan_filter:\n  ros__parameters:\n    scan_rate: fast\n"
BAD_PROFILE = ('<?xml version="1.0" encoding="UTF-8" ?>\n<profiles xmlns="http://www.eprosima.com">\n'
               '  <participant profile_name="udp_only" is_default_profile="true">\n    <rtps>\n'
               '      <useBuiltinTransports>false</useBuiltinTransports>\n    </rtps>\n  </participant>\n')
NO_IFACE = ('<CycloneDDS><Domain><General><Interfaces><NetworkInterface name="wlan0"/></Interfaces>'
            '</General></Domain></CycloneDDS>')


@dataclass(frozen=True)
class Fault:
    id: str
    module: str
    cause: str
    cause_quote: str  # the fault injected, as a person who set it would say it
    args: tuple[str, ...] = ()
    env: dict[str, str] = field(default_factory=dict)
    files: dict[str, str] = field(default_factory=dict)
    program: str = "node"
    outcome: str = "failed"
    notes: str = ""


CONFIG = "bringup.configuration_error"
FAULTS = (
    Fault("params-file-yaml-syntax", "bringup", CONFIG,
          "The params file has a flow sequence that is never closed (a missing ']'), so rcl cannot parse it.",
          ("--ros-args", "--params-file", "scan_filter.yaml"), files={"scan_filter.yaml": BAD_FLOW}),
    Fault("params-file-missing", "bringup", CONFIG,
          "The params file named on the command line does not exist (a wrong path).",
          ("--ros-args", "--params-file", "config/scan_filter.yaml")),
    Fault("params-file-value-before-ros-parameters", "bringup", CONFIG,
          "A parameter is written under the node's name but outside ros__parameters, which rcl refuses.",
          ("--ros-args", "--params-file", "scan_filter.yaml"), files={"scan_filter.yaml": BEFORE}),
    Fault("params-file-wrong-type", "bringup", CONFIG,
          "The params file sets scan_rate to a string where the node declares an integer.",
          ("--ros-args", "--params-file", "scan_filter.yaml"), files={"scan_filter.yaml": WRONG_TYPE}),
    Fault("remap-node-name-with-dash", "bringup", CONFIG,
          "The node is renamed with a dash in its name (__node:=front-lidar), which is not a valid ROS name.",
          ("--ros-args", "-r", "__node:=front-lidar")),
    Fault("remap-without-replacement", "bringup", CONFIG,
          "A remap rule was written without its replacement (scan:=), so rcl cannot parse the arguments.",
          ("--ros-args", "-r", "scan:=")),
    Fault("log-level-misspelt", "bringup", CONFIG,
          "The log level is misspelt ('warning' instead of 'warn'), so rcl refuses the arguments.",
          ("--ros-args", "--log-level", "warning")),
    Fault("rmw-implementation-not-installed", "bringup", CONFIG,
          "RMW_IMPLEMENTATION names Cyclone DDS, which this install does not have; it has Fast DDS only.",
          env={"RMW_IMPLEMENTATION": "rmw_cyclonedds_cpp"}),
    Fault("node-died-on-exception", "bringup", "bringup.process_died",
          "The node's timer callback took min() of an empty list of ranges, raised, and the process ended.",
          ("--crash",)),
    Fault("domain-id-out-of-range", "system", "system.network",
          "ROS_DOMAIN_ID is 300, past the domain ids whose DDS ports exist (0-232), so the node cannot join.",
          env={"ROS_DOMAIN_ID": "300"}),
    Fault("discovery-range-misspelt", "system", "system.network",
          "ROS_AUTOMATIC_DISCOVERY_RANGE is misspelt, so discovery stays on this host and the robot's other "
          "computer is never seen.", env={"ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNETT"}),
    Fault("static-peer-unresolvable", "system", "system.network",
          "ROS_STATIC_PEERS names a host name that does not resolve on this network, so the node is not created.",
          env={"ROS_STATIC_PEERS": "robot-base.local"}),
    Fault("cyclone-interface-missing", "system", "system.network",
          "CYCLONEDDS_URI names a network interface (wlan0) this machine does not have, so Cyclone DDS creates "
          "no participant.", env={"CYCLONEDDS_URI": NO_IFACE}, program="cyclone",
          notes="Run with the cyclonedds Python binding, whose DDS core is the one rmw_cyclonedds_cpp loads; a "
                "ROS node would print the core's line the same way and then rmw's own error."),
    Fault("fastdds-profile-not-closed", "system", CONFIG,
          "The Fast DDS profiles file (UDP only, no shared memory) is cut off before its closing tags, so it is "
          "not loaded and the default transports are used.",
          env={"FASTDDS_DEFAULT_PROFILES_FILE": "fastdds_udp.xml"}, files={"fastdds_udp.xml": BAD_PROFILE}),
    Fault("fastdds-builtin-transports-misspelt", "system", CONFIG,
          "FASTDDS_BUILTIN_TRANSPORTS is misspelt (UDP4 for UDPv4), so Fast DDS keeps its default transports.",
          env={"FASTDDS_BUILTIN_TRANSPORTS": "UDP4"}),
)

ANSI = re.compile(r"\x1b\[[0-9;]*m")
HEADER = """\
# Held-out set 22 of real console excerpts (issue 23's format): not pasted by people, but printed by the real ROS 2
# stack installed on this project's machine (ROS 2 Kilted's rclpy, rcl and Fast DDS from PyPI, and the Cyclone DDS
# core through the cyclonedds binding), each run with one bring-up or middleware fault injected: written by
# scripts/stack_faults.py, which states each excerpt's cause (the fault) before it runs anything. Output is kept as
# printed, less ANSI colours, with this machine's folders replaced by /opt/venv/... and /home/robot/ws. Frozen and
# measured once before anything was tuned on it. Regenerate with: .venv/bin/python scripts/stack_faults.py --out FILE
"""


def run(fault: Fault, work: Path) -> tuple[str, int]:
    for name, text in fault.files.items():
        (work / name).write_text(text, encoding="utf-8")
    script = work / ("scan_filter.py" if fault.program == "node" else "participant.py")
    script.write_text(NODE if fault.program == "node" else CYCLONE, encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "RMW_", "FASTDDS_", "CYCLONEDDS_"))}
    env.update(fault.env)
    done = subprocess.run([sys.executable, script.name, *fault.args], cwd=work, env=env, capture_output=True,
                          text=True, timeout=60, check=False)
    return done.stdout + done.stderr, done.returncode


def scrub(text: str, work: Path) -> str:
    """`text` less ANSI colours and trailing blanks, with this machine's folders (the venv's packages, the Python
    running this, its standard library in a thread's traceback, the fault's work folder) replaced by fixed names."""
    out = ANSI.sub("", text)
    out = out.replace(sysconfig.get_paths()["purelib"], "/opt/venv/lib/python3/site-packages")
    out = out.replace(sys.executable, "/opt/venv/bin/python")
    out = out.replace(sysconfig.get_paths()["stdlib"], "/usr/lib/python3.11")
    out = out.replace(str(work.resolve()), "/home/robot/ws").replace(str(work), "/home/robot/ws")
    return "\n".join(line.rstrip() for line in out.strip().splitlines()) + "\n"


def write_set(out: Path, header: str, script: str, stack: str, faults: Iterable[Fault],
              run_one: Callable[[Fault, Path], tuple[str, int]], silent: Mapping[str, str] | None = None,
              notes: Mapping[str, str] | None = None) -> None:
    """Run each fault in a folder of its own (`run_one`: its scrubbed output and exit code) and write the excerpts in
    the real_modules format, `silent` ones (id -> why) with logs_show_cause false, to `out` under `header`."""
    silent, notes = silent or {}, notes or {}
    entries = []
    for fault in faults:
        with tempfile.TemporaryDirectory() as tmp:
            lines, code = run_one(fault, Path(tmp))
        print(f"{fault.id}: exit {code}, {len(lines.splitlines())} lines")
        said = [f"Exit code {code}.", fault.notes, silent.get(fault.id, ""), notes.get(fault.id, "")]
        entries.append({
            "id": f"kilted-{fault.id}", "source": f"scripts/{script} on ROS 2 Kilted ({stack})",
            "url": f"scripts/{script}#{fault.id}", "distro": "kilted", "module": fault.module,
            "outcome": fault.outcome, "cause": fault.cause,
            "cause_quote": fault.cause_quote, "logs_show_cause": fault.id not in silent,
            "notes": " ".join(filter(None, said)), "lines": lines})
    body = yaml.safe_dump(entries, sort_keys=False, allow_unicode=True, width=120)
    out.write_text(f"{header}\n{body}", encoding="utf-8")


def run_written(fault: Fault, work: Path, programs: Mapping[str, str], scripts: Mapping[str, str]) -> tuple[str, int]:
    """Write the fault's files and its program (`programs[fault.program]`, as `scripts` names it, else
    `<program>.py`) into `work` and run it there with the fault's arguments and environment (none of this machine's
    ROS_, RMW_ or DDS variables; rcl's log files in `work`): its output and exit code."""
    for name, text in fault.files.items():
        (work / name).parent.mkdir(parents=True, exist_ok=True)
        (work / name).write_text(text, encoding="utf-8")
    script = work / scripts.get(fault.program, f"{fault.program}.py")
    script.write_text(programs[fault.program], encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "RMW_", "FASTDDS_", "CYCLONEDDS_"))}
    env.update(fault.env)
    env["ROS_HOME"] = str(work / ".ros")  # rcl's log files, kept out of this machine's home
    done = subprocess.run([sys.executable, script.name, *fault.args], cwd=work, env=env, capture_output=True,
                          text=True, timeout=60, check=False)
    return done.stdout + done.stderr, done.returncode


def generate(doc: str, header: str, script: str, faults: Iterable[Fault], programs: Mapping[str, str],
             scripts: Mapping[str, str], silent: Mapping[str, str] | None = None,
             notes: Mapping[str, str] | None = None) -> int:
    """A generator's command line (`--out FILE.yaml`): each fault run by run_written, its output scrubbed, written
    by write_set."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()

    def run_one(fault: Fault, work: Path) -> tuple[str, int]:
        text, code = run_written(fault, work, programs, scripts)
        return scrub(text, work), code

    write_set(args.out, header, script, versions(), faults, run_one, silent, notes)
    return 0


def versions() -> str:
    """The stack's versions as an excerpt's source names them."""
    return f"rclpy {version('ros-kilted-rclpy')}, cyclonedds {version('cyclonedds')}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()

    def run_one(fault: Fault, work: Path) -> tuple[str, int]:
        text, code = run(fault, work)
        return scrub(text, work), code

    write_set(args.out, HEADER, "stack_faults.py", versions(), FAULTS, run_one)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
