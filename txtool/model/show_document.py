"""What a ROS loader binds from one transmission, as data: ``txtool show``'s effective view.

The values come from :func:`txtool.model.semantics.effective`; :mod:`txtool.views.effective`
fills these classes. They are pydantic-schema'd dataclasses like :mod:`txtool.model.core`, so
``schemas/transmission.schema.json`` describes ``show --format json`` whole.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from txtool.model.core import Transmission

_PYDANTIC_CONFIG = {"extra": "forbid", "use_attribute_docstrings": True}

Field = Literal["joint_reduction", "joint_offset", "actuator_reduction"]


@dataclass(frozen=True, slots=True, kw_only=True)
class Slot:
    """One index of the loader's maths: the parameters there and the members they come from."""

    __pydantic_config__ = _PYDANTIC_CONFIG

    index: int
    joint_parameters_of: str
    """The joint whose written reduction and offset sit at this index."""
    joint_reduction: float | None
    """null when not a finite number (strict JSON has no NaN or infinity)."""
    joint_offset: float | None
    actuator_parameters_of: str
    """The actuator whose written reduction sits at this index."""
    actuator_reduction: float | None
    joint: str
    """The joint whose data (position, velocity, effort) the loader maps at this index."""
    actuator: str
    """The actuator whose data the loader maps at this index."""
    defaults: tuple[Field, ...] = ()
    """Fields that took the loader's default: absent, or unparsable under ros2_control
    (which silently uses 1.0 or 0.0)."""
    not_read: tuple[Field, ...] = ()
    """Fields this type's loader never reads (the neutral 1.0 stands in): the joint
    reduction of a ROS 1 simple transmission, the actuator reduction of a ROS 2 one."""


@dataclass(frozen=True, slots=True, kw_only=True)
class Binding:
    """The transmission as its loader builds it; ``slots`` in the loader's index order."""

    __pydantic_config__ = _PYDANTIC_CONFIG

    loader: Literal["ros1", "ros2"]
    loadable: bool | None
    """false when the loader refuses the transmission; null for a type outside the standard
    three (a plugin: whether and how it loads is the plugin's business)."""
    reason: str | None = None
    """Why the loader refuses the transmission, or why nothing is known of it."""
    parameter_order: Literal["role", "xml"] | None = None
    """How the loader indexes parameters: by <role> (ros_control) or XML order (ros2_control)."""
    data_order: Literal["xml", "name"] | None = None
    """How joint and actuator data are indexed: XML order (ros_control) or sorted by name
    (ros2_control's handles)."""
    slots: tuple[Slot, ...] = ()
    component_type: str | None = None
    """The type= of the enclosing <ros2_control> (system, actuator, sensor)."""
    added_actuators: tuple[str, ...] = ()
    """Actuators ros2_control's parser appends to the transmission (``actuator1`` in an
    actuator component)."""
    notes: tuple[str, ...] = ()
    """Where the bound values differ from what the document seems to say."""


@dataclass(frozen=True, slots=True, kw_only=True)
class ShownTransmission(Transmission):
    """A transmission as written, and what its loader binds."""

    effective: Binding


@dataclass(frozen=True, slots=True, kw_only=True)
class ActuatorLimitRow:
    """A joint's URDF limits seen from one actuator (``show --actuator-limits``)."""

    __pydantic_config__ = _PYDANTIC_CONFIG

    transmission: str
    actuator: str
    position: tuple[float, float] | None
    velocity: float | None
    effort: float | None


@dataclass(frozen=True, slots=True, kw_only=True)
class ShownReaders:
    """The programs judged to read the file (``show --effective``; see "Readers" in
    docs/loaders.md)."""

    __pydantic_config__ = _PYDANTIC_CONFIG

    readers: tuple[str, ...]
    """Reader names, e.g. ros2_control (jazzy), gz_ros2_control, ros_control."""
    because: tuple[str, ...]
    """Why each reader was assumed, in the same order."""
    decided: bool
    """True when the readers are known; false when nothing said, and each transmission is
    shown as the loader of its dialect binds it."""
    unread: tuple[str, ...]
    """The transmissions none of the readers reads."""


@dataclass(frozen=True, slots=True, kw_only=True)
class ShowDocument:
    """What ``txtool show --format json`` prints, transmissions in document order."""

    __pydantic_config__ = _PYDANTIC_CONFIG

    transmissions: tuple[ShownTransmission, ...] = ()
    actuator_limits: tuple[ActuatorLimitRow, ...] | None = None
    """Present with --actuator-limits."""
    readers: ShownReaders | None = None
    """Present with --effective."""
