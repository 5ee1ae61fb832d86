"""PID gains from the YAML parameter files of ROS controllers (``--params FILE.yaml``).

Recognised wherever they sit (under namespaces, and under ``ros__parameters`` in ROS 2):

- **computed_torque_controllers** (ROS 1): ``<ns>: {joints: {<joint>: {p, i, d, i_clamp}}}``.
  Its PID output is an acceleration (the controller multiplies it by ``M(q)``), as in simulate.
- **joint_trajectory_controller** (ros_controllers, ros2_controllers) and **pid_controller**
  (ros2_controllers): ``gains: {<joint>: {p, i, d, i_clamp | i_clamp_max, i_clamp_min}}``.
  With an effort command interface the PID output is the joint effort, so the gains are
  N·m/rad (N/m); :mod:`txtool.simulation.gains` divides them by the joint's inertia. With a
  velocity or position interface they are not effort gains and are not used (a note says so).
- **effort_controllers/JointPositionController** (ROS 1): ``{joint: <joint>, pid: {p, i, d}}``.

Defaults are the controllers' own: ``i`` and ``d`` are 0. ROS 1's control_toolbox ``Pid::init``
requires ``p`` and reads ``i_clamp`` with default 0, which keeps the I-term at 0
(ros-controls/control_toolbox src/pid.cpp, melodic/noetic); in ROS 2 the integral clamps default
to none (ros-controls/ros2_controllers
joint_trajectory_controller/src/joint_trajectory_controller_parameters.yaml, ``gains``).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from txtool.io.xmlio import InputError
from txtool.simulation.params import GainSource, JointGains, Params, key_of

PID_KEYS = ("p", "i", "d", "i_clamp", "i_clamp_max", "i_clamp_min")
# Real PID parameters that do not change the joint-space law simulate runs.
OTHER_KEYS = ("antiwindup", "publish_state", "ff_velocity_scale", "feedforward_gain",
              "u_clamp_max", "u_clamp_min", "antiwindup_strategy", "tracking_time_constant",
              "error_deadband", "angle_wraparound", "normalize_error", "saturation")
# Feed-forward gains a controller adds to its PID's output, which simulate's law replaces with
# the computed torque of the reference (rnea of its position, speed and acceleration).
FEED_FORWARD = {
    # joint_trajectory_controller.cpp:439 (ros2_controllers @94e74de): the command is
    # ff_velocity_scale * reference speed + PID, in the command interface's unit.
    "ff_velocity_scale": "joint_trajectory_controller adds ff_velocity_scale times the "
                         "reference speed to its PID's output; simulate's feed-forward is the "
                         "computed torque of the reference instead",
    # pid_controller.cpp:558-563: the command is feedforward_gain * reference + PID.
    "feedforward_gain": "pid_controller adds feedforward_gain times its reference to its PID's "
                        "output; simulate's feed-forward is the computed torque of the "
                        "reference instead",
}
MAX_DEPTH = 8

Path_ = tuple[str, ...]


@dataclass
class _File:
    path: str
    lines: dict[Path_, int]

    def line(self, keys: Path_) -> int:
        for cut in range(len(keys), 0, -1):
            if keys[:cut] in self.lines:
                return self.lines[keys[:cut]]
        return 0

    def where(self, keys: Path_) -> str:
        line = self.line(keys)
        return f"{self.path}:{line}: {'.'.join(keys)}" if line else \
            f"{self.path}: {'.'.join(keys)}"

    def error(self, keys: Path_, reason: str) -> InputError:
        return InputError(f"{self.where(keys)}: {reason}")


@dataclass(frozen=True)
class _Controller:
    keys: Path_  # where its parameters are
    name: str
    params: dict[str, Any]
    ros2: bool
    layout: str  # "joints" | "gains" | "pid"


def parse_yaml(text: str, path: str, only: str | None = None) -> Params:
    """The gains of every controller in the file (or of controller ``only``) as :class:`Params`.

    When two controllers give gains for one joint (a ROS 1 file often holds alternatives), the
    first one's are used and a note names the other; ``FILE.yaml#NAME`` picks one.
    """
    data, source = _document(text, path)
    found = list(_controllers(data, (), False))
    if only is not None:
        names = [c.name for c in found]
        found = [c for c in found if c.name == only]
        if not found:
            raise InputError(f"{path}: no controller '{only}' with gains (there are: "
                             f"{', '.join(names) or 'none'})")
    if not found:
        raise InputError(f"{path}: no controller gains found (expected <ns>: {{joints: "
                         "{<joint>: {p, i, d}}}, or gains: {<joint>: {p, i, d}})")
    params, unusable = _collect(data, source, text, found)
    if not params.joints:
        raise InputError(f"{path}: no gains of an effort or computed-torque controller: "
                         + "; ".join(unusable))
    return params


def controller_gains(text: str, path: str, name: str) -> Params:
    """The gains controller ``name`` of the file carries, for ``simulate --controllers``: none
    is no error (a position controller has none), and gains simulate cannot use get a note."""
    data, source = _document(text, path)
    return _collect(data, source, text,
                    [c for c in _controllers(data, (), False) if c.name == name])[0]


def _document(text: str, path: str) -> tuple[dict[str, Any], _File]:
    data, lines = _load(text, path)
    if not isinstance(data, dict):
        raise InputError(f"{path}: expected a mapping of controllers, got "
                         f"{type(data).__name__ if data is not None else 'an empty file'}")
    return data, _File(path, lines)


def _collect(data: dict[str, Any], source: _File, text: str, found: list[_Controller]
             ) -> tuple[Params, list[str]]:
    """(the gains of the controllers ``found``, why each unusable one is), the first
    controller's gains for a joint winning."""
    path = source.path
    types = dict(_types(data, ()))
    joints: dict[str, JointGains] = {}
    where: dict[str, str] = {}
    notes: list[str] = []
    unusable: list[str] = []
    for ctrl in found:
        per, fmt, why = _kind(ctrl, types.get(ctrl.name))
        line = source.line(ctrl.keys)
        at = f"{path}:{line}" if line else path
        if per is None:
            unusable.append(f"'{ctrl.name}' {why}")
            notes.append(f"{at}: gains of '{ctrl.name}' not used: {why}")
            continue
        taken: list[str] = []
        for joint, keys, values in _entries(ctrl, source):
            gains = _gains(source, keys, values, ctrl.ros2, per, fmt, notes)
            dotted = f"joints.{key_of(joint)}"
            if dotted in where:
                taken.append(joint)
                continue
            joints[joint] = gains
            where[dotted] = source.where(keys)
        if taken:
            notes.append(f"{at}: gains of '{ctrl.name}' for "
                         f"{', '.join(taken)} not used: an earlier controller in the file gives "
                         f"them (pick one with {Path(path).name}#{ctrl.name})")
    return Params(joints=joints, path=path, text=text, where=where, notes=tuple(notes)), unusable


