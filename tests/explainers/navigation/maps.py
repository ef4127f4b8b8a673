"""A real Nav2 map as a robot records it: nav2_bringup's tb3_sandbox map (data/, from ros-navigation/navigation2 at
a3a97043, Apache-2.0) loaded as nav2_map_server's map_io does (trinary mode, rows flipped so that row 0 lies at the
origin), and a global costmap built from it as nav2_costmap_2d publishes one (100 lethal, 99 within the inscribed
radius, 1-98 decaying cost inside the inflation radius, 0 free, -1 unknown), with nav2_params.yaml's robot_radius
0.22 m and inflation_radius 0.70 m."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import yaml
from scipy import ndimage

from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder
from hexar.events import contract as c

DATA = Path(__file__).parent / "data"
ROBOT_RADIUS = 0.22
INFLATION_RADIUS = 0.70
COST_SCALING = 3.0  # nav2_params.yaml's cost_scaling_factor

Cells = npt.NDArray[np.int8]


def sandbox() -> tuple[Cells, float, tuple[float, float]]:
    """The map's cells (row 0 at the origin), its resolution and its origin."""
    meta = yaml.safe_load((DATA / "tb3_sandbox.yaml").read_text(encoding="utf-8"))
    raw = (DATA / meta["image"]).read_bytes()
    fields = raw.split(maxsplit=4)  # P5, a comment line is skipped below
    lines = raw.split(b"\n")
    header = [ln for ln in lines[:4] if not ln.startswith(b"#")]
    width, height = (int(v) for v in header[1].split())
    pixels = np.frombuffer(raw[len(raw) - width * height:], dtype=np.uint8).reshape(height, width)
    assert fields[0] == b"P5"
    occ = 1.0 - pixels / 255.0 if not meta["negate"] else pixels / 255.0
    cells = np.full((height, width), -1, dtype=np.int8)
    cells[occ >= meta["occupied_thresh"]] = 100
    cells[occ <= meta["free_thresh"]] = 0
    return cells[::-1].copy(), float(meta["resolution"]), (float(meta["origin"][0]), float(meta["origin"][1]))


def costmap(static: Cells, resolution: float) -> Cells:
    """The static map inflated as nav2_costmap_2d's inflation layer does, in the published (0-100) values."""
    lethal = static == 100
    dist = ndimage.distance_transform_edt(~lethal) * resolution
    cost = np.zeros(static.shape, dtype=np.float64)
    inside = (dist > ROBOT_RADIUS) & (dist <= INFLATION_RADIUS)
    # inflation_layer.hpp: (INSCRIBED_INFLATED_OBSTACLE - 1) * exp(-factor * (distance - inscribed_radius))
    cost[inside] = 252 * np.exp(-COST_SCALING * (dist[inside] - ROBOT_RADIUS))
    published = (1 + (97 * (np.clip(cost, 1, 252).astype(int) - 1)) // 251).astype(np.int8)
    out = np.where(cost > 0, published, 0).astype(np.int8)
    out[dist <= ROBOT_RADIUS] = 99
    out[lethal] = 100
    # inflation_layer.cpp: an unknown cell takes an inflated cost only from the inscribed radius in
    out[(static == -1) & (dist > ROBOT_RADIUS)] = -1
    return out


def cell_of(x: float, y: float, resolution: float, origin: tuple[float, float]) -> tuple[int, int]:
    """(row, column) of the point."""
    return int((y - origin[1]) // resolution), int((x - origin[0]) // resolution)


def grid_msg(t: int, cells: Cells, resolution: float, origin: tuple[float, float], frame: str = "map") -> Any:
    T = TYPESTORE.types
    height, width = cells.shape
    sec, nsec = divmod(t, 1_000_000_000)
    stamp = T["builtin_interfaces/msg/Time"](sec=sec, nanosec=nsec)
    pose = T["geometry_msgs/msg/Pose"](
        position=T["geometry_msgs/msg/Point"](x=origin[0], y=origin[1], z=0.0),
        orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))
    info = T["nav_msgs/msg/MapMetaData"](map_load_time=stamp, resolution=resolution, width=width, height=height,
                                         origin=pose)
    return T["nav_msgs/msg/OccupancyGrid"](header=T["std_msgs/msg/Header"](stamp=stamp, frame_id=frame), info=info,
                                           data=cells.reshape(-1).astype(np.int8))


def record_grids(b: BagBuilder, t: int, static: Cells | None, cost: Cells | None, resolution: float,
                 origin: tuple[float, float]) -> None:
    if static is not None:
        b.raw(t, c.MAP, c.GRID_TYPE, grid_msg(t, static, resolution, origin))
    if cost is not None:
        b.raw(t, c.GLOBAL_COSTMAP, c.GRID_TYPE, grid_msg(t, cost, resolution, origin))
