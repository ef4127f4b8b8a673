"""Mine the C library's strerror texts that a driver's error line can carry (facts only, never glibc's code).

    .venv/bin/python scripts/mine_strerror.py --glibc DIR [--check]

DIR is a bare mirror of github:bminor/glibc (its `repo` folder). The texts live in `sysdeps/gnu/errlist.h` as
`_S(EACCES, N_("Permission denied"))`; the script reads that file at the mirror's HEAD, keeps the errnos of the
table below, and writes explainers/stack/strerror.json: for each, its text, `file:line@commit`, the cause id of
hexar/causes.yaml it states (or none: only candidates) and what it means in plain words. `--check` fails when the
written file would differ.

Why each errno maps where it does (the `stated` causes of explainers/stated_causes.py):
- EACCES: the operating system refused the driver its device or file: system.device_permission.
- EADDRINUSE, EBUSY: another program already holds the port or the device (a second driver, a console, a modem
  manager): a set-up conflict, the controller's or its driver's set-up.
- EIO: a read or write on the device failed: the hardware interface could not talk to its device.
- ECONNREFUSED, EHOSTUNREACH, ENETUNREACH, ETIMEDOUT, EHOSTDOWN, ENETDOWN: the driver could not reach its device,
  but whether the device is off (or not running its server), its address was configured wrongly, or a filter on
  the way turned the connection away (a firewall REJECT answers "Connection refused", a DROP lets it time out) the
  text does not say: no cause is claimed, the answer names the candidates.
- ENOENT, ENODEV, ENXIO: the device or file is not there; whether it is unplugged or a wrong path was configured the
  text does not say, so no cause is claimed: the answer names both.
- Each errno also carries its number, for drivers that print the number alone ("open device error | device:
  /dev/ttyACM0, errno: 13"): the Linux numbers of x86_64 and arm64 (include/uapi/asm-generic/errno-base.h and
  errno.h), as this Linux machine's C library reports them through Python's errno module.
- EPERM is left out on purpose: healthy robots print it (ros2_control_node's "Could not enable FIFO RT scheduling
  policy: with error number <1>(Operation not permitted)", controller_manager/src/ros2_control_node.cpp:127@master).
"""

from __future__ import annotations

import argparse
import errno
import json
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "explainers" / "stack" / "strerror.json"
ERRLIST = "sysdeps/gnu/errlist.h"
_ENTRY = re.compile(r'_S\((E[A-Z0-9]+), N_\("([^"]+)"\)\)')

DEVICE_GONE = ("the device or file it names is not there: the device is unplugged or not powered, or a wrong path "
               "or port was configured")
UNREACHED = "control.hardware_failure"
CONFLICT = "control.configuration_error"
# errno -> (cause id or None, what it means when a driver reports it, the fix)
TABLE: dict[str, tuple[str | None, str, str]] = {
    "EACCES": ("system.device_permission",
               "it was not allowed to open its device (permission denied)",
               "Give the user (or the container) access to the device: its group (dialout, video) or a udev rule."),
    "EADDRINUSE": (CONFLICT,
                   "another program already holds the network port it needs (address already in use), such as a "
                   "second driver started on the same port",
                   "Stop the other program on that port, or give each driver its own ports."),
    "EBUSY": (CONFLICT,
              "another program already holds its device (device or resource busy)",
              "Close the other program that holds the device (another driver, a serial console, a modem manager)."),
    "ECONNREFUSED": (None,
                     "nothing accepted the connection at the address and port it was given: the device is off or "
                     "not running the program it connects to, the address or port is wrong, or something between "
                     "us turns the connection away",
                     "Check that the device is on and runs the program the driver connects to, its address and "
                     "port in the driver's parameters, and what lies between (cables, switches, filters)."),
    "EHOSTUNREACH": (None, "there was no route to its device's address: the device is off or unplugged, the "
                           "address is wrong, or something between us stops the connection",
                     "Check the device's address, the cable and this computer's address on the device's subnet."),
    "ENETUNREACH": (None, "the device's network could not be reached from this computer: this computer's network "
                          "settings or the device's address",
                    "Check this computer's network settings and the device's address."),
    "ETIMEDOUT": (None, "its device stayed silent when it tried to connect: the device is off, the address is "
                        "wrong, or something between us drops the connection",
                  "Check that the device is on and reachable (ping its address) and its address in the parameters."),
    "EHOSTDOWN": (None, "its device's host was down: off or unplugged, or its address is wrong",
                  "Check that the device is powered and connected, and its address."),
    "ENETDOWN": (None, "this computer's network interface to the device was down",
                 "Bring up the network interface the device is connected to."),
    "EIO": (UNREACHED, "reading from or writing to its device failed (an input/output error)",
            "Check the device's cable and power; unplug and reconnect it."),
    "ENOENT": (None, DEVICE_GONE, "Check that the device is plugged in and the path or port in its parameters."),
    "ENODEV": (None, DEVICE_GONE, "Check that the device is plugged in and the path or port in its parameters."),
    "ENXIO": (None, DEVICE_GONE, "Check that the device is plugged in and the path or port in its parameters."),
}


def _git(mirror: Path, *args: str) -> str:
    try:
        return subprocess.run(["git", "-C", str(mirror), *args], check=True, capture_output=True,
                              text=True).stdout
    except (OSError, subprocess.CalledProcessError) as err:
        raise SystemExit(f"ERROR: cannot read the glibc mirror {mirror}: {err}") from err


def mine(mirror: Path) -> dict[str, Any]:
    commit = _git(mirror, "rev-parse", "HEAD").strip()
    text = _git(mirror, "show", f"HEAD:{ERRLIST}")
    found: dict[str, tuple[str, int]] = {}
    for n, line in enumerate(text.splitlines(), start=1):
        m = _ENTRY.search(line)
        if m and m[1] in TABLE and m[1] not in found:
            found[m[1]] = (m[2], n)
    missing = sorted(set(TABLE) - set(found))
    if missing:
        raise SystemExit(f"ERROR: {ERRLIST} has no text for {', '.join(missing)}")
    errnos = []
    for name, (cause, meaning, fix) in TABLE.items():
        words, line_no = found[name]
        errnos.append({"errno": name, "text": words, "pattern": rf"\b{re.escape(words)}\b", "cause": cause,
                       "meaning": meaning, "fix": fix, "source": f"glibc/{ERRLIST}:{line_no}@{commit[:12]}",
                       "number": getattr(errno, name)})
    return {"about": "strerror texts of the GNU C library (github:bminor/glibc) a driver's error line can carry, "
                     "mined by scripts/mine_strerror.py; cause null: the text alone names no single cause; number: its "
                     "Linux errno (x86_64, arm64)",
            "commit": commit, "errnos": errnos}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--glibc", type=Path, required=True, help="bare mirror of bminor/glibc")
    parser.add_argument("--check", action="store_true", help="fail when the written file would differ")
    args = parser.parse_args(argv)
    text = json.dumps(mine(args.glibc), indent=1, ensure_ascii=False) + "\n"
    if args.check:
        if not OUT.exists() or OUT.read_text(encoding="utf-8") != text:
            print(f"ERROR: {OUT.relative_to(ROOT)} differs from what the mirror gives", file=sys.stderr)
            return 1
        return 0
    OUT.write_text(text, encoding="utf-8")
    print(f"wrote {OUT.relative_to(ROOT)} ({len(TABLE)} errnos)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