def _load(text: str, path: str) -> tuple[Any, dict[Path_, int]]:
    """PyYAML's safe loader, keeping the line of every mapping key."""
    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
        data = loader.construct_document(node) if node is not None else None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None) or getattr(exc, "context_mark", None)
        where = f"{path}:{mark.line + 1}" if mark is not None else path
        reason = getattr(exc, "problem", None) or str(exc).strip().splitlines()[0]
        context, start = getattr(exc, "context", None), getattr(exc, "context_mark", None)
        if context and start is not None:
            reason += f" ({context} from line {start.line + 1})"
        raise InputError(f"{where}: invalid YAML: {reason}") from None
    finally:
        loader.dispose()
    lines: dict[Path_, int] = {}
    if node is not None:
        _index(node, (), lines, 0)
    return data, lines


def _index(node: yaml.Node, keys: Path_, lines: dict[Path_, int], depth: int) -> None:
    if not isinstance(node, yaml.MappingNode) or depth > MAX_DEPTH:
        return
    for key, value in node.value:
        if not isinstance(key, yaml.ScalarNode) or key.value == "<<":
            continue
        here = (*keys, str(key.value))
        lines.setdefault(here, key.start_mark.line + 1)
        _index(value, here, lines, depth + 1)


def _types(node: dict[str, Any], keys: Path_) -> Iterator[tuple[str, str]]:
    """(controller name, type) wherever a mapping has a ``type`` string (controller_manager)."""
    if len(keys) > MAX_DEPTH:
        return
    for key, value in node.items():
        if isinstance(value, dict):
            if isinstance(value.get("type"), str):
                yield str(key), value["type"]
            yield from _types(value, (*keys, str(key)))


def _controllers(node: dict[str, Any], keys: Path_, ros2: bool) -> Iterator[_Controller]:
    if len(keys) > MAX_DEPTH:
        return
    for key, value in node.items():
        if not isinstance(value, dict):
            continue
        here = (*keys, str(key))
        inner = value.get("ros__parameters")
        params, at, is_ros2 = (inner, (*here, "ros__parameters"), True) \
            if isinstance(inner, dict) else (value, here, ros2)
        layout = _layout(params)
        if layout is not None:
            yield _Controller(at, str(key), params, is_ros2, layout)
        else:
            yield from _controllers(params, at, is_ros2)


def _layout(params: dict[str, Any]) -> str | None:
    if _table_of_tables(params.get("gains")):
        return "gains"
    if _table_of_tables(params.get("joints")):
        return "joints"
    if isinstance(params.get("joint"), str) and isinstance(params.get("pid"), dict):
        return "pid"
    return None


def _table_of_tables(value: Any) -> bool:
    return isinstance(value, dict) and bool(value) and \
        all(isinstance(v, dict) for v in value.values())


