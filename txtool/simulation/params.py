"""Simulation parameters: ``--params`` files (TOML, or controller YAML for gains) or
``[tool.txtool.simulate]`` in pyproject.toml.

::

    bandwidth = 20.0            # optional run settings; the command line overrides them
    [actuators.shoulder_motor]  # per actuator
    rotor_inertia = 1.2e-5      # kg m^2 (kg for linear actuators), reflected through the map
    effort_limit = 2.5          # peak effort at the actuator
    velocity_limit = 400.0      # actuator speed limit
    [joints.shoulder]           # per joint (gains in acceleration units)
    kp = 900.0
    kd = 60.0
    ki = 0.0
    i_clamp = 0.5               # bound of |ki * integral(e)|

YAML files hold the gains of ROS controllers (:mod:`txtool.simulation.yaml_gains`); which
files are read, and how by their kind, is :mod:`txtool.simulation.parameter_files`. Several
``--params`` files merge in order, a later file's entry replacing an earlier one's. Names are
checked against the robot later (:func:`Params.check_names`); everything else is checked here
and reported as one ``path[:line]: reason`` line.
"""

from __future__ import annotations

import math
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from txtool.io.xmlio import InputError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

ACTUATOR_KEYS = ("rotor_inertia", "effort_limit", "velocity_limit")
JOINT_KEYS = ("kp", "kd", "ki", "i_clamp")
RUN_KEYS = ("bandwidth", "dt", "duration", "tolerance")
POSITIVE = ("effort_limit", "velocity_limit", "bandwidth", "dt", "duration", "tolerance")
SECTION = ("tool", "txtool", "simulate")
YAML_SUFFIXES = (".yaml", ".yml")


@dataclass(frozen=True)
class ActuatorParams:
    rotor_inertia: float | None = None
    effort_limit: float | None = None
    velocity_limit: float | None = None


@dataclass(frozen=True)
class GainSource:
    """Where a joint's gains were read: file, line (0: unknown), dotted key, format."""

    file: str
    line: int
    key: str
    format: str  # "toml" or the controller whose YAML layout it was
    given: dict[str, float] = field(default_factory=dict)  # the values as the file has them


@dataclass(frozen=True)
class JointGains:
    """PID gains of one joint; ``per`` "acceleration" (the law's units) or "effort".

    Effort gains (N·m/rad, N/m) come from controllers whose PID output is the joint effort; they
    are turned into acceleration gains with the joint's inertia once the model is built.
    """

    kp: float | None = None
    kd: float | None = None
    ki: float | None = None
    i_clamp: float | None = None
    per: str = "acceleration"
    source: GainSource | None = None


@dataclass(frozen=True)
class Params:
    actuators: dict[str, ActuatorParams] = field(default_factory=dict)
    joints: dict[str, JointGains] = field(default_factory=dict)
    run: dict[str, float] = field(default_factory=dict)
    path: str | None = None
    text: str = ""
    prefix: str = ""
    where: dict[str, str] = field(default_factory=dict)  # "joints.NAME" -> "path:line: key"
    notes: tuple[str, ...] = ()

    def error(self, dotted: str, reason: str) -> InputError:
        """``path:line: key: reason`` with the line of ``dotted`` when it can be found."""
        return InputError(f"{self.located(dotted)}: {reason}")

    def located(self, dotted: str) -> str:
        """``path[:line]: key`` of an entry, for messages about it."""
        if dotted in self.where:
            return self.where[dotted]
        line = _line_of(self.text, self.prefix + dotted)
        where = f"{self.path}:{line}" if line else f"{self.path}"
        return f"{where}: {self.prefix}{dotted}"

    def check_names(self, actuators: set[str], joints: set[str], robot: str) -> None:
        for name in self.actuators:
            if name not in actuators:
                where = self.located(f"actuators.{key_of(name)}")
                raise InputError(f"{where}: no actuator '{name}' in {robot}")
        for name in self.joints:
            if name not in joints:
                where = self.located(f"joints.{key_of(name)}")
                raise InputError(f"{where}: no moving joint '{name}' in {robot}")


def merge(files: list[Params]) -> Params:
    """Files in order; a later file's actuator, joint or setting replaces an earlier one's."""
    if len(files) == 1:
        return files[0]
    actuators: dict[str, ActuatorParams] = {}
    joints: dict[str, JointGains] = {}
    run: dict[str, float] = {}
    where: dict[str, str] = {}
    notes: list[str] = []
    for params in files:
        for kind, entries in (("actuators", params.actuators), ("joints", params.joints)):
            for name in entries:
                where[f"{kind}.{key_of(name)}"] = params.located(f"{kind}.{key_of(name)}")
        actuators.update(params.actuators)
        joints.update(params.joints)
        run.update(params.run)
        notes += params.notes
    return Params(actuators=actuators, joints=joints, run=run, path=files[-1].path,
                  where=where, notes=tuple(notes))


