"""Mutated robot descriptions for the fuzz tests and ``bench/fuzz.py``.

:func:`documents` draws a seed (every file in ``fixtures/`` and, when it is there, every file of
the shared corpus), applies one to three composable mutations to its lxml tree (delete,
duplicate, move or rename elements, swap attribute values, random text in numeric fields, deep
nesting, a new root tag, a bare fragment) and serialises it, then sometimes breaks the bytes
(truncation, random bytes, a misplaced declaration). :func:`invocations` adds the command line
to run on it. Everything a run needs to be reproduced is in the drawn values: the seed name, the
steps, the bytes and the arguments.
"""

from __future__ import annotations

import copy
import functools
import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from click.testing import Result
from hypothesis import strategies as st
from lxml import etree

from tests.corpus import CORPUS
from txtool.io.xmlio import InputError, parse_bytes, safe_parser

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "fixtures"

MEMBER_TAGS = ("transmission", "joint", "actuator", "ros2_control")
NUMERIC_TAGS = ("mechanicalReduction", "mechanical_reduction", "offset", "param")
NUMERIC_ATTRIBUTES = ("lower", "upper", "effort", "velocity", "xyz", "rpy", "value",
                      "multiplier")
NASTY_NUMBERS = ("nan", "NaN", "inf", "-inf", "Infinity", "-0", "0", "0.0", "1e309", "-1e309",
                 "1e-320", "0x10", "", " ", " 2 ", "\u0663", "\uff15\uff10", "1_000", "50abc",
                 "+5", "1,5", "1 2 3", "--1", ".", "e5", "1e", "${ratio}", "$(arg r)",
                 "9" * 400, "1e308", "-1e308", "1e-308", "5e-324", "1e200", "-1e-300",
                 "0.5", "-2", "3")
RENAMES = {
    "type": ("plugin", "Type", "typ"),
    "plugin": ("type", "plugins"),
    "mechanicalReduction": ("mechanical_reduction", "mechanicalreduction", "reduction"),
    "mechanical_reduction": ("mechanicalReduction", "mechanical-reduction"),
    "hardwareInterface": ("hardware_interface", "hardwareinterface"),
    "joint": ("actuator", "joints", "Joint"),
    "actuator": ("joint", "actuators"),
    "transmission": ("transmissions", "Transmission", "ros2_control"),
    "ros2_control": ("transmission", "ros2control"),
    "role": ("roles", "type"),
    "offset": ("Offset", "mechanicalReduction"),
}
TYPES = tuple(f"{prefix}{name}" for prefix in ("transmission_interface/", "")
              for name in ("SimpleTransmission", "DifferentialTransmission",
                           "FourBarLinkageTransmission", "SimpleTansmission")
              ) + ("pr2_mechanism_model/SimpleTransmission", "", " ", "${type}")
INTERFACES = ("hardware_interface/EffortJointInterface", "PositionJointInterface", "position",
              "velocity", "effort", "hardware_interface/NoSuchInterface", "", "${iface}")
ROLE_VALUES = ("joint1", "joint2", "actuator1", "actuator2", "joint3", "", " joint1", "JOINT1")
ROOT_TAGS = ("robot", "ros2_control", "transmission", "sdf", "joint", "{http://www.ros.org/wiki/xacro}robot")
WRAPPER_TAGS = ("group", "xacro_if", "robot", "transmission", "ros2_control", "joint")
XACRO = "http://www.ros.org/wiki/xacro"
XML_CHARACTERS = st.characters(exclude_categories=("Cs", "Cc"))
ENCODINGS = (b"utf-8", b"latin-1", b"utf-16", b"ascii", b"no-such-codec", b"ebcdic-cp-us", b"")


@dataclass(frozen=True)
class Seed:
    name: str
    data: bytes
    tree: etree._ElementTree | None  # None: not well-formed, only byte mutations apply

    @property
    def suffix(self) -> str:
        return ".urdf.xacro" if self.name.endswith(".xacro") else Path(self.name).suffix


@dataclass(frozen=True)
class FuzzDocument:
    seed: str
    suffix: str
    data: bytes
    steps: tuple[str, ...]
    transmission_names: tuple[str, ...]

    def __repr__(self) -> str:  # hypothesis prints this for a failing example
        return (f"FuzzDocument(seed={self.seed!r}, steps={self.steps!r}, "
                f"data={self.data[:2000]!r}{'...' if len(self.data) > 2000 else ''})")


