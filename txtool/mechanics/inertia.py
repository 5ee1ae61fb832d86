"""Rotor inertia reflected into joint space."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from txtool.mechanics.maps import TransmissionMap


def reflected_inertia(tmap: TransmissionMap, rotor_inertia: ArrayLike) -> np.ndarray:
    """``A.T @ diag(J_r) @ A``: the joint-space inertia of the rotors, shape ``(n, n)``.

    ``rotor_inertia`` is one value per actuator in ``tmap.actuators`` order (or one value for
    all). From the rotors' kinetic energy ``1/2 qdot_a^T J_r qdot_a`` with ``qdot_a = A qdot_j``;
    for a simple transmission it is ``J_r n^2`` (what pinocchio calls armature).
    """
    j = np.asarray(rotor_inertia, dtype=float)
    if j.ndim == 0:
        j = np.full(tmap.size, float(j))
    if j.shape != (tmap.size,):
        raise ValueError(f"transmission '{tmap.name}' has {tmap.size} actuator(s), "
                         f"got {j.size} rotor inertia value(s)")
    a = tmap.A
    return a.T @ (j[:, None] * a)
