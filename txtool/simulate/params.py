"""Simulation parameters: a ``--params`` TOML file or ``[tool.txtool.simulate]`` in pyproject.toml.

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

Names are checked against the robot later (:func:`Params.check_names`); everything else is
checked here and reported as one ``path[:line]: reason`` line.
"""

from __future__ import annotations

import math
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


@dataclass(frozen=True)
class ActuatorParams:
    rotor_inertia: float | None = None
    effort_limit: float | None = None
    velocity_limit: float | None = None


@dataclass(frozen=True)
class JointGains:
    kp: float | None = None
    kd: float | None = None
    ki: float | None = None
    i_clamp: float | None = None


@dataclass(frozen=True)
class Params:
    actuators: dict[str, ActuatorParams] = field(default_factory=dict)
    joints: dict[str, JointGains] = field(default_factory=dict)
    run: dict[str, float] = field(default_factory=dict)
    path: str | None = None
    text: str = ""
    prefix: str = ""

    def error(self, dotted: str, reason: str) -> InputError:
        """``path:line: key: reason`` with the line of ``dotted`` when it can be found."""
        line = _line_of(self.text, self.prefix + dotted)
        where = f"{self.path}:{line}" if line else f"{self.path}"
        return InputError(f"{where}: {self.prefix}{dotted}: {reason}")

    def check_names(self, actuators: set[str], joints: set[str], robot: str) -> None:
        for name in self.actuators:
            if name not in actuators:
                raise self.error(f"actuators.{_key(name)}", f"no actuator '{name}' in {robot}")
        for name in self.joints:
            if name not in joints:
                raise self.error(f"joints.{_key(name)}", f"no moving joint '{name}' in {robot}")


def load_params(explicit: str | None, robot_path: str) -> Params:
    """``--params FILE`` if given, else the nearest pyproject.toml with the section, else none."""
    if explicit is not None:
        text = _read(explicit)
        return parse_params(_toml(text, explicit), explicit, text)
    found = find_pyproject(robot_path)
    if found is None:
        return Params()
    path, data, text = found
    return parse_params(data, path, text, prefix="tool.txtool.simulate.")


def find_pyproject(robot_path: str) -> tuple[str, dict[str, Any], str] | None:
    start = Path(robot_path).resolve().parent if robot_path != "-" else Path.cwd()
    for folder in (start, *start.parents):
        candidate = folder / "pyproject.toml"
        if not candidate.is_file():
            continue
        text = _read(str(candidate))
        data: Any = _toml(text, str(candidate))
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
                actuators[name] = ActuatorParams(**_values(shell, f"{key}.{_key(name)}", values,
                                                           ACTUATOR_KEYS))
        elif key == "joints":
            for name, values in _tables(shell, key, value).items():
                joints[name] = JointGains(**_values(shell, f"{key}.{_key(name)}", values,
                                                    JOINT_KEYS))
        elif key in RUN_KEYS:
            run[key] = _number(shell, key, value)
        else:
            raise shell.error(_key(key), "unknown key (expected actuators, joints, "
                              + ", ".join(RUN_KEYS) + ")")
    return Params(actuators=actuators, joints=joints, run=run, path=path, text=text, prefix=prefix)


def _tables(shell: Params, key: str, value: Any) -> dict[str, dict[str, Any]]:
    if not isinstance(value, dict):
        raise shell.error(key, "must be a table of names")
    for name, values in value.items():
        if not isinstance(values, dict):
            raise shell.error(f"{key}.{_key(name)}", "must be a table")
    return value


def _values(shell: Params, where: str, values: dict[str, Any], allowed: tuple[str, ...]
            ) -> dict[str, float]:
    result = {}
    for key, value in values.items():
        if key not in allowed:
            raise shell.error(f"{where}.{_key(key)}",
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


def _key(name: str) -> str:
    return name if re.fullmatch(r"[A-Za-z0-9_-]+", name) else f'"{name}"'


def _read(path: str) -> str:
    try:
        return Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"{path}: cannot read: {exc}") from None


def _toml(text: str, path: str) -> dict[str, Any]:
    try:
        return tomllib.loads(text)
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