def seed_paths() -> list[Path]:
    paths = sorted(p for p in FIXTURES.iterdir() if p.is_file())
    if CORPUS.is_dir():
        paths += sorted(p for p in CORPUS.iterdir() if p.is_file() and p.name != "MANIFEST.tsv")
    return paths


@functools.cache
def seeds() -> tuple[Seed, ...]:
    loaded = []
    for path in seed_paths():
        data = path.read_bytes()
        try:
            tree = parse_bytes(data, path.name)
        except InputError:
            tree = None
        loaded.append(Seed(path.name, data, tree))
    return tuple(loaded)


def _elements(root: etree._Element) -> list[etree._Element]:
    return [e for e in root.iter() if isinstance(e.tag, str)]


def _local(tag: str) -> str:
    return etree.QName(tag).localname


def _pick(draw, items: list):
    return items[draw(st.integers(0, len(items) - 1))]


def _pick_preferring(draw, elements: list[etree._Element], tags: tuple[str, ...]):
    preferred = [e for e in elements if _local(e.tag) in tags]
    if preferred and draw(st.booleans()):
        return _pick(draw, preferred)
    return _pick(draw, elements)


def _detach(element: etree._Element) -> None:
    """Remove an element, keeping its tail text in the document."""
    parent = element.getparent()
    tail = element.tail
    previous = element.getprevious()
    parent.remove(element)
    if tail and tail.strip():
        if previous is not None:
            previous.tail = (previous.tail or "") + tail
        else:
            parent.text = (parent.text or "") + tail


def delete_element(draw, root: etree._Element) -> str:
    candidates = [e for e in _elements(root) if e is not root]
    if not candidates:
        return "delete: nothing"
    victim = _pick_preferring(draw, candidates, (*MEMBER_TAGS, *NUMERIC_TAGS, "type", "plugin"))
    _detach(victim)
    return f"delete <{_local(victim.tag)}>"


def duplicate_element(draw, root: etree._Element) -> str:
    candidates = [e for e in _elements(root) if e is not root]
    if not candidates:
        return "duplicate: nothing"
    original = _pick_preferring(draw, candidates, MEMBER_TAGS)
    original.addnext(copy.deepcopy(original))
    return f"duplicate <{_local(original.tag)}>"


def swap_attribute_values(draw, root: etree._Element) -> str:
    pairs = [(e, name) for e in _elements(root) for name in e.attrib]
    if len(pairs) < 2:
        return "swap: nothing"
    (first, a), (second, b) = _pick(draw, pairs), _pick(draw, pairs)
    first_value, second_value = first.get(a), second.get(b)
    first.set(a, second_value)
    second.set(b, first_value)
    return f"swap {a}={first_value!r} with {b}={second_value!r}"


def nasty_number(draw) -> str:
    return draw(st.one_of(st.sampled_from(NASTY_NUMBERS), st.text(XML_CHARACTERS, max_size=6),
                          st.floats().map(repr)))


def numeric_text(draw, root: etree._Element) -> str:
    elements = _elements(root)
    texts = [e for e in elements if _local(e.tag) in NUMERIC_TAGS]
    attributes = [(e, a) for e in elements for a in e.attrib if a in NUMERIC_ATTRIBUTES]
    value = nasty_number(draw)
    if texts and (not attributes or draw(st.booleans())):
        target = _pick(draw, texts)
        target.text = value
        return f"<{_local(target.tag)}> text {value!r}"
    if attributes:
        element, attribute = _pick(draw, attributes)
        element.set(attribute, value)
        return f"<{_local(element.tag)} {attribute}={value!r}>"
    return "numeric: nothing"


def rename(draw, root: etree._Element) -> str:
    elements = _elements(root)
    renamable = [e for e in elements if _local(e.tag) in RENAMES and e is not root]
    with_role = [e for e in elements if "role" in e.attrib or "name" in e.attrib]
    choice = draw(st.integers(0, 3))
    if choice == 0 and renamable:
        element = _pick(draw, renamable)
        old = _local(element.tag)
        element.tag = draw(st.sampled_from(RENAMES[old]))
        return f"rename <{old}> to <{element.tag}>"
    if choice == 1 and with_role:
        element = _pick(draw, with_role)
        attribute = "role" if "role" in element.attrib else "name"
        del element.attrib[attribute]
        return f"remove {attribute}= from <{_local(element.tag)}>"
    if choice == 2 and with_role:
        element = _pick(draw, with_role)
        attribute = "role" if "role" in element.attrib else "name"
        names = [e.get("name") for e in elements if e.get("name")]
        value = draw(st.sampled_from([*ROLE_VALUES, *names[:20], "\u00e9l\u00e8ve", "a b"]))
        element.set(attribute, value)
        return f"set {attribute}={value!r} on <{_local(element.tag)}>"
    element = _pick(draw, [e for e in elements if e is not root] or elements)
    old = _local(element.tag)
    misspelt = draw(st.sampled_from([old[:-1] or "x", old.upper(), old + "s", old[0] + old]))
    element.tag = misspelt
    return f"misspell <{old}> as <{misspelt}>"


