"""Where elements stand and how they are laid out: indentation read from the document, an
element removed with its lines, one appended in the layout of its siblings, comments carried,
roles restyled in place. Shared by the placer and the writers of converted documents."""

from __future__ import annotations

from collections.abc import Callable

from lxml import etree

from txtool.io.xmlio import local
from txtool.model.core import Dialect
from txtool.model.robot import children


def restyle_roles(element: etree._Element, dialect: Dialect) -> None:
    """Roles as ``role=`` attributes (Proposal 2) or ``<role>`` elements (Proposal 1), in
    place: the rest of the transmission stays as written."""
    for member in [*children(element, "joint"), *children(element, "actuator")]:
        if dialect == "ros2-p2":
            roles = children(member, "role")
            if roles and member.get("role") is None:
                _set_after_name(member, "role", (roles[0].text or "").strip())
            for role in roles:
                cut(role)
            if roles and len(member) == 0 and not (member.text or "").strip():
                member.text = None  # <x/> again
        elif member.get("role") is not None:
            role = etree.Element(member.tag.replace("}" + local(member), "}role")
                                 if "}" in member.tag else "role")
            role.text = member.attrib.pop("role")
            _insert_first(member, role)


def _set_after_name(element: etree._Element, name: str, value: str) -> None:
    items = list(element.attrib.items())
    at = next((i + 1 for i, (key, _) in enumerate(items) if key == "name"), len(items))
    items.insert(at, (name, value))
    element.attrib.clear()
    element.attrib.update(items)


def _insert_first(parent: etree._Element, child: etree._Element) -> None:
    indent, step = indentation(parent)
    first = next(iter(parent), None)
    if first is None:
        child.tail = "\n" + indent
    else:
        child.tail = parent.text if parent.text and parent.text.strip() == "" else None
    parent.text = "\n" + (leading_space(first) if first is not None else indent + step)
    parent.insert(0, child)


def runs_of(elements: list[etree._Element]) -> list[list[etree._Element]]:
    """Elements that stand together (siblings with only whitespace between them). The first
    run is replaced by the generated block, which keeps the blank lines between them."""
    runs: list[list[etree._Element]] = []
    for element in elements:
        if runs and element.getprevious() is runs[-1][-1]:
            runs[-1].append(element)
        else:
            runs.append([element])
    return runs


def cut(element: etree._Element) -> None:
    """Remove ``element`` with the lines it stands on: the whitespace that starts its line
    goes with it, its tail stays (so the blank lines on either side are kept)."""
    parent = element.getparent()
    previous = element.getprevious()
    before = (previous.tail if previous is not None else parent.text) or ""
    head, newline, indent = before.rpartition("\n")
    tail = element.tail or ""
    joined = head + tail if newline and not indent.strip() and tail.startswith(("\n", "\r")) \
        else before + tail
    if previous is not None:
        previous.tail = joined
    else:
        parent.text = joined
    parent.remove(element)


def append(parent: etree._Element, element: etree._Element) -> None:
    last = next(parent.iterchildren(reversed=True), None)  # len(parent) walks every child
    if last is not None:
        element.tail = last.tail or ""
        last.tail = "\n" + leading_space(last)
    else:
        indent, _ = indentation(parent)
        element.tail = "\n" + indent
    parent.append(element)


def reindent(tail: str | None, indent: str) -> str:
    """``tail`` with the indentation of its last line replaced by ``indent``."""
    head, newline, _ = (tail or "").rpartition("\n")
    return head + newline + indent if newline else "\n" + indent


def with_comments(new: etree._Element, old: etree._Element) -> bool:
    """Carry the comments of the old element: under the same joint or actuator when they
    stood there, else at the top of the transmission. Whether there was one to carry."""
    if not has_comment(old):
        return False  # (most transmissions)
    parents = [old, *children(old, "joint"), *children(old, "actuator")]
    targets = {(local(m), m.get("name")): m for m in new if isinstance(m.tag, str)}
    carried = False
    for parent in parents:
        target = new if parent is old else targets.get((local(parent), parent.get("name")), new)
        comments = [etree.Comment(c.text) for c in parent if isinstance(c, etree._Comment)]
        carried = carried or bool(comments)
        if target is new:  # at the top, in order: each put first, the last one first
            for comment in reversed(comments):  # (lxml walks to an index: insert(i) costs i)
                new.insert(0, comment)
        else:
            for comment in comments:
                target.append(comment)
    return carried


def has_comment(element: etree._Element) -> bool:
    return next(element.iter(etree.Comment), None) is not None


def namespace_of(element: etree._Element) -> str | None:
    tag = element.tag
    return tag[1:].split("}", 1)[0] if isinstance(tag, str) and tag.startswith("{") else None


def become(old: etree._Element, new: etree._Element) -> None:
    """Give the root element ``new``'s content, keeping its place among top-level comments."""
    old.tag = new.tag
    old.attrib.clear()
    old.attrib.update(new.attrib)
    old.text = new.text
    del old[:]
    old.extend(list(new))


def qualifier(like: etree._Element) -> Callable[[str], str]:
    """Tag names in the default namespace of ``like`` (some URDFs declare one)."""
    ns = namespace_of(like)
    return (lambda tag: f"{{{ns}}}{tag}") if ns else (lambda tag: tag)


def leading_space(element: etree._Element) -> str:
    previous = element.getprevious()
    text = previous.tail if previous is not None else (
        element.getparent().text if element.getparent() is not None else "")
    text = text or ""
    return text.rsplit("\n", 1)[-1] if "\n" in text else ""


def indentation(element: etree._Element) -> tuple[str, str]:
    """The indentation of ``element`` and the step its first child element is indented by
    (two spaces where it has none)."""
    indent = leading_space(element)
    first = next((c for c in element if isinstance(c.tag, str)), None)
    inner = leading_space(first) if first is not None else ""
    if inner.startswith(indent) and len(inner) > len(indent):
        return indent, inner[len(indent):]
    return indent, "  "


def child_indentation(parent: etree._Element) -> tuple[str, str]:
    outer, step = indentation(parent)
    last = next((c for c in reversed(parent) if isinstance(c.tag, str)), None)
    if last is not None:
        return leading_space(last), step
    return outer + step, step