def _kind(ctrl: _Controller, declared: str | None) -> tuple[str | None, str, str]:
    """(gains per "acceleration"/"effort" or None when unusable, format, why or assumption)."""
    kind = ctrl.params.get("type") if isinstance(ctrl.params.get("type"), str) else declared
    kind = kind or ""
    if ctrl.layout == "joints":
        return "acceleration", "computed_torque_controllers", ""
    if ctrl.layout == "pid":
        if kind and not kind.startswith("effort_controllers/JointPositionController"):
            return None, kind, f"a {kind}'s PID does not output a joint effort from position"
        return "effort", "effort_controllers/JointPositionController", ""
    fmt = "pid_controller" if "pid_controller" in kind or "dof_names" in ctrl.params \
        or "command_interface" in ctrl.params else "joint_trajectory_controller"
    measured = ctrl.params.get("reference_and_state_interfaces")
    if fmt == "pid_controller" and isinstance(measured, list) and measured \
            and measured[0] != "position":
        # pid_controller.cpp:566-596 (ros2_controllers @94e74de): its PID acts on the error of
        # the first of them.
        return None, fmt, (f"its PID acts on the {measured[0]} error "
                           "(reference_and_state_interfaces), not the position error")
    interfaces = ctrl.params.get("command_interfaces", ctrl.params.get("command_interface"))
    if isinstance(interfaces, str):
        interfaces = [interfaces]
    if isinstance(interfaces, list) and interfaces:
        if "effort" in interfaces:
            return "effort", fmt, ""
        return None, fmt, (f"its command interface is {', '.join(map(str, interfaces))}, so "
                           "its PID output is not a joint effort")
    if kind.startswith(("velocity_controllers/", "position_controllers/")):
        return None, fmt, f"a {kind} does not output a joint effort"
    return "effort", fmt, "" if kind.startswith("effort_controllers/") else \
        "no command interface given: effort assumed"


def _entries(ctrl: _Controller, source: _File
             ) -> Iterator[tuple[str, Path_, dict[str, Any]]]:
    if ctrl.layout == "pid":
        yield ctrl.params["joint"], (*ctrl.keys, "pid"), ctrl.params["pid"]
        return
    table = ctrl.params[ctrl.layout]
    for joint, values in table.items():
        yield str(joint), (*ctrl.keys, ctrl.layout, str(joint)), values


def _gains(source: _File, keys: Path_, values: dict[str, Any], ros2: bool, per: str,
           fmt: str, notes: list[str]) -> JointGains:
    given: dict[str, float] = {}
    for key, value in values.items():
        key = str(key)
        if key in FEED_FORWARD and type(value) in (int, float) and value:
            notes.append(f"{source.where((*keys, key))}: {value!r} not used: {FEED_FORWARD[key]}")
        if key in OTHER_KEYS:
            continue
        if key not in PID_KEYS:
            raise source.error((*keys, key), f"unknown key (expected {', '.join(PID_KEYS)})")
        given[key] = _number(source, (*keys, key), value)
    if "p" not in given and not ros2:
        raise source.error(keys, "no p gain: control_toolbox's Pid refuses to start without one")
    clamp = _clamp(source, keys, given, ros2, notes)
    if clamp == 0 and given.get("i", 0) > 0:
        notes.append(f"{source.where(keys)}: i_clamp is 0, so the I-term stays 0 "
                     "(control_toolbox's default)")
    origin = GainSource(source.path, source.line(keys), ".".join(keys),
                        fmt + ("" if per == "acceleration" else " (effort gains)"), given)
    return JointGains(kp=given.get("p", 0.0), kd=given.get("d", 0.0), ki=given.get("i", 0.0),
                      i_clamp=clamp, per=per, source=origin)


def _clamp(source: _File, keys: Path_, given: dict[str, float], ros2: bool,
           notes: list[str]) -> float | None:
    """The symmetric bound of |i * integral(e)|; None for none."""
    bound = given.get("i_clamp", math.inf if ros2 else 0.0)
    upper = given.get("i_clamp_max", bound)
    lower = given.get("i_clamp_min", bound)
    if upper != lower:
        notes.append(f"{source.where(keys)}: integral clamp taken as +-{min(upper, lower):g} "
                     "(simulate's bound is symmetric)")
    value = min(upper, lower)
    return None if math.isinf(value) else value


def _number(source: _File, keys: Path_, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise source.error(keys, f"expected a number, got {value!r}")
    number = float(value)
    if keys[-1].startswith("i_clamp"):
        number = abs(number)  # control_toolbox reads clamps as magnitudes (i_min = -|i_clamp|)
        if math.isnan(number):
            raise source.error(keys, f"expected a number, got {value!r}")
        return number
    if not math.isfinite(number) or number < 0:
        raise source.error(keys, f"must be finite and zero or positive, got {value!r}")
    return number