def retype(draw, root: etree._Element) -> str:
    """A new transmission type or hardware interface: other maths for the same members."""
    elements = _elements(root)
    typed = [e for e in elements if _local(e.tag) in ("type", "plugin", "hardwareInterface")]
    with_attribute = [e for e in elements if _local(e.tag) == "transmission" and "type" in e.attrib]
    if not typed and not with_attribute:
        return "retype: nothing"
    element = _pick(draw, typed + with_attribute)
    if _local(element.tag) == "hardwareInterface":
        value = draw(st.sampled_from(INTERFACES))
        element.text = value
        return f"interface {value!r}"
    value = draw(st.sampled_from(TYPES))
    if element in with_attribute:
        element.set("type", value)
    else:
        element.text = value
    return f"type {value!r}"


def move_element(draw, root: etree._Element) -> str:
    elements = _elements(root)
    movable = [e for e in elements if e is not root]
    if not movable:
        return "move: nothing"
    element = _pick_preferring(draw, movable, (*MEMBER_TAGS, *NUMERIC_TAGS))
    inside = set(element.iter())
    parents = [e for e in elements if e not in inside]
    parent = _pick_preferring(draw, parents, MEMBER_TAGS)
    _detach(element)
    parent.insert(draw(st.integers(0, len(parent))), element)
    return f"move <{_local(element.tag)}> into <{_local(parent.tag)}>"


def deep_nesting(draw, root: etree._Element) -> str:
    candidates = [e for e in _elements(root) if e is not root]
    if not candidates:
        return "nest: nothing"
    element = _pick_preferring(draw, candidates, ("transmission", "ros2_control"))
    depth = draw(st.one_of(st.integers(1, 40), st.integers(200, 300), st.integers(300, 3000)))
    tag = draw(st.sampled_from(WRAPPER_TAGS))
    parent = element.getparent()
    index = parent.index(element)
    outer = current = etree.Element(tag)
    for _ in range(depth - 1):
        current = etree.SubElement(current, tag)
    parent.remove(element)
    current.append(element)
    parent.insert(index, outer)
    return f"nest <{_local(element.tag)}> in {depth} <{tag}>"


def insert_comment(draw, root: etree._Element) -> str:
    element = _pick_preferring(draw, _elements(root), MEMBER_TAGS)
    text = draw(st.sampled_from([" note ", " txtool: disable-next-line TX106 ",
                                 " txtool: disable-file ", "", "-"]))
    comment = etree.Comment(text) if text != "-" else etree.Comment(" - ")
    element.insert(draw(st.integers(0, len(element))), comment)
    return f"comment {text!r} in <{_local(element.tag)}>"


def xacro_wrap(draw, root: etree._Element) -> str:
    """Put an element inside a xacro macro or conditional, and a ``${...}`` into a name."""
    candidates = [e for e in _elements(root) if e is not root]
    if not candidates:
        return "xacro: nothing"
    element = _pick_preferring(draw, candidates, ("transmission", "ros2_control"))
    kind = draw(st.sampled_from(["macro", "if", "unless"]))
    wrapper = etree.Element(f"{{{XACRO}}}{kind}", nsmap={"xacro": XACRO})
    if kind == "macro":
        wrapper.set("name", "m")
        wrapper.set("params", "prefix")
    else:
        wrapper.set("value", draw(st.sampled_from(["true", "false", "${flag}", "$(arg a)"])))
    element.addprevious(wrapper)
    wrapper.append(element)
    if element.get("name") is not None and draw(st.booleans()):
        element.set("name", "${prefix}" + element.get("name"))
    return f"xacro:{kind} around <{_local(element.tag)}>"


def change_root(draw, tree: etree._ElementTree) -> tuple[etree._ElementTree, str]:
    root = tree.getroot()
    if draw(st.booleans()):
        root.tag = draw(st.sampled_from(ROOT_TAGS))
        return tree, f"root tag {root.tag}"
    members = [e for e in _elements(root) if _local(e.tag) in ("transmission", "ros2_control")]
    if not members:
        return tree, "fragment: nothing"
    fragment = _pick(draw, members)
    return etree.ElementTree(copy.deepcopy(fragment)), f"fragment <{_local(fragment.tag)}>"


