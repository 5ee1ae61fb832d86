"""A loaded transmission's maps at single points, in plain Python floats (no numpy).

``map``, ``show --actuator-limits`` and ``roundtrip`` map a handful of values; they use these
maps so that the base install needs no numpy. The formulas are :mod:`txtool.mechanics.formulas`,
the same IEEE double operations in the same order as :mod:`txtool.mechanics.maps` (numpy, for
the simulation), so both give the same bits. Where Python would stop, IEEE arithmetic goes on:
a division by zero (reductions whose product underflows to 0) gives an infinity or NaN, as
numpy and the loaders' C++ do, instead of raising :class:`ZeroDivisionError`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from txtool.mechanics import linear
from txtool.mechanics.formulas import EFFORT_ALIASES, FORMULAS, Formula, formula_key
from txtool.model.core import Transmission
from txtool.model.semantics import Effective, NotLoadable, effective

TO_ACTUATOR = ("position", "velocity", *EFFORT_ALIASES)
TO_JOINT = (*TO_ACTUATOR, "absolute_position")


class ZeroReduction(NotLoadable):
    """A reduction ratio of zero: neither ROS loader constructs such a transmission."""

    def __init__(self, name: str) -> None:
        super().__init__(f"transmission '{name}': reduction ratio cannot be zero")
        self.transmission = name


class IEEE(float):
    """A float whose arithmetic stays IEEE 754 double arithmetic where Python's would raise:
    ``x / 0.0`` is a signed infinity, ``0.0 / 0.0`` NaN. Every result is an IEEE again."""

    __slots__ = ()

    def __add__(self, other: float) -> IEEE:
        return IEEE(float(self) + float(other))

    __radd__ = __add__

    def __sub__(self, other: float) -> IEEE:
        return IEEE(float(self) - float(other))

    def __rsub__(self, other: float) -> IEEE:
        return IEEE(float(other) - float(self))

    def __mul__(self, other: float) -> IEEE:
        return IEEE(float(self) * float(other))

    __rmul__ = __mul__

    def __truediv__(self, other: float) -> IEEE:
        return IEEE(divide(float(self), float(other)))

    def __rtruediv__(self, other: float) -> IEEE:
        return IEEE(divide(float(other), float(self)))

    def __neg__(self) -> IEEE:
        return IEEE(-float(self))


def divide(a: float, b: float) -> float:
    """``a / b`` as IEEE 754 divides: by a signed zero, a signed infinity or NaN."""
    if b != 0.0:
        return a / b
    if a == 0.0 or math.isnan(a):
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


@dataclass(frozen=True)
class PointMap:
    """One loaded transmission: values in index order (``joints``/``actuators``) in and out."""

    name: str
    kind: str
    joints: tuple[str, ...]
    actuators: tuple[str, ...]
    actuator_reduction: tuple[float, ...]
    joint_reduction: tuple[float, ...]
    offset: tuple[float, ...]
    convention: str = "ros2"

    @property
    def size(self) -> int:
        return len(self.joints)

    def joint_to_actuator(self, quantity: str, values: Sequence[float]) -> tuple[float, ...]:
        """Actuator values of the joint ``values``."""
        if quantity not in TO_ACTUATOR:
            raise ValueError(f"cannot map {quantity!r} from joint to actuator "
                             f"(expected one of {', '.join(TO_ACTUATOR)})")
        return self._apply(FORMULAS[formula_key(self.kind, quantity, self.convention)][1], values)

    def actuator_to_joint(self, quantity: str, values: Sequence[float]) -> tuple[float, ...]:
        """Joint values of the actuator ``values``."""
        if quantity not in TO_JOINT:
            raise ValueError(f"cannot map {quantity!r} from actuator to joint "
                             f"(expected one of {', '.join(TO_JOINT)})")
        return self._apply(FORMULAS[formula_key(self.kind, quantity, self.convention)][0], values)

    def _apply(self, formula: Formula, values: Sequence[float]) -> tuple[float, ...]:
        if len(values) != self.size:
            raise ValueError(f"transmission '{self.name}' maps {self.size} value(s) per sample, "
                             f"got {len(values)}")
        mapped = formula([IEEE(v) for v in values], _ieee(self.actuator_reduction),
                         _ieee(self.joint_reduction), _ieee(self.offset))
        return tuple(float(v) for v in mapped)


def _ieee(values: Sequence[float]) -> tuple[IEEE, ...]:
    return tuple(IEEE(v) for v in values)


def from_effective(eff: Effective, convention: str = "ros2") -> PointMap:
    """The maps of a loaded transmission (see :func:`txtool.mechanics.maps.from_effective`)."""
    linear.check_convention(convention)
    if 0.0 in eff.actuator_reduction + eff.joint_reduction:
        raise ZeroReduction(eff.name)
    return PointMap(eff.name, eff.kind, eff.joints, eff.actuators,
                    tuple(map(float, eff.actuator_reduction)),
                    tuple(map(float, eff.joint_reduction)),
                    tuple(map(float, eff.joint_offset)), convention)


def from_transmission(t: Transmission, convention: str = "ros2") -> PointMap:
    """The maps the transmission's loader builds; :class:`NotLoadable` when it builds none."""
    return from_effective(effective(t), convention)
