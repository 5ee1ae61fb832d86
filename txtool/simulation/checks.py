"""Checks on a finished run beyond tracking and limits: the effort path and limit cycles.

* **Effort path**: the joint torque the controller commands (its actuator efforts read back
  through the candidate's own effort map) against the torque the robot's transmissions apply
  to the same actuator efforts. Feedback hides a wrong effort map in the tracking error (the
  integral and high gains make up for it), so it is compared directly.
* **Chatter**: an actuator whose saturated demand keeps reversing sign (every step, or every few
  steps when the loop's delay slows the oscillation down) is in a limit cycle against its
  limits. Its joint may still track, but the loop is unstable: this fails even with
  ``--allow-saturation``.

:func:`judge` adds these reasons and, when the run fails, the likely causes from
:mod:`txtool.simulation.diagnose`.
"""

from __future__ import annotations

import numpy as np

from txtool.simulation import diagnose
from txtool.simulation.drive import Drive
from txtool.simulation.result import Cause, RunResult, Series
from txtool.simulation.sensing import Encoder

EFFORT_TOLERANCE = 0.01  # of the joint's peak torque
CHATTER_WINDOW = 100  # steps
CHATTER_REVERSALS = 8  # saturated sign reversals within the window: a period <= 25 steps


def judge(run: RunResult, series: Series, plant: Drive, ctrl: Drive, S: np.ndarray,
          candidate: bool, encoder: Encoder | None = None, delay: bool = True) -> None:
    """Append the effort-path and chatter reasons, then what differs between the maps: the
    likely causes of a failure, or the failure itself where the run tracked anyway.

    ``candidate``: a config other than the robot's own was given.
    """
    with np.errstate(all="ignore"):
        run.reasons += effort_path(series, plant, ctrl, S)
        run.reasons += chatter(series)
    interfaces = interface_mismatch(plant, ctrl)
    run.reasons += interfaces
    found = diagnose.find(plant, ctrl, S, series.units)
    run.causes = [Cause("interface", reason) for reason in interfaces] + found
    if run.failed:
        if found:
            run.reasons += [f"likely cause: {cause.text}" for cause in found]
        elif candidate and not interfaces:  # an interface mismatch is its own cause
            nothing = Cause("not_transmissions", "not the transmissions: the config's maps "
                            "equal the robot's (look at the gains, the limits or the reference)")
            run.causes.append(nothing)
            run.reasons.append(f"likely cause: {nothing.text}")
    elif found:
        # The maps are compared exactly: a config that differs is not the robot's, even where
        # this motion and these gains happen to keep the tracking error within the tolerance.
        run.reasons += [f"the config's maps differ from the robot's (it tracks within the "
                        f"tolerance on this motion): {cause.text}" for cause in found]
    run.notes += sensing_notes(encoder, delay, plant)


def interface_mismatch(plant: Drive, ctrl: Drive) -> list[str]:
    """Joints the config commands through other interfaces than the robot's (effort where the
    robot takes position, say): a controller written for one cannot drive the other. The
    simulation itself runs on efforts, so only this comparison sees the difference."""
    reasons = []
    for joint, robot_kinds in plant.commands.items():
        config_kinds = ctrl.commands.get(joint)
        if config_kinds is None or config_kinds == robot_kinds:
            continue
        reasons.append(f"joint '{joint}': the config commands it through "
                       f"{_kinds(config_kinds)}, the robot through {_kinds(robot_kinds)}")
    return reasons


def _kinds(kinds: frozenset[str]) -> str:
    return " and ".join(sorted(kinds))


def effort_path(series: Series, plant: Drive, ctrl: Drive, S: np.ndarray) -> list[str]:
    """Joints whose applied torque differs from the commanded one by over 1% of its peak."""
    demand = series.effort_demand  # robot actuator order, before saturation
    if not len(demand) or not np.isfinite(demand).all():
        return []
    commanded = demand @ (ctrl.eff_a2j @ S).T
    applied = demand @ plant.eff_a2j.T
    difference = np.abs(applied - commanded)
    peak = np.maximum(np.abs(commanded).max(axis=0), np.abs(applied).max(axis=0))
    floor = 1e-9 * peak.max(initial=0.0)
    reasons = []
    for v, joint in enumerate(series.joints):
        k = int(np.argmax(difference[:, v]))
        worst = difference[k, v]
        if worst <= max(EFFORT_TOLERANCE * peak[v], floor):
            continue
        unit = "N" if series.units[v] == "m" else "N·m"
        reasons.append(
            f"joint '{joint}': the robot's transmissions apply {applied[k, v]:.4g} {unit} where "
            f"the controller commands {commanded[k, v]:.4g} {unit} (at t={series.time[k]:.3f} s; "
            f"off by {100 * worst / peak[v]:.0f}% of the peak torque)")
    return reasons


def chatter(series: Series) -> list[str]:
    """Actuators whose saturated demand reverses sign at least 8 times within 100 steps."""
    reasons = []
    for i, name in enumerate(series.actuators):
        limit = series.effort_limit[i]
        if not np.isfinite(limit):
            continue
        hit = _limit_cycle(series.effort_demand[:, i], limit)
        if hit is None:
            continue
        start, count = hit
        reasons.append(
            f"actuator '{name}': chatters against its effort limit {limit:.4g} from "
            f"t={series.time[start]:.3f} s: its saturated demand reverses sign {count} times, "
            f"at least {CHATTER_REVERSALS} times within {CHATTER_WINDOW} steps (a limit cycle: "
            "the loop is unstable)")
    return reasons


def _limit_cycle(demand: np.ndarray, limit: float) -> tuple[int, int] | None:
    """(first step of the first window with enough saturated reversals, reversals in all)."""
    side = np.where(demand > limit, 1, np.where(demand < -limit, -1, 0))
    saturated = np.nonzero(side)[0]
    if len(saturated) < 2:
        return None
    turns = saturated[1:][side[saturated[1:]] != side[saturated[:-1]]]
    if len(turns) < CHATTER_REVERSALS:
        return None
    # Reversals in the window of CHATTER_WINDOW steps that ends at each reversal.
    inside = np.arange(len(turns)) - np.searchsorted(turns, turns - CHATTER_WINDOW + 1) + 1
    hits = np.nonzero(inside >= CHATTER_REVERSALS)[0]
    if not len(hits):
        return None
    first = int(hits[0]) - CHATTER_REVERSALS + 1
    return int(turns[first]), len(turns)


def sensing_notes(encoder: Encoder | None, delay: bool, plant: Drive) -> list[str]:
    notes = []
    if not delay:
        notes.append("no read-to-write delay (--no-delay): each command acts in its own step")
    if encoder is not None:
        linear = [plant.actuators[i] for i in np.nonzero(encoder.linear)[0]]
        notes.append(f"encoders of {encoder.counts} counts per actuator revolution; velocity "
                     "by finite differences"
                     + (f"; not quantised (linear): {', '.join(linear)}" if linear else ""))
    return notes
