"""The JSON report of ``txtool simulate``, as ``schemas/simulate.schema.json`` describes it.

One shape for one config or many: ``{"verdict", "runs": [...]}``. Units follow one convention:
every object holding numbers has a ``units`` map giving the unit of each of its numeric keys
(``"1"`` for counts, shares and line numbers), whether the value is a number or null.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from txtool.simulation.report import overall_verdict
from txtool.simulation.result import ActuatorStats, Coverage, GainsUsed, JointStats, RunResult

if TYPE_CHECKING:
    from txtool.simulation.controlled import Driver

ONE = "1"  # counts, shares, line numbers


def document(runs: list[RunResult]) -> dict[str, Any]:
    """``{"verdict", "runs": [...]}``, one run per config; non-finite numbers are null."""
    return _clean({"verdict": overall_verdict(runs), "runs": [run_json(r) for r in runs]})


def run_json(run: RunResult) -> dict[str, Any]:
    """One config's run: verdict and reasons, then its numbers, each with its unit."""
    kinds = {j.units for j in run.joints.values()}
    return {
        "verdict": run.verdict,
        "reasons": list(run.reasons),
        "causes": [{"kind": c.kind, "text": c.text} for c in run.causes],
        "robot": run.robot,
        "config": run.config,
        "readers": {role: r.as_json() for role, r in run.readers.items()},
        "reference": run.reference,
        "notes": list(run.notes),
        "joints": {name: joint_json(j) for name, j in run.joints.items()},
        "actuators": {name: actuator_json(a) for name, a in run.actuators.items()},
        "gains": {name: gains_json(g) for name, g in run.gains.items()},
        "counterbalance": {name: counterbalance_json(entry)
                           for name, entry in run.counterbalance.items()},
        "checked": coverage_json(run.coverage),
        "controllers": {name: driver_json(d) for name, d in run.controllers.items()},
        "tolerance": run.tolerance,
        "steps": run.steps,
        "dt": run.dt,
        "duration": run.duration,
        "units": {"tolerance": kinds.pop() if len(kinds) == 1 else "rad|m", "steps": ONE,
                  "dt": "s", "duration": "s"},
    }


def joint_json(j: JointStats) -> dict[str, Any]:
    return {"max_error": j.max_error, "rms_error": j.rms_error,
            "max_error_time": j.max_error_time, "limit_margin": j.limit_margin,
            "transmission": j.transmission or None,
            "units": {"max_error": j.units, "rms_error": j.units, "max_error_time": "s",
                      "limit_margin": j.units}}


def actuator_json(a: ActuatorStats) -> dict[str, Any]:
    effort, speed = a.effort_units, a.speed_units
    return {"peak_effort": a.peak_effort, "effort_limit": _finite(a.effort_limit),
            "rms_effort": a.rms_effort, "peak_velocity": a.peak_velocity,
            "velocity_limit": _finite(a.velocity_limit),
            "saturated_fraction": a.saturated_fraction, "first_violation": a.first_violation,
            "transmission": a.transmission or None,
            "units": {"peak_effort": effort, "effort_limit": effort, "rms_effort": effort,
                      "peak_velocity": speed, "velocity_limit": speed,
                      "saturated_fraction": ONE, "first_violation": "s"}}


def counterbalance_json(entry: dict[str, float | str]) -> dict[str, Any]:
    """Static load, limit and carried torque (peaks) of a counterbalanced joint."""
    unit = str(entry["units"])
    numbers = {key: value for key, value in entry.items() if key != "units"}
    return {**numbers, "units": dict.fromkeys(numbers, unit)}


def coverage_json(covered: Coverage) -> dict[str, Any]:
    """What the run checked: the config's transmissions and the joints driven through them."""
    return {"transmissions": covered.transmissions,
            "simulated": list(covered.simulated),
            "skipped": {name: why for name, why in covered.skipped},
            "unread": {name: why for name, why in covered.unread},
            "joints": covered.joints, "joints_checked": covered.joints_checked,
            "still": list(covered.still),
            "units": {"transmissions": ONE, "joints": ONE, "joints_checked": ONE}}


def driver_json(driver: Driver | None) -> dict[str, Any] | None:
    """The controller commanding a joint (``--controllers``); None: no controller does, the
    joint is held."""
    if driver is None:
        return None
    return {"controller": driver.controller, "type": driver.type,
            "command_interfaces": list(driver.interfaces), "file": driver.file,
            "line": driver.line or None, "units": {"line": ONE}}


def gains_json(g: GainsUsed) -> dict[str, Any]:
    """Gains as used (acceleration per error), their units and where they came from."""
    return {"kp": g.kp, "kd": g.kd, "ki": g.ki, "i_clamp": g.i_clamp,
            "units": {"kp": "1/s²", "kd": "1/s", "ki": "1/s³", "i_clamp": f"{g.units}/s²"},
            "source": _gain_source(g)}


def _gain_source(g: GainsUsed) -> dict[str, Any]:
    units: dict[str, str] = {}
    if g.source is None:
        source: dict[str, Any] = {"default": "bandwidth"}
    else:
        given = dict(g.source.given)
        given["units"] = {key: _given_unit(key, g) for key in given}
        source = {"file": g.source.file, "line": g.source.line or None, "key": g.source.key,
                  "format": g.source.format, "given": given}
        units["line"] = ONE
        if g.inertia is not None:
            source["divided_by_inertia"] = g.inertia
            units["divided_by_inertia"] = "kg" if g.units == "m" else "kg·m²"
    if g.bandwidth is not None:
        source["bandwidth"] = g.bandwidth
        units["bandwidth"] = "rad/s"
    source["units"] = units
    return source


def _given_unit(key: str, g: GainsUsed) -> str:
    """The unit of a gain as the file gives it: per acceleration, or (divided by the joint's
    inertia later) per effort."""
    q = g.units
    key = key.removeprefix("k")  # TOML writes kp, kd, ki
    if g.inertia is None:
        return {"p": "1/s²", "d": "1/s", "i": "1/s³"}.get(key, f"{q}/s²")
    effort = "N" if q == "m" else "N·m"
    return {"p": f"{effort}/{q}", "d": f"{effort}·s/{q}", "i": f"{effort}/({q}·s)"}.get(
        key, effort)


def _finite(value: float | None) -> float | None:
    return None if value is None or not math.isfinite(value) else value


def _clean(value: Any) -> Any:
    if isinstance(value, float):
        return _finite(value)
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_clean(v) for v in value]
    return value