TreeMutation = Callable[..., str]
TREE_MUTATIONS: tuple[TreeMutation, ...] = (
    delete_element, duplicate_element, swap_attribute_values, numeric_text, rename,
    move_element, deep_nesting, retype, insert_comment, xacro_wrap,
)


def truncate(draw, data: bytes) -> tuple[bytes, str]:
    cut = draw(st.integers(0, max(len(data) - 1, 0)))
    return data[:cut], f"truncate at {cut}"


def insert_bytes(draw, data: bytes) -> tuple[bytes, str]:
    at = draw(st.integers(0, len(data)))
    junk = draw(st.one_of(
        st.binary(min_size=1, max_size=8),
        st.sampled_from([b"<", b">", b"&", b"&amp;", b"&#0;", b"&#x110000;", b"]]>", b"\xff\xfe",
                         b"<!--", b"\x00", b"<![CDATA[", b"<?xml version='1.0'?>",
                         b"<!DOCTYPE r [<!ENTITY e 'x'>]>", b"&e;"]),
    ))
    return data[:at] + junk + data[at:], f"insert {junk!r} at {at}"


def misplaced_declaration(draw, data: bytes) -> tuple[bytes, str]:
    encoding = draw(st.sampled_from(ENCODINGS))
    declaration = b'<?xml version="1.0" encoding="' + encoding + b'"?>\n'
    if draw(st.booleans()):
        declaration = b"<!-- licence -->\n" + declaration
    body = data.split(b"?>", 1)[1] if data.lstrip().startswith(b"<?xml") else data
    return declaration + body, f"declaration {encoding!r}"


def line_endings(draw, data: bytes) -> tuple[bytes, str]:
    style = draw(st.sampled_from(["crlf", "cr", "one line", "tabs"]))
    lines = data.replace(b"\r\n", b"\n").split(b"\n")
    if style == "tabs":
        return b"\n".join(line.replace(b"  ", b"\t") for line in lines), style
    joiner = {"crlf": b"\r\n", "cr": b"\r", "one line": b""}[style]
    return joiner.join(lines), style


BYTE_MUTATIONS = (truncate, insert_bytes, misplaced_declaration, line_endings)


@st.composite
def documents(draw) -> FuzzDocument:
    seed = draw(st.sampled_from(seeds()))
    steps: list[str] = []
    data = seed.data
    names: tuple[str, ...] = ()
    if seed.tree is not None:
        tree = copy.deepcopy(seed.tree)
        for _ in range(draw(st.integers(0, 3))):
            mutation = draw(st.sampled_from(TREE_MUTATIONS))
            steps.append(mutation(draw, tree.getroot()))
        if draw(st.integers(0, 9)) == 0:
            tree, step = change_root(draw, tree)
            steps.append(step)
        names = tuple(e.get("name", "") for e in tree.getroot().iter("transmission"))
        data = etree.tostring(tree, encoding="utf-8",
                              xml_declaration=seed.data.lstrip().startswith(b"<?xml"))
    if seed.tree is None or draw(st.integers(0, 3)) == 0:
        mutation = draw(st.sampled_from(BYTE_MUTATIONS))
        data, step = mutation(draw, data)
        steps.append(step)
    return FuzzDocument(seed.name, seed.suffix, data, tuple(steps), names)


MAP_NUMBERS = ("0", "1.5", "-2", "1e300", "-1e308", "5e-324", " 2 ", "-0", "3.25")
MAP_JUNK = ("nan", "inf,1", "1e309", "abc", "", ",", "1,2,3", "0x10", "\u0663", "1;2")

COMMANDS: dict[str, tuple[str, ...]] = {
    "show": ("show",),
    "show-json": ("show", "--format", "json"),
    "show-limits": ("show", "--actuator-limits", "--format", "json"),
    "show-effective": ("show", "--effective"),
    "validate": ("validate",),
    "validate-json": ("validate", "--format", "json"),
    "convert-ros1": ("convert", "--to", "ros1"),
    "convert-ros2-p1": ("convert", "--to", "ros2-p1"),
    "convert-ros2-p2": ("convert", "--to", "ros2-p2"),
    "convert-bb": ("convert", "--to", "bb"),
    "roundtrip": ("roundtrip",),
    "roundtrip-json": ("roundtrip", "--format", "json"),
    "roundtrip-against-json": ("roundtrip", "--format", "json", "--against"),
    "migrate-diff": ("migrate", "--diff"),
    "migrate-diff-to": ("migrate", "--diff", "--allow-lossy", "--to"),
    "map": ("map",),
    # Standard input ("-"), reported under the --stdin-filename given.
    "show-stdin": ("show", "--format", "json", "--stdin-filename"),
    "validate-stdin": ("validate", "--format", "json", "--stdin-filename"),
    "convert-stdin": ("convert", "--to", "ros2-p2", "--stdin-filename"),
}


