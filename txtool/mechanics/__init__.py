"""Transmission mechanics: joint/actuator maps, checks, limits, inertia and equivalence.

The names below load lazily, so importing :mod:`txtool.mechanics.linear` (as the linter does)
never loads numpy; :mod:`txtool.mechanics.points` (``map``, ``show``, ``roundtrip``) needs none.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from txtool.mechanics.inertia import reflected_inertia
    from txtool.mechanics.maps import (
        TransmissionMap,
        from_effective,
        from_parameters,
        from_transmission,
    )
    from txtool.mechanics.points import ZeroReduction

_EXPORTS = {
    "TransmissionMap": "maps",
    "ZeroReduction": "points",
    "from_effective": "maps",
    "from_parameters": "maps",
    "from_transmission": "maps",
    "reflected_inertia": "inertia",
}

__all__ = [
    "TransmissionMap",
    "ZeroReduction",
    "from_effective",
    "from_parameters",
    "from_transmission",
    "reflected_inertia",
]


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'txtool.mechanics' has no attribute {name!r}")
    return getattr(importlib.import_module(f"txtool.mechanics.{module}"), name)
