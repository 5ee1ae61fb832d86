"""ros2_control's standard transmissions as vectorised numpy maps.

The formulas (:mod:`txtool.mechanics.formulas`) are written out as ros2_control's
``transmission_interface`` computes them (not via a matrix inverse), so results match its test
vectors to the last bits. Inputs have shape ``(..., n)``: the last axis is the transmission
index (``joints``/``actuators`` order).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from txtool.mechanics import linear
from txtool.mechanics.formulas import EFFORT_ALIASES, FORMULAS, Formula, formula_key
from txtool.mechanics.points import ZeroReduction  # noqa: F401 - also a name of this module
from txtool.model.core import Transmission
from txtool.model.semantics import Effective, effective

KINDS = ("simple", "differential", "four_bar")
TO_ACTUATOR = ("position", "velocity", *EFFORT_ALIASES)
TO_JOINT = (*TO_ACTUATOR, "absolute_position")



@dataclass(frozen=True, eq=False)
class TransmissionMap:
    """One loaded transmission as maps between joint space and actuator space."""

    name: str
    kind: str
    joints: tuple[str, ...]
    actuators: tuple[str, ...]
    A: np.ndarray
    offset: np.ndarray
    convention: str = "ros2"
    actuator_reduction: tuple[float, ...] = field(default=())
    joint_reduction: tuple[float, ...] = field(default=())

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"transmission '{self.name}': unknown kind {self.kind!r}")
        linear.check_convention(self.convention)
        a = np.array(self.A, dtype=float)
        offset = np.array(self.offset, dtype=float).reshape(-1)
        n = 1 if self.kind == "simple" else 2
        if a.shape != (n, n) or offset.shape != (n,):
            raise ValueError(f"transmission '{self.name}': A must be {n}x{n} and offset {n}")
        a.setflags(write=False)
        offset.setflags(write=False)
        object.__setattr__(self, "A", a)
        object.__setattr__(self, "offset", offset)
        if not self.actuator_reduction or not self.joint_reduction:
            ar, jr = _reductions_from_a(self.kind, a)
            object.__setattr__(self, "actuator_reduction", ar)
            object.__setattr__(self, "joint_reduction", jr)
        if 0.0 in self.actuator_reduction or 0.0 in self.joint_reduction:
            raise ZeroReduction(self.name)
        expected = linear.velocity_matrix(self.kind, self.actuator_reduction, self.joint_reduction)
        if not np.allclose(a, expected, rtol=1e-12, atol=0.0):
            raise ValueError(f"transmission '{self.name}': A does not have the structure of a "
                             f"{self.kind} transmission with these reductions")

    @property
    def size(self) -> int:
        return len(self.offset)

    @property
    def A_inv(self) -> np.ndarray:  # noqa: N802 - the maths' name
        """Joint velocity = ``A_inv @`` actuator velocity."""
        return np.linalg.inv(self.A)

    @property
    def effort_to_joint(self) -> np.ndarray:
        """``E`` with joint effort = ``E @`` actuator effort (``A.T`` when power-conserving)."""
        ar, jr = self.actuator_reduction, self.joint_reduction
        return np.array(linear.effort_matrix(self.kind, ar, jr, self.convention))

    @property
    def effort_to_actuator(self) -> np.ndarray:
        """Actuator effort = this ``@`` joint effort."""
        return np.linalg.inv(self.effort_to_joint)

    def joint_to_actuator(self, quantity: str, values: ArrayLike) -> np.ndarray:
        """Map joint values (shape ``(..., n)``) to actuator values."""
        if quantity not in TO_ACTUATOR:
            raise ValueError(f"cannot map {quantity!r} from joint to actuator "
                             f"(expected one of {', '.join(TO_ACTUATOR)})")
        return self._apply(FORMULAS[self._key(quantity)][1], values)

    def actuator_to_joint(self, quantity: str, values: ArrayLike) -> np.ndarray:
        """Map actuator values (shape ``(..., n)``) to joint values."""
        if quantity not in TO_JOINT:
            raise ValueError(f"cannot map {quantity!r} from actuator to joint "
                             f"(expected one of {', '.join(TO_JOINT)})")
        return self._apply(FORMULAS[self._key(quantity)][0], values)

    def _key(self, quantity: str) -> tuple[str, str]:
        return formula_key(self.kind, quantity, self.convention)

    def _apply(self, formula: Formula, values: ArrayLike) -> np.ndarray:
        x = np.asarray(values, dtype=float)
        if x.ndim == 0 or x.shape[-1] != self.size:
            raise ValueError(f"transmission '{self.name}' maps {self.size} value(s) per sample, "
                             f"got shape {x.shape}")
        # Finite but huge (or tiny) values overflow to inf or nan; callers decide what a
        # non-finite result means, and numpy's RuntimeWarnings would be noise on stderr.
        with np.errstate(all="ignore"):
            columns = [x[..., i] for i in range(self.size)]
            mapped = formula(columns, self.actuator_reduction, self.joint_reduction, self.offset)
            return np.stack(mapped, axis=-1)


def _reductions_from_a(kind: str, a: np.ndarray) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Reductions reproducing ``A`` when a map was built from a matrix (not unique: scale)."""
    if kind == "simple":
        return (float(a[0, 0]),), (1.0,)
    if kind == "differential":
        jr1 = float(a[0, 1] / a[0, 0]) if a[0, 0] != 0 else 0.0
        return (float(a[0, 0]), float(a[1, 0])), (1.0, jr1)
    jr1 = float(a[1, 1] / a[1, 0]) if a[1, 0] != 0 else 0.0
    return (float(a[0, 0]), float(a[1, 0])), (1.0, jr1)


def from_parameters(
    name: str,
    kind: str,
    actuator_reduction: tuple[float, ...],
    joint_reduction: tuple[float, ...],
    joint_offset: tuple[float, ...],
    *,
    joints: tuple[str, ...] | None = None,
    actuators: tuple[str, ...] | None = None,
    convention: str = "ros2",
) -> TransmissionMap:
    """A map from raw parameters (index order); names default to ``joint1``/``actuator1``..."""
    n = 1 if kind == "simple" else 2
    if 0.0 in tuple(actuator_reduction) + tuple(joint_reduction):
        raise ZeroReduction(name)
    if not (len(actuator_reduction) == len(joint_reduction) == len(joint_offset) == n):
        raise ValueError(f"transmission '{name}': a {kind} transmission takes {n} value(s) "
                         f"per reduction and offset")
    ar, jr = tuple(map(float, actuator_reduction)), tuple(map(float, joint_reduction))
    return TransmissionMap(
        name=name,
        kind=kind,
        joints=joints or tuple(f"joint{i + 1}" for i in range(n)),
        actuators=actuators or tuple(f"actuator{i + 1}" for i in range(n)),
        A=np.array(linear.velocity_matrix(kind, ar, jr)),
        offset=np.array(joint_offset, dtype=float),
        convention=convention,
        actuator_reduction=ar,
        joint_reduction=jr,
    )


def from_effective(eff: Effective, convention: str = "ros2") -> TransmissionMap:
    """The maps of a loaded transmission (index order = ``eff.joints``/``eff.actuators``)."""
    return from_parameters(
        eff.name,
        eff.kind,
        eff.actuator_reduction,
        eff.joint_reduction,
        eff.joint_offset,
        joints=eff.joints,
        actuators=eff.actuators,
        convention=convention,
    )


def from_transmission(t: Transmission, convention: str = "ros2") -> TransmissionMap:
    """The maps the transmission's loader builds; :class:`NotLoadable` when it builds none."""
    return from_effective(effective(t), convention)