@st.composite
def extra_arguments(draw, command: str, document: FuzzDocument) -> tuple[str, ...]:
    """The arguments after the file: a target dialect for migrate, a map request for map."""
    if command == "migrate-diff-to":
        return (draw(st.sampled_from(["ros1", "ros2-p1", "ros2-p2"])),)
    if command != "map":
        return ()
    names = list(document.transmission_names[:8])
    if not names or draw(st.integers(0, 4)) == 0:
        names = ["no_such_trans", ""]
    arguments = ["-t", draw(st.sampled_from(names)),
                 "--to", draw(st.sampled_from(["actuator", "joint"]))]
    # Mostly one or two plain numbers, the counts a simple or coupled transmission takes.
    numbers = st.lists(st.sampled_from(MAP_NUMBERS), min_size=1, max_size=2).map(",".join)
    quantities = draw(st.sets(st.sampled_from(["--position", "--velocity", "--effort"]),
                              max_size=3).map(sorted))
    for option in quantities:
        junk = draw(st.integers(0, 5)) == 0
        arguments += [option, draw(st.sampled_from(MAP_JUNK) if junk else numbers)]
    if draw(st.booleans()):
        arguments += ["--effort-convention", "ros1"]
    if draw(st.booleans()):
        arguments += ["--format", "json"]
    return tuple(arguments)


@dataclass(frozen=True)
class Invocation:
    path: str  # the document's path, or the name it is reported under when read from stdin
    argv: list[str]
    stdin: bytes | None = None


def write_inputs(folder: str, command: str, document: FuzzDocument,
                 extra: tuple[str, ...]) -> Invocation:
    """Write the document (and, for ``--against``, its seed) into ``folder``; the command line
    that runs ``command`` on it."""
    path = str(Path(folder) / ("robot" + document.suffix))
    name, *options = COMMANDS[command]
    if options[-1:] == ["--stdin-filename"]:
        return Invocation(path, [name, "-", *options, path, *extra], document.data)
    Path(path).write_bytes(document.data)
    if options[-1:] == ["--against"]:
        seed = next(s for s in seeds() if s.name == document.seed)
        other = Path(folder) / ("seed" + document.suffix)
        other.write_bytes(seed.data)
        extra = (str(other), *extra)
    return Invocation(path, [name, path, *options, *extra])


def run_failure(command: str, path: str, result: Result) -> str | None:
    """What is wrong with one in-process run (``None``: it ended the way txtool promises).

    Every run exits 0, 1 or 2 with a message and no traceback; exit 2 is a ``txtool: PATH`` line
    on stderr naming the input; ``validate`` reports a file it could read as findings (exit 0 or 1), never exit 2;
    JSON output parses, strictly (no NaN); a conversion writes well-formed XML.
    """
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        return f"crash: {type(result.exception).__name__}: {result.exception}"
    if result.exit_code not in (0, 1, 2):
        return f"exit code {result.exit_code}"
    output = result.stdout + result.stderr
    if "Traceback" in output:
        return "a traceback in the output"
    if not output.strip():
        return f"exit {result.exit_code} without a message"
    folder = str(Path(path).parent)  # the document, or the seed it is compared --against
    if result.exit_code == 2 and not any(
        line.startswith(f"txtool: {folder}") for line in result.stderr.splitlines()
    ):
        return f"exit 2 without naming the input: {result.stderr[:300]!r}"
    if command.startswith("validate") and result.exit_code == 2:
        return f"validate exit 2 on a readable file: {result.stderr[:300]!r}"
    if result.exit_code == 0 and command.startswith(("convert-ros", "convert-stdin")):
        try:
            etree.fromstring(result.stdout_bytes, safe_parser())
        except etree.XMLSyntaxError as exc:
            return f"convert wrote malformed XML: {exc}"
    if result.exit_code in (0, 1) and "json" in command:
        try:
            json.loads(result.stdout, parse_constant=_reject_constant)
        except ValueError as exc:
            return f"invalid JSON output: {exc}"
    return None


def _reject_constant(name: str) -> None:
    raise ValueError(f"{name} is not JSON")
