"""What a TIAGo records while it runs, whatever it is doing: latched flags, battery, idle poses, diagnostics and
the noise lines the navigation explainer filters out.

Conventions of the background state (`simulate_robot_state`):
- `/joy_priority` (transient local, depth 1): one message at recording start with the current value. A toggle
  made before the recording shows as the joystick relay's INFO line, stamped when it happened and received at
  recording start (`/rosout` is transient local with a 10 s lifespan in Humble).
- `/power/is_charging`: 1 Hz, our choice for a battery-state publisher.
- `/amcl_pose`: AMCL's latched pose at recording start, then an idle sample every 4-6 s (a simplification:
  a still robot gets filter updates only from odometry drift). While navigating, AMCL publishes after each
  filter update, every `update_min_d` = 0.25 m of travel; a robot that cannot move gets a sample every ~2 s.
  `simulate_navigation` replaces idle samples inside its run and moves later ones to where the run ended.
- `/diagnostics` at 1 Hz carries the controller's configured speed limits: a DiagnosticStatus named
  `controller_server: velocity limits` (level 0, message `OK`) with the keys `max_vel_x` (m/s) and
  `max_vel_theta` (rad/s), formatted `%.2f`; TIAGo's DWB configuration sets both to 1.00.
- Noise the explainer's filter drops: costmap `Map update loop missed its desired rate` warnings, AMCL's
  `Message Filter dropping message` lines, and the costmap filters' info/mask re-subscription lines.
"""

from __future__ import annotations

import math
import random
from typing import Any

from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder, sec_ns
from hexar.evals.scenarios.nav_names import (
    AMCL,
    GCM,
    JOY_RELAY,
    LCM,
    MAX_VEL_THETA,
    MAX_VEL_X,
    SPEED_STATUS_NAME,
)
from hexar.events import contract as c
from hexar.events.records import INFO, WARN

_TRANSFORM_CACHE = "the timestamp on the message is earlier than all the data in the transform cache"


def _fmt2(x: float) -> str:
    return f"{x:.2f}"


def _pose_tuple(msg: Any) -> tuple[int, float, float, float, float, float, float]:
    stamp = int(msg.header.stamp.sec) * 1_000_000_000 + int(msg.header.stamp.nanosec)
    p, q, cov = msg.pose.pose.position, msg.pose.pose.orientation, msg.pose.covariance
    yaw = 2.0 * math.atan2(float(q.z), float(q.w))
    return stamp, float(p.x), float(p.y), yaw, float(cov[0]), float(cov[7]), float(cov[35])


def _pose_messages(b: BagBuilder) -> list[tuple[int, str, str, Any]]:
    return [m for m in b.messages if m[1] == c.AMCL_POSE]


def simulate_robot_state(
    b: BagBuilder,
    rng: random.Random,
    start: int,
    end: int,
    *,
    joystick: bool = False,
    charging: bool = False,
    pose: tuple[float, float, float] = (0.0, 0.0, 0.0),
) -> None:
    """What the robot records in the background across [start, end] (see the module docstring)."""
    if joystick:
        toggled = start - sec_ns(rng.uniform(2.0, 8.0))
        msg = TYPESTORE.types["rcl_interfaces/msg/Log"](
            stamp=TYPESTORE.types["builtin_interfaces/msg/Time"](sec=toggled // 1_000_000_000,
                                                               nanosec=toggled % 1_000_000_000),
            level=INFO, name=JOY_RELAY, msg="Toggled joy_priority, current status is: True",
            file="", function="", line=0,
        )
        b.raw(start, c.ROSOUT, c.LOG_TYPE, msg)
    b.flag(start, c.JOY_PRIORITY, joystick)

    t = start
    while t <= end:
        b.flag(t, c.IS_CHARGING, charging)
        b.status(t + sec_ns(0.3), c.DIAGNOSTICS, SPEED_STATUS_NAME, "OK",
                 [("max_vel_x", _fmt2(MAX_VEL_X)), ("max_vel_theta", _fmt2(MAX_VEL_THETA))])
        t += sec_ns(1.0)

    existing = sorted(_pose_tuple(m[3]) for m in _pose_messages(b))
    t = start
    while t <= end:
        # A navigation run publishes its own poses: an idle sample there would contradict it.
        if not any(abs(p[0] - t) < sec_ns(2.5) for p in existing):
            before = [p for p in existing if p[0] <= t]
            x, y, yaw = before[-1][1:4] if before else pose
            b.pose(t, x, y, yaw, rng.uniform(0.01, 0.04), rng.uniform(0.01, 0.04), rng.uniform(0.005, 0.02))
        t += sec_ns(rng.uniform(4.0, 6.0))

    _background_noise(b, rng, start, end)


def _background_noise(b: BagBuilder, rng: random.Random, start: int, end: int) -> None:
    # The zone server re-publishes the costmap filter info shortly after the recording starts.
    t = start + sec_ns(rng.uniform(0.5, 3.0))
    for logger, kinds in ((GCM, ("KeepoutFilter", "SpeedFilter")), (LCM, ("KeepoutFilter",))):
        for kind in kinds:
            base = kind.lower().replace("filter", "_filter")
            info, mask = f"/{base}_info", f"/{base}_mask"
            b.log(t, logger, WARN, f"{kind}: New costmap filter info arrived from {info} topic. "
                  "Updating old filter info.")
            if kind == "SpeedFilter":
                b.log(t + sec_ns(0.001), logger, INFO,
                      "SpeedFilter: Using absolute speed_limit = 0.000000 + filter_mask_data * 0.010000")
            b.log(t + sec_ns(0.002), logger, INFO,
                  f'{kind}: Subscribing to "{mask}" topic for filter mask...')
            b.log(t + sec_ns(rng.uniform(0.02, 0.08)), logger, WARN,
                  f"{kind}: New filter mask arrived from {mask} topic. Updating old filter mask.")
            t += sec_ns(rng.uniform(0.01, 0.05))
    t = start + sec_ns(rng.uniform(3.0, 15.0))
    while t <= end:
        took = rng.uniform(0.21, 0.45)
        b.log(t, LCM, WARN, "Costmap2DROS: Map update loop missed its desired rate of 5.0000Hz... "
              f"the loop actually took {took:.4f} seconds")
        t += sec_ns(rng.uniform(15.0, 40.0))
    t = start + sec_ns(rng.uniform(2.0, 10.0))
    while t <= end:
        scan = (t - sec_ns(rng.uniform(0.3, 0.9))) / 1e9
        b.log(t, AMCL, INFO, f"Message Filter dropping message: frame 'base_laser_link' at time {scan:.3f} "
              f"for reason '{_TRANSFORM_CACHE}'")
        t += sec_ns(rng.uniform(8.0, 30.0))
