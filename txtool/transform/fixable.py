"""Whether migrate's fixes can find anything in a document, from facts cheap to take.

Each test answers for one fixable rule and may say yes where its fix finds nothing, never the
reverse: a ``no`` means the fix, run on this document, would change nothing and count nothing,
so :func:`txtool.transform.migrate.fix_tree` need not run (it walks every transmission and
indexes its members, twice per migration). A rule without a test here is always run.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from lxml import etree

from txtool.dialects.read import text_of
from txtool.model.robot import children
from txtool.rules import Rule
from txtool.rules.tx204_unknown_interface import unprefixed_registered

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
