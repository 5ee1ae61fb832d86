"""``simulate --campaign FILE``: the campaign file and the samples drawn from it.

A campaign asks whether candidate configs still pass when the robot differs from its URDF
within bounds. The file is TOML (``schemas/campaign.schema.json`` describes it)::

    seed = 7                      # the generator of the random samples
    samples = 16                  # random samples, each parameter uniform within its bounds
    corners = true                # also every corner of the bounds (2^k for k ranges)
    candidates = ["robot.ros2.urdf"]   # relative to this file; default: the command's configs

    [bounds]
    damping = [0.0, 0.2]          # viscous damping added to every joint, N·m·s/rad (N·s/m)
    friction = [0.0, 0.5]         # Coulomb friction added to every joint, N·m (N)
    rotor_inertia = [0.8, 1.2]    # factor on every actuator's rotor inertia
    gains = [0.7, 1.3]            # factor on the controller's kp, kd and ki
    sensor_noise = [0.0, 1e-4]    # std of each actuator position reading, rad (m)

    [bounds.payload]
    link = "tool0"
    mass = [0.0, 2.0]             # kg, a point mass
    xyz = [0.0, 0.0, 0.05]        # where on the link, m in the link's frame (default: origin)

A bound is ``[low, high]`` or one number (a fixed value). The samples are drawn here, once, in
sample order, so every candidate meets the same perturbations and a worker draws nothing but
its own sensor noise, from a generator seeded with ``(seed, sample)``. Every problem is one line
``path[:line]: reason`` (exit 2).
"""

from __future__ import annotations

import itertools
import math
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from txtool.io.xmlio import InputError
from txtool.simulation.params import _line_of, parse_toml, read_text

TOP_KEYS = ("seed", "samples", "corners", "candidates", "bounds")
# Per bounded parameter: its unit (for reports) and the smallest value it may take.
PARAMETERS: dict[str, tuple[str, str]] = {
    "payload_mass": ("kg", "zero or positive"),
    "damping": ("N·m·s/rad (N·s/m)", "zero or positive"),
    "friction": ("N·m (N)", "zero or positive"),
    "rotor_inertia": ("factor", "zero or positive"),
    "gains": ("factor", "positive"),
    "sensor_noise": ("rad (m)", "zero or positive"),
}
BOUND_KEYS = ("damping", "friction", "rotor_inertia", "gains", "sensor_noise", "payload")
PAYLOAD_KEYS = ("link", "mass", "xyz")
MAX_SAMPLES = 100_000
MAX_RUNS = 1_000_000  # samples times candidates: each is a task built before any runs
# The largest value of any bound and of a payload's coordinates: far beyond any robot, and
# small enough that the loop's arithmetic stays finite (1e307 overflowed it).
MAX_BOUND = 1e6
MAX_XYZ = 1e3


@dataclass(frozen=True)
class Payload:
    link: str
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Campaign:
    path: str
    seed: int
    samples: int
    corners: bool
    candidates: tuple[str, ...]  # resolved against the file's folder; () = the command's own
    bounds: dict[str, tuple[float, float]]  # PARAMETERS key -> (low, high)
    payload: Payload | None = None
    text: str = field(default="", repr=False)

    def error(self, dotted: str, reason: str) -> InputError:
        line = _line_of(self.text, dotted)
        return InputError(f"{self.path}:{line}: {reason}" if line else f"{self.path}: {reason}")


def read_campaign(path: str) -> Campaign:
    """The campaign in ``path``, checked; a problem is one ``path[:line]: reason`` line."""
    text = read_text(path)
    data = parse_toml(text, path)
    shell = Campaign(path, 0, 0, False, (), {}, text=text)
    for key in data:
        if key not in TOP_KEYS:
            raise shell.error(key, f"unknown key '{key}' (expected {', '.join(TOP_KEYS)})")
    seed = _integer(shell, data, "seed", 0, minimum=0)
    samples = _integer(shell, data, "samples", 0, minimum=0)
    corners = data.get("corners", False)
    if not isinstance(corners, bool):
        raise shell.error("corners", f"corners: expected true or false, got {corners!r}")
    bounds, payload = _bounds(shell, data.get("bounds", {}))
    candidates = _candidates(shell, data.get("candidates", []))
    ranged = sum(low != high for low, high in bounds.values())
    count = samples + (2**ranged if corners else 0)
    if count == 0:
        raise shell.error("samples", "no samples: give samples = N (N > 0) or corners = true")
    if count > MAX_SAMPLES:
        raise shell.error("samples", f"{count} samples; a campaign takes at most {MAX_SAMPLES}")
    if count * len(candidates) > MAX_RUNS:
        raise shell.error("candidates", f"{len(candidates)} candidates of {count} samples: "
                                        f"{count * len(candidates)} runs; a campaign makes at "
                                        f"most {MAX_RUNS}")
    return Campaign(path, seed, samples, corners, candidates, bounds, payload, text)


