"""Hand decoders for the two hot message types of a recording.

`/rosout` dominates a recording (hundreds of thousands of lines an hour); rosbags' generic deserialiser builds
a full message object per line, which caps decoding well below 100k lines/s. These decoders read only the
fields HEXAR uses from little-endian CDR and return None on anything unexpected, so the caller falls back to
rosbags.

A message whose bytes do not end where the standard layout ends was written with another definition (a newer
or custom message type); decoding it as the standard one would misread it, so the decoders raise LayoutError
and the reader decides what to do (decode with the recording's own definition, or report the topic).
"""

from __future__ import annotations

from struct import Struct
from struct import error as StructError

_U32 = Struct("<I")
# CDR pads a message to its alignment; more left-over bytes than this means fields the standard layout lacks
_MAX_PAD = 7


class LayoutError(ValueError):
    """The message's bytes do not fit the standard definition of its type."""


_LOG_HEAD = Struct("<iIB")  # stamp.sec, stamp.nanosec, level


def decode_log(raw: bytes) -> tuple[int, int, str, str] | None:
    """(stamp in ns, level, name, msg) of an rcl_interfaces/msg/Log, or None."""
    try:
        if raw[1] != 1:
            return None
        sec, nanosec, level = _LOG_HEAD.unpack_from(raw, 4)
        # name starts at offset 16: 13 bytes of payload so far, aligned to 4 from the payload start (4)
        (size,) = _U32.unpack_from(raw, 16)
        end = 20 + size
        name = raw[20 : end - 1].decode("utf-8", "replace")
        pos = 4 + ((end - 1) & ~3)
        (size,) = _U32.unpack_from(raw, pos)
        stop = pos + 4 + size
        if size == 0 or stop > len(raw):
            return None
        msg = raw[pos + 4 : stop - 1].decode("utf-8", "replace")
    except (IndexError, StructError):
        return None
    try:
        # file, function, line: the rest of the standard Log; anything else is another layout (inlined: this
        # runs for every line of an hour's log)
        p = 4 + ((stop - 1) & ~3)
        q = p + 4 + _U32.unpack_from(raw, p)[0]
        p = 4 + ((q - 1) & ~3)
        q = p + 4 + _U32.unpack_from(raw, p)[0]
        end = 4 + ((q - 1) & ~3) + 4
    except (IndexError, StructError):
        end = len(raw) + _MAX_PAD + 1  # the standard strings run past the message: another layout
    if not 0 <= len(raw) - end <= _MAX_PAD:
        raise LayoutError(f"rcl_interfaces/msg/Log of {len(raw)} bytes where the standard layout ends at {end}")
    return sec * 1_000_000_000 + nanosec, level, name, msg


def decode_string(raw: bytes) -> str | None:
    """The data of a std_msgs/msg/String in CDR, or None."""
    try:
        if raw[1] != 1:
            return None
        (size,) = _U32.unpack_from(raw, 4)
        if size == 0 or 8 + size > len(raw):
            return None
        text = raw[8 : 8 + size - 1].decode("utf-8", "replace")
    except (IndexError, StructError):
        return None
    if len(raw) - (8 + size) > _MAX_PAD:
        raise LayoutError(f"std_msgs/msg/String of {len(raw)} bytes where the standard layout ends at {8 + size}")
    return text


_POSE = Struct("<43d")  # position xyz, orientation xyzw, 36 covariance values


def decode_pose_cov(raw: bytes) -> tuple[int, tuple[float, ...]] | None:
    """(header stamp in ns, the 43 doubles of pose and covariance) of a PoseWithCovarianceStamped, or None."""
    try:
        if raw[1] != 1:
            return None
        sec, nanosec = _LOG_HEAD.unpack_from(raw, 4)[:2]
        (size,) = _U32.unpack_from(raw, 12)
        body = 12 + size  # payload offset of the first byte after frame_id
        start = 4 + ((body + 7) & ~7)
        if start + _POSE.size > len(raw):
            return None
        if len(raw) - (start + _POSE.size) > _MAX_PAD:
            raise LayoutError(f"PoseWithCovarianceStamped of {len(raw)} bytes where the standard layout ends at "
                              f"{start + _POSE.size}")
        return sec * 1_000_000_000 + nanosec, _POSE.unpack_from(raw, start)
    except (IndexError, StructError):
        return None


_TWIST = Struct("<6d")  # linear xyz, angular xyz
_F64 = Struct("<d")


def _after_header(raw: bytes) -> tuple[int, int]:
    """(header stamp in ns, payload offset just after the header's frame_id) of a stamped message."""
    sec, nanosec = _LOG_HEAD.unpack_from(raw, 4)[:2]
    (size,) = _U32.unpack_from(raw, 12)
    return sec * 1_000_000_000 + nanosec, 12 + size


def decode_twist(raw: bytes, stamped: bool) -> tuple[int, tuple[float, ...]] | None:
    """(header stamp in ns or 0, the 6 doubles) of a Twist or TwistStamped, or None."""
    try:
        if raw[1] != 1:
            return None
        stamp, body = _after_header(raw) if stamped else (0, 0)
        start = 4 + ((body + 7) & ~7)
        if start + _TWIST.size > len(raw):
            return None
        return stamp, _TWIST.unpack_from(raw, start)
    except (IndexError, StructError):
        return None


