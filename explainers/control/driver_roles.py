"""What a driver's error means by where it is logged: ros2_control_catalogue.json records, for each line of a hardware
interface the miner read (UR, Kinova, KUKA, Franka, Dynamixel, Robotiq, MuJoCo, the simulators' systems), the
hardware_interface callbacks it is logged in (on_init, on_configure, on_activate, read, write, the switch
callbacks) and the role they give it (scripts/modules_mining.yaml `hardware_roles`, scripts/driver_functions.py).

An ERROR or FATAL of such a line that no rule of the catalogue gives a cause, and that is the window's first
unexplained error, is read by that role: logged in read() or write() the driver could not exchange state or
commands with its device (a hardware failure), in on_init naming a parameter that is missing (it never reached the
driver) or a joint or interface that does not fit (a configuration error), in prepare_command_mode_switch it would
not take the controllers' interfaces. A role with no cause (on_init alone: set-up or device) names where it was
logged, and no cause.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

from hexar.events.records import ERROR
from hexar.explainers.control.catalogue import catalogue
from hexar.explainers.logcause import ModuleCatalogueError, Reading

CATALOGUE = "ros2_control_catalogue.json"
START = frozenset({"on_init", "configure", "on_configure", "on_activate", "start"})
EXCHANGE = frozenset({"read", "write", "perform_command_mode_switch"})
# lines that show the control loop running (a goal of a controller, a controller up): a driver's error after one is
# not from its start
RUNNING_KINDS = frozenset({"begin", "begin_server", "succeeded", "end_server", "nominal"})


@dataclass(frozen=True)
class Role:
    name: str  # exchange, setup, configuration, switch, start, device
    cause: str | None
    meaning: str  # with the callbacks filled in: "... (logged in its write())"
    functions: tuple[str, ...]

    @property
    def also_at_start(self) -> bool:
        """Logged both where the driver starts its device and where it exchanges with it (Kinova's "Kortex
        exception" in on_init and in write()): the line alone does not tell which, its time does."""
        return bool(set(self.functions) & START) and bool(set(self.functions) & EXCHANGE)


@dataclass(frozen=True)
class RoleReading(Reading):
    """A driver's error read by the role of the callback it is logged in (decisive only when no rule decides)."""

    role: Role | None = None

    @property
    def strong(self) -> bool:
        return True


@dataclass(frozen=True)
class _Mined:
    roles: dict[str, tuple[str | None, str]]  # role -> (cause, meaning with "{functions}")
    placed: dict[str, tuple[str, tuple[str, ...]]]  # entry id -> (role, callbacks)

    def role(self, name: str, functions: tuple[str, ...]) -> Role:
        cause, meaning = self.roles[name]
        return Role(name, cause, meaning.format(functions=f"logged in its {_listed(functions)}"), functions)


@cache
def _mined() -> _Mined:
    """The catalogue's roles and, for each entry the miner found in a hardware interface's callbacks, its role."""
    control = catalogue()
    try:
        roles = {str(k): (None if v.get("cause") is None else str(v["cause"]), str(v["meaning"]))
                 for k, v in control.hardware_roles.items()}
    except (KeyError, TypeError, AttributeError) as err:
        raise ModuleCatalogueError(f"malformed catalogue {CATALOGUE}: {err}") from err
    placed = {i: (m.hw_role, m.functions) for i, m in control.mined.items()
              if m.hw_role is not None and m.hw_role in roles}
    if "start" not in roles:
        raise ModuleCatalogueError(f"malformed catalogue {CATALOGUE}: no 'start' hardware role")
    return _Mined(roles, placed)


def _listed(functions: tuple[str, ...]) -> str:
    calls = [f"{f}()" for f in functions]
    return calls[0] if len(calls) == 1 else f"{', '.join(calls[:-1])} and {calls[-1]}"


def role_of(r: Reading) -> Role | None:
    """The role of a driver's ERROR/FATAL line the catalogue gives no cause (None: not such a line)."""
    if r.entry is None or r.cause is not None or r.line.level < ERROR or r.catalogue != CATALOGUE:
        return None
    found = _mined().placed.get(r.entry.id)
    return _mined().role(*found) if found is not None else None


def by_role(r: Reading, before: list[Reading]) -> RoleReading | None:
    """`r` read by the role of the callback its driver logs it in (None: not a driver's error the catalogue places);
    a role with no cause is kept, to be told as the line's place. A line logged both at the start and in the
    exchange is the exchange's only after `before` shows the control loop running; else it is told as the start's."""
    role = role_of(r)
    if role is None:
        return None
    if role.also_at_start and not any(b.kind in RUNNING_KINDS for b in before):
        role = _mined().role("start", tuple(f for f in role.functions if f in START))
    return RoleReading(r.line, r.entry, role.cause, r.catalogue, role.meaning, role=role)