def _integer(shell: Campaign, data: dict[str, Any], key: str, default: int, minimum: int) -> int:
    value = data.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise shell.error(key, f"{key}: expected a whole number of at least {minimum}, "
                               f"got {value!r}")
    return value


def _candidates(shell: Campaign, value: Any) -> tuple[str, ...]:
    if not isinstance(value, list) or not all(isinstance(v, str) and v for v in value):
        raise shell.error("candidates", "candidates: expected a list of file names")
    folder = os.path.dirname(shell.path)
    return tuple(os.path.normpath(os.path.join(folder, v)) for v in value)


def _bounds(shell: Campaign, table: Any) -> tuple[dict[str, tuple[float, float]], Payload | None]:
    if not isinstance(table, dict):
        raise shell.error("bounds", "bounds: expected a table")
    bounds: dict[str, tuple[float, float]] = {}
    payload = None
    for key, value in table.items():
        if key not in BOUND_KEYS:
            raise shell.error(f"bounds.{key}",
                              f"bounds.{key}: unknown (expected {', '.join(BOUND_KEYS)})")
        if key == "payload":
            payload, bounds["payload_mass"] = _payload(shell, value)
        else:
            bounds[key] = _bound(shell, f"bounds.{key}", key, value)
    return bounds, payload


def _payload(shell: Campaign, table: Any) -> tuple[Payload, tuple[float, float]]:
    where = "bounds.payload"
    if not isinstance(table, dict):
        raise shell.error(where, f"{where}: expected a table with link and mass")
    for key in table:
        if key not in PAYLOAD_KEYS:
            raise shell.error(f"{where}.{key}",
                              f"{where}.{key}: unknown (expected {', '.join(PAYLOAD_KEYS)})")
    link = table.get("link")
    if not isinstance(link, str) or not link:
        raise shell.error(where, f"{where}.link: expected the name of a link")
    if "mass" not in table:
        raise shell.error(where, f"{where}.mass: missing (kg, [low, high] or one number)")
    mass = _bound(shell, f"{where}.mass", "payload_mass", table["mass"])
    xyz = table.get("xyz", [0.0, 0.0, 0.0])
    if not (isinstance(xyz, list) and len(xyz) == 3
            and all(_finite_number(v) and abs(v) <= MAX_XYZ for v in xyz)):
        raise shell.error(f"{where}.xyz", f"{where}.xyz: expected three numbers (m) within "
                                          f"±{MAX_XYZ:g}, got {xyz!r}")
    return Payload(link, (float(xyz[0]), float(xyz[1]), float(xyz[2]))), mass


def _finite_number(value: Any) -> bool:
    return not isinstance(value, bool) and isinstance(value, int | float) and math.isfinite(value)


def _bound(shell: Campaign, dotted: str, name: str, value: Any) -> tuple[float, float]:
    pair = value if isinstance(value, list) else [value, value]
    if len(pair) != 2 or not all(_finite_number(v) for v in pair):
        raise shell.error(dotted, f"{dotted}: expected [low, high] or one number, got {value!r}")
    low, high = float(pair[0]), float(pair[1])
    if low > high:
        raise shell.error(dotted, f"{dotted}: low {low:g} is above high {high:g}")
    wanted = PARAMETERS[name][1]
    if low < 0 or (wanted == "positive" and low == 0):
        raise shell.error(dotted, f"{dotted}: must be {wanted}, got {low:g}")
    if high > MAX_BOUND:
        raise shell.error(dotted, f"{dotted}: at most {MAX_BOUND:g}, got {high:g}")
    return low, high


def draw(campaign: Campaign) -> list[dict[str, float]]:
    """The samples in order: the corners (if asked), then the random draws.

    Each is ``{parameter: value}`` for the bounded parameters. The random draws come from one
    generator seeded with ``seed``, one parameter after the other in :data:`PARAMETERS` order,
    so a file gives the same samples on any machine.
    """
    names = [n for n in PARAMETERS if n in campaign.bounds]
    samples: list[dict[str, float]] = []
    if campaign.corners:
        ranged = [n for n in names if campaign.bounds[n][0] != campaign.bounds[n][1]]
        for corner in itertools.product((0, 1), repeat=len(ranged)):
            sample = {n: campaign.bounds[n][0] for n in names}
            sample.update({n: campaign.bounds[n][side] for n, side in zip(ranged, corner,
                                                                          strict=True)})
            samples.append(sample)
    generator = np.random.default_rng(campaign.seed)
    for _ in range(campaign.samples):
        samples.append({n: float(generator.uniform(*campaign.bounds[n])) for n in names})
    return samples
