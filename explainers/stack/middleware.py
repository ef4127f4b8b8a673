"""The middleware under every node (rcl's rmw check, rmw_fastrtps, rmw_cyclonedds, Fast DDS, Cyclone DDS): a line that
kept a node from joining the others, or a middleware setting that never applied (stable API).

    middleware_line(lines, before=None) -> tuple[LogLine, str] | None
    middleware_words(line) -> tuple[str, str]

Read through the mined stack catalogue (explainers/stack/sources.yaml: its entries of cause `stack.network` and
`stack.middleware_configuration`). Fast DDS prints its own errors to stderr as "[CATEGORY Error] text -> Function f",
and Cyclone DDS as "{time} [{domain}] {thread}: text" (events/console.py reads both), so such a line names no node.
What each line means is said from the line's own words and the source that prints it, never from a guess about the
network: a DDS that could not start names no firewall.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from hexar.events.records import WARN, LogLine, clock
from hexar.explainers.stack.catalogue import stack_catalogue

NETWORK = "stack.network"
CONFIGURATION = "stack.middleware_configuration"
CAUSES = {NETWORK: "system.network", CONFIGURATION: "bringup.configuration_error"}

_QUOTED = re.compile(r"'([^']*)'")
# Cyclone DDS's configuration errors (ddsi_config.c cfg_error: "config: <element path>: <what> (<source> line N)"),
# whose message is formatted from pieces too short to mine ("%s: unknown %s")
_NO_FILE = "can't open configuration file"  # ddsi_config.c:2252@releases/0.10.x
_CYCLONE_CONFIG_AT = "config: //CycloneDDS"  # the path every such error names: a cheap look before the match
_CYCLONE_CONFIG = re.compile(r"^config: (?P<path>//CycloneDDS\S*?): (?P<what>.+?)(?: \((?P<where>[^()]*)\))?$")
_PORTS = re.compile(r"failed to create unicast sockets for domain \S+ participant index \S+ \(ports (?P<ports>[^)]*)\)")
_BUFFER = re.compile(r"failed to increase socket (?P<which>\w+) buffer size to at least (?P<want>\d+) bytes, "
                     r"current is (?P<got>\d+) bytes")
_OVERSIZE = re.compile(r"dropping oversize \((?P<size>\d+) > (?P<limit>\d+)\) sample from local writer")
# Fast DDS's console decoration: "[RTPS Error] text -> Function getMulticastPort"
_FASTDDS = re.compile(r"^\[(?P<category>[A-Z][A-Z0-9_]*) (?:Error|Warning|Info)\] (?P<text>.*?)(?: -> Function \w+)?$",
                      re.S)


# Fast-DDS 3.6.x: TopicPayloadPool::get_payload logs it when PayloadNode::resize's realloc fails for a message
# larger than the buffers it holds (TopicPayloadPool.cpp:74, TopicPayloadPool.hpp:175); the message is not taken
PAYLOAD = "Failed to resize the payload"
# SharedMemTransport::init logs the exception that kept its segment from being made (RTPS_MSG_OUT, with the
# system's words), SharedMemSegment/SharedMemManager "Failed to create segment <name>: <what>" (RTPS_TRANSPORT_SHM),
# and RTPSParticipantImpl.cpp:549 "Unable to Register SHM Transport ..." before it goes on with its other transports
_SHM = ("Unable to Register SHM Transport", "Failed to create segment")


def fastdds_meaning(line: LogLine) -> str:
    """What one of Fast DDS's lines about a message or its shared-memory transport means, from its source; ""
    for any other line."""
    category, words = _decorated(line)
    if words.startswith(PAYLOAD):
        return ("my DDS middleware (Fast DDS) ran out of memory for a message larger than the buffers it "
                "held (its realloc failed), so that message was not taken: the node it was for never got it")
    if words.startswith(_SHM) or (category == "RTPS_MSG_OUT" and line.msg.rstrip().endswith("Function init")):
        # the system's words for why, after the segment's name ("…: Read-only file system"), or the whole line
        why = words.split(": ", 1)[1] if words.startswith("Failed to create segment") and ": " in words else \
            words if category == "RTPS_MSG_OUT" else ""
        made = f"its segment under /dev/shm could not be made: \"{why}\"" if why else \
            "its segment under /dev/shm could not be made"
        return (f"my DDS middleware (Fast DDS) could not set up its shared-memory transport ({made}), and went on "
                "with its other transports (UDP by default): nodes still reach each other, over the network stack "
                "instead of shared memory")
    return ""


def middleware_line(lines: Sequence[LogLine], before: int | None = None) -> tuple[LogLine, str] | None:
    """The first line (WARN or above: Cyclone's stderr lines carry no level) whose catalogue entry is the
    middleware's, with the project cause it supports; None when there is none."""
    cat = stack_catalogue()
    for line in lines:
        if line.level < WARN or (before is not None and line.t > before):
            continue
        if _CYCLONE_CONFIG_AT in line.msg and _CYCLONE_CONFIG.match(text(line)):
            return line, CAUSES[CONFIGURATION]
        entry = cat.match(line.msg)
        if entry is not None and entry.cause in CAUSES:
            return line, CAUSES[entry.cause]
    return None


def text(line: LogLine) -> str:
    """The middleware's own words, without Fast DDS's category and function decoration, first line only."""
    return _decorated(line)[1]


def _decorated(line: LogLine) -> tuple[str, str]:
    """(Fast DDS's category, or "" for a line without its decoration; the words, first line only)."""
    first = line.msg.strip().splitlines()[0] if line.msg.strip() else ""
    m = _FASTDDS.match(first)
    return (m["category"], m["text"].strip()) if m else ("", first.strip())


def _quoted(words: str, n: int = 0) -> str:
    found = _QUOTED.findall(words)
    return found[n] if len(found) > n else ""


def middleware_words(line: LogLine) -> tuple[str, str]:
    """(what happened, the fix), for a person, from a line `middleware_line` found."""
    words = text(line)
    if "Calculated port number is too high" in words:
        # NetworkFactory.cpp (Fast DDS): the RTPS ports are computed from the domain id; past 232 none fits
        return ("my DDS middleware (Fast DDS) could not open its network ports: the ports it computes from "
                "ROS_DOMAIN_ID do not exist for that domain (it says the domain id is probably over 232), so my "
                "node could not join the others",
                "Set ROS_DOMAIN_ID to a number from 0 to 101 (the range every platform supports) on every computer "
                "of the robot, the same everywhere.")
    if "does not match an available interface" in words:
        iface = words.split(":", 1)[0].strip()
        return (f"my DDS middleware (Cyclone DDS) could not start: its configuration names a network interface "
                f"this machine does not have ({iface}), so my node could not join the others",
                "Name an interface that `ip link` lists in CYCLONEDDS_URI (NetworkInterface), or leave the choice to "
                "Cyclone DDS by removing it.")
    if "Unable to resolve peer" in words:
        after = words.split("Unable to resolve peer", 1)[1].split()
        peer = after[0] if after else ""
        return (f"my DDS middleware could not resolve a static peer ROS_STATIC_PEERS names ({peer}), so my node "
                "could not be created",
                "Give ROS_STATIC_PEERS addresses or host names this machine resolves (check with `getent hosts`), "
                "or add the name to /etc/hosts.")
    if "passed into the server's list" in words:
        # ServerAttributes.cpp (Fast DDS): each entry of ROS_DISCOVERY_SERVER is an IPv4/IPv6 address or a host name
        # it resolves, with an optional port; one it cannot read drops the whole list
        what, _, value = words.partition(" passed into the server's list")
        kind = {"Wrong domain name": "a host name that does not resolve", "Wrong ipv4 address": "an IPv4 address "
                "that is not valid", "Wrong ipv6 address": "an IPv6 address that is not valid"}.get(
                    what.strip(), what.strip().removeprefix("Wrong ").lower() + " that is not valid")
        return (f"my DDS middleware (Fast DDS) could not use the discovery server ROS_DISCOVERY_SERVER names: it "
                f"holds {kind} ({value.strip()}), so my node ran without the server and never sees the nodes that "
                "find each other through it",
                "Set ROS_DISCOVERY_SERVER to the server's address as ADDRESS:PORT (a host name must resolve on "
                "this computer: check with `getent hosts`; the default port is 11811), the same on every computer "
                "that should use it.")
    if "assuming localhost only" in words:
        value, var = _quoted(words), _quoted(words, 1) or "ROS_AUTOMATIC_DISCOVERY_RANGE"
        return (f"DDS discovery stayed on this computer: {var} had a value rcl does not know ('{value}'), so nodes on "
                "the robot's other computers are never seen",
                f"Set {var} to one rcl knows (ROS_AUTOMATIC_DISCOVERY_RANGE: SUBNET, LOCALHOST, OFF or "
                "SYSTEM_DEFAULT) on every computer.")
    if "failed to create domain" in words:
        return ("my DDS middleware could not start: Cyclone DDS failed to create its domain, so my node could not be "
                "created",
                "Check the Cyclone DDS configuration (CYCLONEDDS_URI): the network interfaces it selects must exist "
                "on this machine, each named once; unset it to try the defaults.")
    if "free participant index" in words:
        return ("my DDS middleware (Cyclone DDS) found no free participant index for this domain on this computer, "
                "so my node could not join the others",
                "Run fewer ROS processes per computer, or raise Cyclone DDS's ParticipantIndex/MaxAutoParticipantIndex "
                "in CYCLONEDDS_URI.")
    if words.startswith("failed to find interfaces for"):
        # ddsi_nwinterfaces.c:325@releases/11.0.x: no interface is up for the transport (the network is not up yet)
        return (f"my DDS middleware (Cyclone DDS) found no network interface up for its transport "
                f"({words.rsplit(' ', 1)[-1]}), so it could not start and my node could not join the others",
                "Start the nodes once the network is up (in systemd: After=network-online.target), or name an "
                "interface that is always there in CYCLONEDDS_URI (lo for one computer).")
    if (m := _PORTS.search(words)) is not None:
        # ddsi_init.c:1421-1425@releases/11.0.x: the participant's unicast ports could not be bound
        return (f"my DDS middleware (Cyclone DDS) could not open its unicast ports ({m['ports']}), so it could not "
                "start and my node could not join the others: another program holds them, or another participant "
                "was given the same participant index",
                "Find what holds the ports (ss -ulpn), and leave Cyclone DDS's ParticipantIndex on auto or give "
                "each process its own.")
    if (m := _BUFFER.search(words)) is not None:
        # ddsi_udp.c:505@releases/11.0.x: the configuration's minimum, which the kernel caps lower
        return (f"my DDS middleware (Cyclone DDS) could not start: its configuration requires a socket "
                f"{m['which']} buffer of at least {m['want']} bytes and the operating system gives {m['got']}, so my "
                "node could not join the others",
                "Raise the kernel's limit (sysctl net.core.rmem_max, or wmem_max for the send buffer) to at least "
                "that size, or lower the minimum in CYCLONEDDS_URI (SocketReceiveBufferSize min).")
    if words.startswith("ddsi_udp_conn_write to"):
        # ddsi_udp.c:330@releases/11.0.x: a send on a socket whose interface or route is gone
        to = (words.split()[2:3] or ["a peer"])[0]
        return (f"my DDS middleware (Cyclone DDS) could not send to {to}: the network link or interface it sends on "
                "went away while it ran, so the other computer stopped hearing my node",
                "Check the link (cable, Wi-Fi, ip link) of the computer that logged it; DDS resumes once it is up.")
    if (m := _OVERSIZE.search(words)) is not None:
        # ddsi_transmit.c:825@releases/11.0.x: a sample over the configured maximum is dropped by its own writer
        return (f"my DDS middleware (Cyclone DDS) could not send a message: at {m['size']} bytes it was larger than "
                f"the most it is set to carry ({m['limit']} bytes), so it dropped it and the others never got it",
                "Raise Cyclone DDS's MaxMessageSize / MaxSampleSize in CYCLONEDDS_URI, or send smaller messages "
                "(fewer points per message).")
    if "Expected RMW implementation identifier" in words:
        wanted, found = _quoted(words), _quoted(words, 1)
        return (f"the middleware's settings never reached my node: RMW_IMPLEMENTATION names {wanted}, but the program "
                f"was built with {found}, so rcl stopped it before any node existed",
                f"Install {wanted} for this program's ROS distribution, or set RMW_IMPLEMENTATION to {found} (or "
                "unset it); every node of the robot should use the same middleware.")
    if "failed to load shared library" in words:
        return (f"the middleware's settings never reached my node: the middleware library RMW_IMPLEMENTATION names "
                f"could not be loaded ({_quoted(words) or words[:120]})",
                "Install that rmw package for this ROS distribution, or unset RMW_IMPLEMENTATION.")
    if "environment variable" in words:
        value, var = _quoted(words), _quoted(words, 1)
        return (f"the middleware's settings never reached my node: Fast DDS did not understand {var or 'a variable'}"
                f"{f' ({value})' if value else ''} and kept its defaults",
                f"Set {var or 'the variable'} to a value Fast DDS documents (for FASTDDS_BUILTIN_TRANSPORTS: DEFAULT, "
                "UDPv4, UDPv6, SHM, LARGE_DATA, DEFAULTv6, ...), or unset it.")
    if (m := _CYCLONE_CONFIG.match(words)) is not None:
        return (f"the middleware's settings never reached my node: Cyclone DDS did not take its configuration "
                f"({m['path']}: {m['what']}), so it did not start",
                "Fix that element of the Cyclone DDS configuration (CYCLONEDDS_URI or the file it names: element "
                "names are case-sensitive, see Cyclone DDS's configuration reference), or unset it to try the "
                "defaults.")
    if words.startswith(_NO_FILE):
        return (f"the middleware's settings never reached my node: Cyclone DDS could not open the configuration "
                f"file CYCLONEDDS_URI names ({words.removeprefix(_NO_FILE).strip()}), so it did not start",
                "Point CYCLONEDDS_URI at the file that exists (file:// and an absolute path), or put the XML "
                "itself in the variable.")
    if words.startswith("realpath failed"):
        return ("the middleware's settings never reached my node: Fast DDS found no XML profiles file where "
                f"FASTDDS_DEFAULT_PROFILES_FILE points ({words}), so it ran on its default settings",
                "Point FASTDDS_DEFAULT_PROFILES_FILE at the XML file (an absolute path that exists on this "
                "computer), or unset it.")
    if words.startswith(("Error opening '", "Error parsing '")):
        return (f"the middleware's settings never reached my node: Fast DDS could not load its XML profiles file "
                f"({_quoted(words)}), so it ran on its default settings instead of that file's",
                "Fix the XML file (a closing tag missing, a misspelt element) and check its path in "
                "FASTDDS_DEFAULT_PROFILES_FILE; Fast DDS prints each parse error before this line.")
    return (f"my DDS middleware reported a problem that kept my node from working with the others: '{words[:160]}'",
            "Read the middleware's lines around it (Fast DDS and Cyclone DDS print their errors on stderr).")


def dropped_messages(lines: list[LogLine], until: int) -> list[LogLine]:
    """Fast DDS's lines, up to `until`, that say a message was not taken for want of memory (PAYLOAD)."""
    return [ln for ln in lines if ln.t <= until and text(ln).startswith(PAYLOAD)]


def dropped_said(dropped: list[LogLine], lines: list[LogLine]) -> str:
    """'my DDS middleware … ("Failed to resize the payload", 20 times from 13:33:03.387, right after map_server's
    "publishing map 8000x8000 …")': what the first of `dropped` means, and the named line just before it."""
    first = dropped[0]
    before = next((ln for ln in reversed(lines) if ln.t <= first.t and ln is not first and ln.name
                   and not _FASTDDS.match(ln.msg.strip()) and first.t - ln.t <= 1_000_000_000), None)
    after = (f", right after {before.name}'s \"{' '.join(before.msg.split())[:80]}\"" if before is not None else "")
    times = f"{len(dropped)} times from" if len(dropped) > 1 else "at"
    return f"{fastdds_meaning(first)} (\"{PAYLOAD}\", {times} {clock(first.t)}{after})"