def find_pyproject(robot_path: str) -> tuple[str, dict[str, Any], str] | None:
    """The ``pyproject.toml`` whose ``[tool.txtool.simulate]`` applies: for a robot inside the
    run's root (see :func:`~txtool.lint.config_files.applicable_config`), the first found from
    the root upward, never one a pull request drops beside the robot; else the nearest above
    the robot."""
    from txtool.lint.config_files import repository_root

    root = repository_root()
    start = Path(os.path.realpath(robot_path)).parent if robot_path != "-" else Path(root)
    if start == Path(root) or Path(root) in start.parents:
        start = Path(root)
    for folder in (start, *start.parents):
        candidate = folder / "pyproject.toml"
        if not os.path.lexists(candidate):
            continue
        text = read_text(str(candidate))
        data: Any = parse_toml(text, str(candidate))
        for key in SECTION:
            data = data.get(key) if isinstance(data, dict) else None
        if data is not None:
            if not isinstance(data, dict):
                raise InputError(f"{candidate}: tool.txtool.simulate must be a table")
            return str(candidate), data, text
    return None


def parse_params(data: dict[str, Any], path: str, text: str = "", prefix: str = "") -> Params:
    shell = Params(path=path, text=text, prefix=prefix)
    actuators: dict[str, ActuatorParams] = {}
    joints: dict[str, JointGains] = {}
    run: dict[str, float] = {}
    for key, value in data.items():
        if key == "actuators":
            for name, values in _tables(shell, key, value).items():
                actuators[name] = ActuatorParams(**_values(shell, f"{key}.{key_of(name)}", values,
                                                           ACTUATOR_KEYS))
        elif key == "joints":
            for name, values in _tables(shell, key, value).items():
                dotted = f"{key}.{key_of(name)}"
                numbers = _values(shell, dotted, values, JOINT_KEYS)
                source = GainSource(path, _line_of(text, prefix + dotted), prefix + dotted,
                                    "toml", dict(numbers))
                joints[name] = JointGains(**numbers, source=source)
        elif key in RUN_KEYS:
            run[key] = _number(shell, key, value)
        else:
            raise shell.error(key_of(key), "unknown key (expected actuators, joints, "
                              + ", ".join(RUN_KEYS) + ")")
    return Params(actuators=actuators, joints=joints, run=run, path=path, text=text, prefix=prefix)


def _tables(shell: Params, key: str, value: Any) -> dict[str, dict[str, Any]]:
    if not isinstance(value, dict):
        raise shell.error(key, "must be a table of names")
    for name, values in value.items():
        if not isinstance(values, dict):
            raise shell.error(f"{key}.{key_of(name)}", "must be a table")
    return value


def _values(shell: Params, where: str, values: dict[str, Any], allowed: tuple[str, ...]
            ) -> dict[str, float]:
    result = {}
    for key, value in values.items():
        if key not in allowed:
            raise shell.error(f"{where}.{key_of(key)}",
                              f"unknown key (expected {', '.join(allowed)})")
        result[key] = _number(shell, f"{where}.{key}", value)
    return result


def _number(shell: Params, dotted: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise shell.error(dotted, f"expected a number, got {value!r}")
    number = float(value)
    last = dotted.rsplit(".", 1)[-1]
    if not math.isfinite(number) or number < 0 or (last in POSITIVE and number == 0):
        bound = "positive" if last in POSITIVE else "zero or positive"
        raise shell.error(dotted, f"must be finite and {bound}, got {value!r}")
    return number


def key_of(name: str) -> str:
    return name if re.fullmatch(r"[A-Za-z0-9_-]+", name) else f'"{name}"'


def read_text(path: str) -> str:
    """A parameter file's text: a regular file of at most 1 MB (a FIFO would block, a device
    never end), else one line."""
    from txtool.io.xmlio import read_regular
    from txtool.lint.config_files import MAX_CONFIG_BYTES

    try:
        return read_regular(path, MAX_CONFIG_BYTES).decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"{path}: cannot read: {exc}") from None


def parse_toml(text: str, path: str) -> dict[str, Any]:
    try:
        return tomllib.loads(text)
    except RecursionError:  # tomllib recurses once per level of nested arrays and tables
        raise InputError(f"{path}: configuration nested too deep") from None
    except tomllib.TOMLDecodeError as exc:
        match = re.search(r"\(at line (\d+), column \d+\)", str(exc))
        reason = re.sub(r"\s*\(at line .*\)$", "", str(exc))
        where = f"{path}:{match.group(1)}" if match else path
        raise InputError(f"{where}: invalid TOML: {reason}") from None


def _line_of(text: str, dotted: str) -> int:
    """Best-effort line of a dotted key: its table header, then the key inside the table."""
    if not text:
        return 0
    parts = dotted.split(".")
    lines = text.splitlines()
    for cut in range(len(parts), 0, -1):
        header = ".".join(parts[:cut])
        for number, line in enumerate(lines, 1):
            if re.match(r"\s*\[\s*" + re.escape(header) + r"\s*\]", line):
                return _key_line(lines, number, parts[cut:]) or number
    leaf = parts[-1].strip('"')
    for number, line in enumerate(lines, 1):
        if re.match(r"\s*\"?" + re.escape(leaf) + r"\"?\s*=", line):
            return number
    return 0


def _key_line(lines: list[str], header: int, rest: list[str]) -> int:
    if not rest:
        return header
    leaf = rest[-1].strip('"')
    for number in range(header + 1, len(lines) + 1):
        line = lines[number - 1]
        if re.match(r"\s*\[", line):
            return 0
        if re.match(r"\s*\"?" + re.escape(leaf) + r"\"?\s*=", line):
            return number
    return 0
