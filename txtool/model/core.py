"""The canonical, format-neutral transmission model.

Every reader produces these values and every writer consumes them. Values are stored where the
document wrote them (a joint's reduction on the joint, an actuator's on the actuator); what a
ROS loader actually uses from them is the business of :mod:`txtool.model.semantics`.

The classes are frozen dataclasses whose schema is pydantic's: :func:`validate` and
:func:`json_schema` go through a pydantic ``TypeAdapter``, loaded only by those functions, so
``txtool validate`` and ``show`` start without pydantic's model machinery (about 50 ms);
:func:`dump` writes the same JSON in plain Python.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache, lru_cache
from typing import TYPE_CHECKING, Any, Literal, TypeVar

if TYPE_CHECKING:
    from pydantic import TypeAdapter

Kind = Literal["simple", "differential", "four_bar", "other"]
Dialect = Literal["ros1", "ros2-p1", "ros2-p2"]
DIALECTS: tuple[Dialect, ...] = ("ros1", "ros2-p1", "ros2-p2")

STANDARD_TYPES: dict[str, Kind] = {
    "SimpleTransmission": "simple",
    "DifferentialTransmission": "differential",
    "FourBarLinkageTransmission": "four_bar",
}
TYPE_PREFIX = "transmission_interface/"

# pydantic reads this from each class: no unknown keys, descriptions from attribute docstrings.
_PYDANTIC_CONFIG = {"extra": "forbid", "use_attribute_docstrings": True}

Value = TypeVar("Value")


@dataclass(frozen=True, slots=True, kw_only=True)
class Location:
    """Where an element is written: 1-based line and column; path as the user gave it."""

    __pydantic_config__ = _PYDANTIC_CONFIG

    path: str
    line: int = 0
    column: int = 0


@dataclass(frozen=True, slots=True, kw_only=True)
class Number:
    """A numeric field: its value (None when the text is not a number) and the text as written.

    Keeping the text lets writers reproduce an unchanged value byte for byte (``325.949``)
    and lets the linter report text that a loader would reject or silently replace.
    """

    __pydantic_config__ = _PYDANTIC_CONFIG

    value: float | None
    text: str | None = None


@dataclass(frozen=True, slots=True, kw_only=True)
class Member:
    """A joint or an actuator of a transmission."""

    __pydantic_config__ = _PYDANTIC_CONFIG

    name: str
    role: str | None = None
    mechanical_reduction: Number | None = None
    offset: Number | None = None
    interfaces: tuple[str, ...] = ()
    state_interfaces: tuple[str, ...] = ()
    read_only: bool = False
    location: Location | None = None


@dataclass(frozen=True, slots=True, kw_only=True)
class Transmission:
    """One ``<transmission>`` element in any dialect."""

    __pydantic_config__ = _PYDANTIC_CONFIG

    name: str
    type: str
    """The type string as written (<type>, <plugin> or type=)."""
    kind: Kind
    joints: tuple[Member, ...] = ()
    actuators: tuple[Member, ...] = ()
    parameters: tuple[tuple[str, str], ...] = ()
    """Free <param name=...> values, in document order."""
    dialect: Dialect
    location: Location | None = None
    ros2_control: str | None = None
    """Name of the enclosing <ros2_control> element (ROS 2)."""
    xml: str | None = None
    """The element's XML, kept for custom types passed through."""


@dataclass(frozen=True, slots=True, kw_only=True)
class Document:
    """What ``txtool show`` prints: the transmissions of one document, in document order."""

    __pydantic_config__ = _PYDANTIC_CONFIG

    transmissions: tuple[Transmission, ...] = ()


def replace(value: Value, **changes: Any) -> Value:
    """A copy of a model value with some fields changed (:func:`dataclasses.replace`, without
    its per-call field inspection and keyword ``__init__``: conversions make several per
    transmission). The models are frozen, slotted and have no ``__post_init__``, so the copy
    sets each slot directly."""
    return _copier(type(value))(value, changes)  # type: ignore[no-any-return]


