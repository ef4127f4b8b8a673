"""Shared by the live benchmark scripts: a `hexar serve` process, its memory, and a listener on its answers."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.live.dds_helpers import Listener  # noqa: E402  -- the same listener the tests use


def start_serve(domain: int, *extra: str, transport: str = "dds",
                python: str = sys.executable) -> subprocess.Popen[str]:
    # run outside the checkout, whose hexar/ folder would shadow the package of another install's python
    proc = subprocess.Popen([python, "-m", "hexar", "serve", "--transport", transport, "--domain", str(domain),
                             "--quiet", *extra], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True, cwd=tempfile.gettempdir())
    assert proc.stderr is not None
    line = proc.stderr.readline()
    if "listening" not in line:
        raise SystemExit(f"hexar serve did not start: {line}{proc.stderr.read()}")
    return proc


def lossy(cyclone_uri: str, permille: int) -> str:
    """`cyclone_uri` plus Cyclone DDS's own fault injection: each participant of a process started with it drops
    `permille` of every 1,000 packets it sends (data, heartbeats, acknowledgements and discovery alike), as a lossy
    Wi-Fi link would. Set before a process creates its first participant; child processes inherit it."""
    drop = f"<Internal><Test><XmitLossiness>{permille}</XmitLossiness></Test></Internal>"
    return f"{cyclone_uri},{drop}" if cyclone_uri.strip() else drop


NETNS_MARK = "HEXAR_BENCH_NETNS_LOSS"
# one loopback link of its own: multicast on (DDS discovery) and a route for it, then nftables drops `permille` of
# every 1,000 UDP datagrams any process sends on it, as the kernel would drop them on a bad link
_NETNS_SETUP = """set -e
ip link set lo up
ip link set lo multicast on
ip route add 224.0.0.0/4 dev lo
nft -f - <<RULES
table inet hexar_loss {
  chain out {
    type filter hook output priority 0;
    meta l4proto udp numgen random mod 1000 < $HEXAR_BENCH_NETNS_LOSS counter drop
  }
}
RULES
exec "$@"
"""


def in_lossy_netns(permille: int) -> None:
    """Run this script again in a network namespace of its own whose loopback link loses `permille` of every 1,000
    UDP datagrams (nftables, in the kernel), for every process and both DDS vendors alike; returns once inside.
    Fast DDS is kept to UDP, as between two computers: its shared-memory transport would pass the link by. Needs
    root (or CAP_NET_ADMIN in a user namespace), `unshare`, `ip` and `nft`."""
    if os.environ.get(NETNS_MARK) == str(permille):
        return
    missing = [tool for tool in ("unshare", "ip", "nft") if shutil.which(tool) is None]
    if missing:
        raise SystemExit(f"ERROR: --netloss needs {', '.join(missing)} (Debian: util-linux, iproute2, nftables)")
    env = {**os.environ, NETNS_MARK: str(permille), "FASTDDS_BUILTIN_TRANSPORTS": "UDPv4"}
    try:
        os.execvpe("unshare", ["unshare", "-n", "sh", "-c", _NETNS_SETUP, "sh", sys.executable, *sys.argv], env)
    except OSError as err:
        raise SystemExit(f"ERROR: cannot make a network namespace: {err}") from err


def netns_dropped() -> str:
    """The datagrams the namespace's link dropped so far, as nftables counted them ("" outside one)."""
    if NETNS_MARK not in os.environ:
        return ""
    out = subprocess.run(["nft", "list", "table", "inet", "hexar_loss"], capture_output=True, text=True).stdout
    counter = next((line.split("counter", 1)[1].split("drop")[0].strip() for line in out.splitlines()
                    if "counter" in line), "")
    return counter


def rss_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return 0.0


class RssSampler:
    def __init__(self, pid: int, every_s: float = 0.5) -> None:
        self.pid, self.every_s = pid, every_s
        self.samples: list[tuple[float, float]] = []
        self._stop = threading.Event()
        self._t0 = time.monotonic()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        while not self._stop.is_set():
            try:
                self.samples.append((time.monotonic() - self._t0, rss_mb(self.pid)))
            except OSError:
                return
            self._stop.wait(self.every_s)

    def stop(self) -> list[tuple[float, float]]:
        self._stop.set()
        self._thread.join(2)
        return self.samples


def percentile(values: list[float], q: float) -> float:
    if not values:
        return float("nan")
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


__all__ = ["Listener", "RssSampler", "in_lossy_netns", "lossy", "netns_dropped", "percentile", "rss_mb",
           "start_serve"]
