"""Whether migrate's fixes can find anything in a document, from facts cheap to take.

Each test answers for one fixable rule and may say yes where its fix finds nothing, never the
reverse: a ``no`` means the fix, run on this document, would change nothing and count nothing,
so :func:`txtool.transform.migrate.fix_tree` need not run (it walks every transmission and
indexes its members, twice per migration). A rule without a test here is always run.

The bytes of a document are asked first where they can answer (:func:`settled_text`): a few
scans in C instead of a walk of the tree with a Python object per element; the tree is walked
only where they cannot. A conversion's output is judged on its bytes alone.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence

from lxml import etree

from txtool.dialects.read import text_of
from txtool.io.encodings import SCANNABLE, detect_encoding
from txtool.model.robot import children
from txtool.rules import Rule
from txtool.rules.tx204_unknown_interface import PREFIX, ROS1_INTERFACES, unprefixed_registered

_INTERFACE = "{*}hardwareInterface"


def _unprefixed_interface(root: etree._Element) -> bool:
    """TX300 fixes a ``<hardwareInterface>`` naming a registered interface without its prefix."""
    return any(unprefixed_registered((text_of(element) or "").strip())
               for element in root.iter(_INTERFACE))


def _interface_on_actuator(root: etree._Element) -> bool:
    """TX301 copies an actuator's interfaces to a joint of the same transmission that has
    none."""
    for element in root.iter(_INTERFACE):
        actuator = element.getparent()
        if actuator is None or not _named(actuator, "actuator") or not _has_text(element):
            continue
        transmission = actuator.getparent()
        if transmission is not None and any(
                not any(_has_text(h) for h in children(joint, "hardwareInterface"))
                for joint in children(transmission, "joint")):
            return True
    return False


def _type_attribute(root: etree._Element) -> bool:
    """TX302 rewrites a ``<transmission>`` that has a ``type`` attribute."""
    return any(element.get("type") is not None for element in root.iter("{*}transmission"))


TESTS: dict[str, Callable[[etree._Element], bool]] = {
    "TX300": _unprefixed_interface,
    "TX301": _interface_on_actuator,
    "TX302": _type_attribute,
}


def might_fix(root: etree._Element, rules: Sequence[Rule], data: bytes | None = None) -> bool:
    """Whether any of ``rules`` could fix something in the tree of ``root``; ``data``, the
    text it was parsed from, answers first where it can."""
    settled = settled_text(data, rules) if data is not None else set()
    return any(TESTS.get(rule.code, _always)(root) for rule in rules
               if rule.code not in settled)


# A <hardwareInterface> holding a prefixed name and nothing else, first in a <joint> written
# with one name attribute (only white space between): its text names no unprefixed interface,
# and its parent is no actuator. The usual ROS 1 layout; anything else is read in the tree.
_JOINT_INTERFACE = re.compile(
    rb"<joint name=(?:\"[^\"<]*\"|'[^'<]*')>\s*<hardwareInterface>\s*" + PREFIX.encode()
    + rb"[^<]*</hardwareInterface>()")  # the empty group: findall() copies no match
_TRANSMISSION_TAG = re.compile(rb"transmission(\s[^<]*)")
_TYPE = re.compile(rb"type\s*=")
# No registered name starts like the prefix, so a text that does is no unprefixed name.
assert all(name[len(PREFIX):][:1] not in ("", PREFIX[0]) for name in ROS1_INTERFACES)


def settled_text(data: bytes, rules: Sequence[Rule]) -> set[str]:
    """The codes of ``rules`` whose fix, from the bytes ``data`` alone, surely finds nothing
    in the document (its tests may still say yes for the others)."""
    if detect_encoding(data).codec not in SCANNABLE:
        return set()
    codes = {rule.code for rule in rules}
    settled = set()
    if codes & {"TX300", "TX301"} and _interfaces_settled(data):
        settled |= {"TX300", "TX301"}
    if "TX302" in codes and not _type_attribute_text(data):
        settled.add("TX302")
    return settled & codes


# The fixes that look only for ROS 1 spellings (``<hardwareInterface>``, a ``type`` attribute
# on a ``<transmission>``), which a conversion to ROS 2 never writes.
ROS1_ONLY = frozenset({"TX300", "TX301", "TX302"})


def might_fix_converted(data: bytes, rules: Sequence[Rule], target: str) -> bool:
    """:func:`might_fix_text` on ``data``, what converting to ``target`` a document in which
    none of ``rules`` finds anything gave: a conversion to ROS 2 writes nothing that the fixes
    of :data:`ROS1_ONLY` look for, and leaves the rest as it was."""
    if target != "ros1" and all(rule.code in ROS1_ONLY for rule in rules):
        return False
    return might_fix_text(data, rules)


def might_fix_text(data: bytes, rules: Sequence[Rule]) -> bool:
    """:func:`might_fix` on the parse of ``data``, from its bytes alone (it may say yes where
    the tree would say no)."""
    settled = settled_text(data, rules)
    return any(rule.code not in settled for rule in rules)


def _interfaces_settled(data: bytes) -> bool:
    """Every ``hardwareInterface`` in the bytes belongs to an element that neither TX300 nor
    TX301 fixes: each occurrence is one of the two names of a :data:`_JOINT_INTERFACE`.

    Sound: a real element's start tag is one such name; only white space separates it from
    the ``<joint ...>`` before it, which is therefore a real start tag and its parent (a
    comment, CDATA section or instruction would end in between)."""
    total = data.count(b"hardwareInterface")
    if not total:
        return True
    # No match starts before the "<joint" last before the first occurrence (only a name and
    # white space stand between a match's "<joint" and its "<hardwareInterface>"), nor ends
    # after the last occurrence's ">".
    start = max(data.rfind(b"<joint", 0, data.find(b"hardwareInterface")), 0)
    end = data.rfind(b"hardwareInterface") + len(b"hardwareInterface>")
    return 2 * len(_JOINT_INTERFACE.findall(data, start, end)) == total


def _type_attribute_text(data: bytes) -> bool:
    """Whether a ``transmission`` start tag may have a ``type`` attribute."""
    first = data.find(b"transmission")
    if first < 0:
        return False
    # Every match starts at an occurrence and ends before the "<" after the last one.
    end = data.find(b"<", data.rfind(b"transmission"))
    tags = _TRANSMISSION_TAG.findall(data, first, len(data) if end < 0 else end)
    return bool(tags) and _TYPE.search(b"\0".join(tags)) is not None


def _named(element: etree._Element, name: str) -> bool:
    tag = element.tag
    return tag == name or tag.__class__ is str and tag.endswith("}" + name)


def _has_text(element: etree._Element) -> bool:
    return bool((text_of(element) or "").strip())


def _always(_: object) -> bool:
    return True