@cache
def _copier(model: type) -> Callable[[Any, dict[str, Any]], Any]:
    """A function that copies a ``model`` value, setting each slot in one straight line of
    code (a loop over the fields costs as much again)."""
    names = _field_names(model)
    scope: dict[str, Any] = {"new": object.__new__, "model": model, "known": frozenset(names),
                             "unknown": _unknown}
    lines = ["def copy(value, changes):",
             "    if not changes.keys() <= known:",
             "        unknown(model, changes, known)",
             "    get = changes.get",
             "    result = new(model)"]
    for index, name in enumerate(names):
        scope[f"set{index}"] = model.__dict__[name].__set__
        lines.append(f"    set{index}(result, get({name!r}, value.{name}))")
    lines.append("    return result")
    exec("\n".join(lines), scope)  # noqa: S102 (code from the model's own field names)
    return scope["copy"]  # type: ignore[no-any-return]


def builder(model: type[Value]) -> Callable[..., Value]:
    """A constructor of ``model`` values with the keywords and defaults of the class, that sets
    each slot directly: a frozen dataclass's ``__init__`` costs about three times as much, and
    the readers build several values per transmission. Tested against the class itself."""
    return _builder(model)  # type: ignore[no-any-return]


@cache
def _builder(model: type) -> Callable[..., Any]:
    scope: dict[str, Any] = {"new": object.__new__, "model": model}
    parameters, lines = [], []
    for index, f in enumerate(dataclasses.fields(model)):
        if f.default_factory is not dataclasses.MISSING:
            raise TypeError(f"{model.__name__}.{f.name}: a default factory is not supported")
        if f.default is dataclasses.MISSING:
            parameters.append(f.name)
        else:
            scope[f"default{index}"] = f.default
            parameters.append(f"{f.name}=default{index}")
        scope[f"set{index}"] = model.__dict__[f.name].__set__
        lines.append(f"    set{index}(built_, {f.name})")
    source = "\n".join([f"def build(*, {', '.join(parameters)}):", "    built_ = new(model)",
                        *lines, "    return built_"])
    exec(source, scope)  # noqa: S102 (code from the model's own field names)
    return scope["build"]  # type: ignore[no-any-return]


def _unknown(model: type, changes: dict[str, Any], known: frozenset[str]) -> None:
    raise TypeError(f"{model.__name__} has no field {', '.join(sorted(changes.keys() - known))}")


@cache
def adapter(model: type) -> TypeAdapter[Any]:
    from pydantic import TypeAdapter

    return TypeAdapter(model)


def validate(model: type[Value], data: Any) -> Value:
    """Check ``data`` (parsed JSON) against a model; raises pydantic's ``ValidationError``."""
    return adapter(model).validate_python(data)  # type: ignore[no-any-return]


def dump(value: Any) -> Any:
    """A model value as JSON-ready data, as pydantic's JSON mode gives it (fields in
    declaration order, tuples as lists); a NaN or infinite number is null (strict JSON has
    neither, and the number's text as written is kept beside it). Plain Python: building a
    pydantic serializer costs more than a command's own work (tests compare the two)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if value is None or isinstance(value, str | int):
        return value
    if isinstance(value, tuple | list):
        return [dump(item) for item in value]
    if isinstance(value, dict):
        return {key: dump(item) for key, item in value.items()}
    return {name: dump(getattr(value, name)) for name in _field_names(type(value))}


@cache
def _field_names(model: type) -> tuple[str, ...]:
    return tuple(f.name for f in dataclasses.fields(model))


def pydantic_dump(value: Any) -> Any:
    """:func:`dump` through pydantic's serializer (the reference the tests hold it to)."""
    import json

    return json.loads(adapter(type(value)).dump_json(value))


def json_schema(model: type) -> dict[str, Any]:
    return adapter(model).json_schema()  # type: ignore[no-any-return]


@lru_cache(maxsize=256)  # the few type texts documents use: each transmission asks
def kind_of(type_string: str) -> Kind:
    """Classify a type string; custom and misspelt types are ``other``."""
    text = type_string.strip()
    if text.startswith(TYPE_PREFIX):
        text = text[len(TYPE_PREFIX) :]
    return STANDARD_TYPES.get(text, "other")


def standard_type(kind: Kind) -> str:
    """The plugin name of a standard kind, as both ROS loaders register it."""
    standard = _STANDARD_TYPE.get(kind)
    if standard is None:
        raise ValueError(f"kind {kind!r} has no standard type")
    return standard


_STANDARD_TYPE = {kind: TYPE_PREFIX + short for short, kind in STANDARD_TYPES.items()}