_XY = Struct("<2d")
_TWIST_OFFSET = _POSE.size  # the twist follows the pose and its 36 covariance values
_WZ_OFFSET = _TWIST_OFFSET + 5 * 8


def decode_odom(raw: bytes) -> tuple[int, float, float, float, float] | None:
    """(header stamp in ns, x, y, linear.x, angular.z) of a nav_msgs/msg/Odometry, or None."""
    try:
        if raw[1] != 1:
            return None
        sec, nanosec = _LOG_HEAD.unpack_from(raw, 4)[:2]
        (size,) = _U32.unpack_from(raw, 12)
        child = (12 + size + 3) & ~3  # child_frame_id: uint32 length, then the bytes
        (size,) = _U32.unpack_from(raw, 4 + child)
        pose = 4 + ((child + 4 + size + 7) & ~7)
        if pose + _WZ_OFFSET + 8 > len(raw):
            return None
        x, y = _XY.unpack_from(raw, pose)
        (vx,) = _F64.unpack_from(raw, pose + _TWIST_OFFSET)
        (wz,) = _F64.unpack_from(raw, pose + _WZ_OFFSET)
        return sec * 1_000_000_000 + nanosec, x, y, vx, wz
    except (IndexError, StructError):
        return None


_LEVEL = Struct("<b")  # DiagnosticStatus.level: a byte, no alignment, signed as rosbags reads it


def _string(raw: bytes, pos: int) -> tuple[str, int]:
    """A CDR string at payload offset `pos` (aligned here to 4), decoded strictly as rosbags decodes it (a text
    that is not UTF-8 raises, and the caller leaves it to rosbags); and the payload offset after it."""
    pos = (pos + 3) & ~3
    (size,) = _U32.unpack_from(raw, 4 + pos)
    end = pos + 4 + size
    if size == 0 or 4 + end > len(raw):
        raise IndexError(pos)
    return raw[4 + pos + 4 : 4 + end - 1].decode("utf-8"), end


def _count(raw: bytes, pos: int) -> tuple[int, int]:
    """A sequence length at payload offset `pos`, and the payload offset after it."""
    pos = (pos + 3) & ~3
    (n,) = _U32.unpack_from(raw, 4 + pos)
    if n > len(raw):  # each element takes at least a byte: a count this large is not this layout
        raise IndexError(pos)
    return n, pos + 4


Status = tuple[int, str, str, str, tuple[tuple[str, str], ...]]  # level, name, message, hardware_id, values


# The statuses of the DiagnosticArrays decoded so far, by the bytes after their stamp: an aggregator publishes the
# same statuses again and again, only the stamp moves (2,883 arrays of 50 simulated recordings held 136 texts).
# Arrays up to SEEN_BYTES, at most SEEN_KEPT of them: a few MB at most in a process that runs for days.
_SEEN: dict[bytes, tuple[Status, ...]] = {}
SEEN_KEPT = 2048
SEEN_BYTES = 4096


def decode_diagnostics(raw: bytes) -> tuple[int, int, tuple[Status, ...]] | None:
    """(header stamp sec, nanosec, statuses) of a diagnostic_msgs/msg/DiagnosticArray, or None (then rosbags
    decodes it). /diagnostics and HEXAR's status topics are the most frequent messages after /rosout."""
    if len(raw) >= 12 and raw[1] == 1 and (seen := _SEEN.get(raw[12:])) is not None:
        sec, nanosec = _LOG_HEAD.unpack_from(raw, 4)[:2]
        return sec, nanosec, seen
    decoded = _decode_diagnostics(raw)
    if decoded is not None and len(raw) <= SEEN_BYTES:
        if len(_SEEN) >= SEEN_KEPT:
            _SEEN.clear()
        _SEEN[raw[12:]] = decoded[2]
    return decoded


def _decode_diagnostics(raw: bytes) -> tuple[int, int, tuple[Status, ...]] | None:
    try:
        if raw[1] != 1:
            return None
        sec, nanosec = _LOG_HEAD.unpack_from(raw, 4)[:2]
        _, pos = _string(raw, 8)  # frame_id
        n, pos = _count(raw, pos)
        statuses: list[Status] = []
        for _ in range(n):
            (level,) = _LEVEL.unpack_from(raw, 4 + pos)
            name, pos = _string(raw, pos + 1)
            message, pos = _string(raw, pos)
            hardware_id, pos = _string(raw, pos)
            m, pos = _count(raw, pos)
            values = []
            for _ in range(m):
                key, pos = _string(raw, pos)
                value, pos = _string(raw, pos)
                values.append((key, value))
            statuses.append((level, name, message, hardware_id, tuple(values)))
    except (IndexError, StructError, UnicodeDecodeError):
        return None
    if not 0 <= len(raw) - (4 + pos) <= _MAX_PAD:
        raise LayoutError(f"DiagnosticArray of {len(raw)} bytes where the standard layout ends at {4 + pos}")
    return sec, nanosec, tuple(statuses)


def decode_bool(raw: bytes) -> bool | None:
    """The data of a std_msgs/msg/Bool in CDR (any non-zero byte is true, as rosbags reads it), or None."""
    if len(raw) < 5 or raw[1] != 1:
        return None
    if len(raw) - 5 > _MAX_PAD:
        raise LayoutError(f"std_msgs/msg/Bool of {len(raw)} bytes where the standard layout ends at 5")
    return raw[4] != 0
