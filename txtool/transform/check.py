"""The check of a conversion: read the written document back, convert it back, compare.

Each transmission of the document as read is paired, by its name (same-named ones in document
order), with the one the written document holds; that one is translated back to the
original's dialect and compared with it on what the original itself defines
(:func:`judge`): a value it leaves out is not judged, and the interfaces that an existing
``<ros2_control>`` declares besides its own are a note, not a loss.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from functools import cache
from typing import Any

from lxml import etree

from txtool.dialects.read import read_each
from txtool.dialects.translate import translate
from txtool.model.core import Transmission
from txtool.views.tables import FIELDS, view


@dataclass
class Verdict:
    """What did not survive the round trip (``losses``) and what is worth knowing
    (``notes``), in the order of the transmissions."""

    losses: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)


def round_trip(originals: Sequence[Transmission], written: etree._Element) -> Verdict:
    """Judge each of ``originals`` (the transmissions as read) against what ``written``
    (the root of the converted document, as a parse of its bytes reads it) holds of it
    (:func:`paired`). A custom type, or one the written document no longer holds, is not
    judged; what is said comes in the order of the originals."""
    said: dict[int, Verdict] = {}
    blocks = cache(lambda: {e.get("name") for e in written.iter("{*}ros2_control")})
    for i, out in paired(originals, read_each(written)):
        t = originals[i]
        if t.kind == "other":
            continue
        heard = Verdict()
        _judge(t, out, heard, blocks)
        if heard.losses or heard.notes:
            said[i] = heard
    verdict = Verdict()
    for i in sorted(said):
        verdict.losses.extend(said[i].losses)
        verdict.notes.extend(said[i].notes)
    return verdict


def paired(originals: Sequence[Transmission], written: Iterable[Transmission]
           ) -> Iterator[tuple[int, Transmission]]:
    """Each of ``originals`` that ``written`` (the transmissions of a written document, in
    document order: :func:`~txtool.dialects.read.read_each`) holds: its index and what
    ``written`` holds of it. Paired by name and by whether the type is custom, same-named
    ones in document order (the order a conversion keeps among them)."""
    # Each name's indexes last first, taken from the end: a list of one or two (a deque is
    # ten times the size, and a document has a queue per transmission).
    waiting: dict[tuple[str, bool], list[int]] = {}
    for i in range(len(originals) - 1, -1, -1):
        t = originals[i]
        waiting.setdefault((t.name, t.kind == "other"), []).append(i)
    for out in written:
        queue = waiting.get((out.name, out.kind == "other"))
        if queue:
            yield queue.pop(), out


def _judge(t: Transmission, out: Transmission, result: Verdict,
           blocks: Callable[[], set[str | None]]) -> None:
    """Convert ``out``, what the output holds of the original ``t``, back to ``t``'s dialect,
    and say in ``result`` what did not survive. ``blocks``: the names of the output's
    ``<ros2_control>`` blocks (asked only where needed)."""
    back = translate(out, t.dialect).transmission
    a_view, b_view = view(t), view(back)
    lost = _lost(a_view, b_view)
    if out.ros2_control is not None:  # it stands in a <ros2_control>
        lost.pop("interfaces", None)
        _interfaces(t, *_defined(a_view["interfaces"], b_view["interfaces"]), result)
    elif "interfaces" in lost and t.ros2_control is not None and t.ros2_control in blocks():
        lost.pop("interfaces")
        _kept_declaration(t, *_defined(a_view["interfaces"], b_view["interfaces"]), result)
    for key, change in lost.items():
        result.losses.append(f"transmission '{t.name}' did not survive the round trip: "
                             f"{key}: {change}")


def judge(before: Transmission, after: Transmission) -> dict[str, str]:
    """The fields of ``before`` that ``after`` (its round trip) does not keep, as
    ``before -> after`` texts: judged on what ``before`` itself defines. A value it leaves
    out is not judged (a missing ROS 1 reduction comes back as ros2_control's 1.0), a joint
    that names no valid interface may come back state-only, and command interfaces that a
    ``<ros2_control>`` block declares besides its own are kept, not lost."""
    return _lost(view(before), view(after))


def _lost(a_view: dict[str, Any], b_view: dict[str, Any]) -> dict[str, str]:
    """:func:`judge` on the views of both transmissions."""
    lost = {}
    for key in ("kind", *FIELDS):
        a, b = _defined(a_view[key], b_view[key])
        if key == "interfaces":
            a, b = _without_state(a), _without_state(b)
            if all(kinds <= b.get(joint, frozenset()) for joint, kinds in a.items()):
                continue
        if not _same(a, b):
            lost[key] = f"{_show(a)} -> {_show(b)}"
    return lost


def _defined(a: Any, b: Any) -> tuple[Any, Any]:
    """Both views without the members whose value the original leaves undefined."""
    if not isinstance(a, dict) or not isinstance(b, dict):
        return a, b
    keep = {k for k, v in a.items() if v is not None}
    return ({k: v for k, v in a.items() if k in keep},
            {k: v for k, v in b.items() if k in keep or k not in a})


def _without_state(kinds: dict) -> dict:
    """A joint that names no command interface comes back as state-only: the same."""
    return {joint: names - {"state"} for joint, names in kinds.items()}


def _interfaces(t: Transmission, a: dict, b: dict, result: Verdict) -> None:
    for joint, kinds in a.items():
        back = b.get(joint, frozenset()) - {"state"}
        kinds = kinds - {"state"}
        if kinds - back:
            result.losses.append(
                f"joint '{joint}': transmission '{t.name}' names {_show(kinds)} but the "
                f"<ros2_control> that declares the joint commands {_show(back) or 'nothing'}; "
                "add the missing command interface there (txtool does not change a hardware "
                "declaration)")
        elif back - kinds:
            result.notes.append(
                f"joint '{joint}': its <ros2_control> declaration also commands "
                f"{_show(back - kinds)}, which transmission '{t.name}' does not name; kept")


def _kept_declaration(t: Transmission, a: dict, b: dict, result: Verdict) -> None:
    """Back to ROS 1 out of a ``<ros2_control>`` that stays in the document: what the block
    declares besides what the ROS 1 transmission names stays declared there (a file that
    had both before ``--reversible`` took it to ROS 2 gets both back), not a loss."""
    for joint, kinds in a.items():
        back = b.get(joint, frozenset()) - {"state"}
        kinds = kinds - {"state"}
        if back - kinds:
            result.losses.append(
                f"joint '{joint}': transmission '{t.name}' names {_show(back - kinds)} in "
                f"ros1, which <ros2_control name=\"{t.ros2_control}\"> does not command")
        elif kinds - back:
            result.notes.append(
                f"joint '{joint}': <ros2_control name=\"{t.ros2_control}\"> also commands "
                f"{_show(kinds - back)}, which transmission '{t.name}' does not name in ros1; "
                "the block stays")


def _same(x: Any, y: Any) -> bool:
    if isinstance(x, dict) and isinstance(y, dict):
        return x.keys() == y.keys() and all(_same(x[k], y[k]) for k in x)
    return repr(x) == repr(y) if isinstance(x, float) or isinstance(y, float) else x == y


def _show(value: Any) -> str:
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {_show(v)}" for k, v in value.items()) + "}"
    if isinstance(value, frozenset | set):
        return "{" + ", ".join(sorted(value)) + "}"
    return repr(value)
