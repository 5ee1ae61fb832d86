"""The fixable rules' fixes: which apply to a file under its readers, whether any can find
something in a document, and applying them to its tree (``migrate`` and ``validate --fix``).

Which apply: the fixes of TX300, TX301 and TX302 rewrite top-level ROS 1 transmissions,
ros_control's. Where the file's readers are decided (``--ros-distro``, the configuration's
``ros-distro`` or ``readers``, ``package.xml``, a ``<gazebo>`` plugin) and none of them reads
top-level transmissions, validate reports nothing on those (TX305 says nothing reads them), so
nothing is fixed there either. Transmissions inside ``<ros2_control>`` are never ROS 1 to these
rules.

Whether any can find something (:func:`might_fix`): a test for each of those rules, from facts
cheap to take, which may say yes where its fix finds nothing, never the reverse; a ``no`` means
the fix would change nothing and count nothing, so neither the readers need deciding nor
:func:`fix_tree` running (it walks every transmission and indexes its members). A rule without
a test is always run.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from lxml import etree

from txtool.dialects.read import text_of, transmission_elements
from txtool.io.xmlio import Source
from txtool.lint.config import readers_of
from txtool.lint.suppress import Suppressions
from txtool.lint.suppress import parse as parse_suppressions
from txtool.model.readers import Placement
from txtool.model.robot import children
from txtool.rules import Rule
from txtool.rules.tx204_unknown_interface import unprefixed_registered

MAX_FIX_ROUNDS = 4

TOP_LEVEL_FIXES = frozenset({"TX300", "TX301", "TX302"})


def fixes_read(source: Source, rules: Sequence[Rule], ros_distro: str | None = None,
               config: str | None = None) -> list[Rule]:
    """The ``rules`` whose fixes change what a reader of ``source`` reads, its readers decided
    as ``validate`` decides them (``ros_distro``: its ``--ros-distro``; ``config``: its
    ``--config``)."""
    if all(rule.code not in TOP_LEVEL_FIXES for rule in rules):
        return list(rules)
    if readers_of(source, ros_distro, config).reads(Placement.TOP_LEVEL):
        return list(rules)
    return [rule for rule in rules if rule.code not in TOP_LEVEL_FIXES]


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


def might_fix(root: etree._Element, rules: Sequence[Rule]) -> bool:
    """Whether any of ``rules`` could fix something in the tree of ``root``."""
    return any(rule.code not in TESTS or TESTS[rule.code](root) for rule in rules)


def _named(element: etree._Element, name: str) -> bool:
    tag = element.tag
    return tag == name or tag.__class__ is str and tag.endswith("}" + name)


def _has_text(element: etree._Element) -> bool:
    return bool((text_of(element) or "").strip())


def fix_tree(tree: etree._ElementTree, rules: Sequence[Rule], data: bytes) -> dict[str, int]:
    """Apply the fixes of ``rules`` until none finds anything more; counts by code.

    Suppression comments in ``data`` (the text ``tree`` was parsed from) are honoured: a
    ``disable-file`` directive turns a fix off, a line directive keeps it off the transmission
    holding that line.
    """
    suppressions = parse_suppressions(data)
    counts: dict[str, int] = {}
    for _ in range(MAX_FIX_ROUNDS):
        fixed = 0
        for rule in rules:
            count = _fix_one(tree.getroot(), rule, suppressions)
            if count:
                counts[rule.code] = counts.get(rule.code, 0) + count
                fixed += count
        if not fixed:
            break
    return counts


def _fix_one(root: etree._Element, rule: Rule, suppressions: Suppressions) -> int:
    fix = rule.fix
    assert fix is not None
    if not _mentions(suppressions, rule.code):
        return fix(root)
    return sum(fix(element) for element in transmission_elements(root)
               if not _silenced(element, rule.code, suppressions))


def _mentions(suppressions: Suppressions, code: str) -> bool:
    return any(not d.codes or code in d.codes for d in suppressions.directives)


def _silenced(element: etree._Element, code: str, suppressions: Suppressions) -> bool:
    """Whether a directive covers ``code`` on any line of ``element`` (as originally parsed)."""
    lines = {e.sourceline for e in element.iter() if e.sourceline is not None}
    return suppressions.silences(code, lines or {0})
