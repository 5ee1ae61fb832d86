"""Transmissions converted once per shape (txtool.transform.repeated.renamings) convert as each one alone.

Each document repeats a few transmissions under names drawn from a small pool, so that names
collide, members share joints, and the names the conversion writes itself (``actuator1``,
``*``) appear as written names; some stand in a ``<ros2_control>`` that declares their joints,
some carry comments, xacro expressions or children no loader reads. Converting it with the
memo must give what converting without it gives: the bytes and every message.
"""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree

from txtool.io.xmlio import Source, parse_bytes
from txtool.transform import convert as convert_module
from txtool.transform.convert import convert_source
from txtool.transform.repeated.renamings import renaming_of

NAMES = ("a", "b", "j1", "actuator1", "*", "joint1", "z", "A", "\u00fc")
REDUCTIONS = ("50", "-2", "${ratio}", "1.0", "abc")
TARGETS = ("ros1", "ros2-p1", "ros2-p2")


@st.composite
def ros1_simple(draw) -> str:
    name, joint, actuator = (draw(st.sampled_from(NAMES)) for _ in range(3))
    reduction = draw(st.sampled_from(REDUCTIONS))
    offset = draw(st.sampled_from(["", "<offset>0.5</offset>"]))
    extra = draw(st.sampled_from(["", "<!-- note -->", "<unknown_tag/>"]))
    return (f'<transmission name="{name}">{extra}'
            "<type>transmission_interface/SimpleTransmission</type>"
            f'<joint name="{joint}">{offset}<hardwareInterface>'
            "hardware_interface/EffortJointInterface</hardwareInterface></joint>"
            f'<actuator name="{actuator}"><mechanicalReduction>{reduction}'
            "</mechanicalReduction></actuator></transmission>")


@st.composite
def ros1_differential(draw) -> str:
    name, *members = (draw(st.sampled_from(NAMES)) for _ in range(5))
    roles = draw(st.sampled_from([("joint1", "joint2"), ("joint2", "joint1")]))
    joints = "".join(f'<joint name="{m}"><role>{r}</role><hardwareInterface>'
                     "hardware_interface/PositionJointInterface</hardwareInterface></joint>"
                     for m, r in zip(members[:2], roles, strict=True))
    actuators = "".join(f'<actuator name="{m}"><role>actuator{i + 1}</role>'
                        "<mechanicalReduction>10</mechanicalReduction></actuator>"
                        for i, m in enumerate(members[2:4]))
    return (f'<transmission name="{name}">'
            "<type>transmission_interface/DifferentialTransmission</type>"
            f"{joints}{actuators}</transmission>")


@st.composite
def ros2_simple(draw) -> str:
    name, joint, actuator = (draw(st.sampled_from(NAMES)) for _ in range(3))
    role = draw(st.sampled_from(['role="joint1"', "", "<role>joint1</role>"]))
    opening, inner = (f"<joint name=\"{joint}\" {role}>", "") if "=" in role else (
        f'<joint name="{joint}">', role)
    return (f'<transmission name="{name}"><plugin>transmission_interface/SimpleTransmission'
            f"</plugin>{opening}{inner}<mechanical_reduction>"
            f"{draw(st.sampled_from(REDUCTIONS))}</mechanical_reduction></joint>"
            f'<actuator name="{actuator}"/></transmission>')


@st.composite
def documents(draw) -> bytes:
    shapes = draw(st.lists(st.one_of(ros1_simple(), ros1_differential(), ros2_simple()),
                           min_size=1, max_size=3))
    body = [draw(st.sampled_from(shapes)) for _ in range(draw(st.integers(2, 8)))]
    if draw(st.booleans()):  # a block that already declares some of the joints
        declared = draw(st.lists(st.sampled_from(NAMES), max_size=3, unique=True))
        joints = "".join(f'\n    <joint name="{j}"><command_interface name="effort"/>'
                         '<state_interface name="position"/></joint>' for j in declared)
        inside = [draw(st.sampled_from(shapes)) for _ in range(draw(st.integers(0, 2)))]
        body.insert(draw(st.integers(0, len(body))),
                    '<ros2_control name="hw" type="system"><hardware><plugin>x/Y</plugin>'
                    f"</hardware>{joints}{''.join(inside)}\n  </ros2_control>")
    if draw(st.booleans()):  # one inside a xacro macro
        body.append('<xacro:macro name="m" params="ratio">'
                    f"{draw(st.sampled_from(shapes))}</xacro:macro>")
    separator = draw(st.sampled_from(["\n  ", "\n\n  ", ""]))
    return ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n  '
            + separator.join(body) + "\n</robot>\n").encode()


def converted(data: bytes, target: str, *, memo: bool = True) -> tuple:
    """What converting ``data`` gives; without ``memo`` every transmission is converted in
    full, as if none had a key."""
    result = convert_source(Source("<doc>", data, parse_bytes(data, "<doc>")), target,
                            repeats=memo)
    return (result.data, result.losses, result.notes, result.warnings, result.converted,
            result.found, result.already)


@settings(max_examples=150, deadline=None)
@given(documents(), st.sampled_from(TARGETS))
def test_a_document_converts_as_without_the_memo(data, target):
    fast = converted(data, target)
    assert fast == converted(data, target, memo=False)
    if target != "ros1":  # and the result converts back as without the memo
        assert converted(fast[0], "ros1") == converted(fast[0], "ros1", memo=False)


def test_thousands_of_repeats_give_the_messages_of_each():
    """A lossy shape repeated: each copy says its loss, under its own name."""
    data = ('<robot name="r">\n' + "\n".join(
        f'  <transmission name="t{i}"><type>transmission_interface/SimpleTransmission</type>'
        f'<joint name="j{i}"><mechanicalReduction>3</mechanicalReduction><hardwareInterface>'
        "hardware_interface/EffortJointInterface</hardwareInterface></joint>"
        f'<actuator name="m{i}"><mechanicalReduction>2</mechanicalReduction></actuator>'
        "</transmission>" for i in range(300)) + "\n</robot>\n").encode()
    result = convert_source(Source("<doc>", data, parse_bytes(data, "<doc>")), "ros2-p2")
    assert result.converted == 300
    assert [loss.split(":")[0] for loss in result.losses] == [f"joint 'j{i}'" for i in range(300)]


def test_names_are_keyed_in_tags_only():
    """A text that reads like a name attribute is part of the shape, not a name."""
    first = parse_bytes(b'<transmission name="a"><type>name="x"</type></transmission>', "<d>")
    second = parse_bytes(b'<transmission name="b"><type>name="y"</type></transmission>', "<d>")
    one, two = renaming_of(first.getroot()), renaming_of(second.getroot())
    assert one is not None and two is not None
    assert one.names == ("a",) and two.names == ("b",)
    assert one.key != two.key


def test_what_a_name_cannot_key_is_converted_in_full():
    commented = parse_bytes(b'<transmission name="a"><!-- name="a" --></transmission>', "<d>")
    escaped = parse_bytes(b'<transmission name="a&amp;b"/>', "<d>")
    assert renaming_of(commented.getroot()) is None
    assert renaming_of(escaped.getroot()) is None


def test_a_name_not_in_ascii_is_not_keyed_nor_matched():
    """Its order is kept out of the key (as for an escaped one); a text that is not ASCII
    elsewhere is part of the shape."""
    from txtool.dialects.read import read_transmission
    from txtool.transform.repeated.renamings import Follower, Memo

    def element(name: str, joint: str) -> etree._Element:
        return parse_bytes(f'<transmission name="{name}"><type>\u00e9</type><joint name="{joint}"/>'
                           "</transmission>".encode(), "<d>").getroot()

    assert renaming_of(element("\u00fc", "j")) is None
    memo = Memo()
    first = element("x", "y")
    renaming = memo.keyed(first)
    assert renaming is not None and renaming.names == ("x", "y")
    t = read_transmission(first, None)
    memo.learn(renaming, t, t, clean=True)
    assert isinstance(memo.keyed(element("v", "w")), Follower)
    assert memo.keyed(element("b", "\u00fc")) is None


def test_the_order_of_names_is_part_of_the_key():
    """ros2_control orders handles by name: names that sort otherwise make another key."""
    def key(joint: str, actuator: str):
        text = f'<transmission name="t"><joint name="{joint}"/><actuator name="{actuator}"/>'
        renaming = renaming_of(parse_bytes((text + "</transmission>").encode(), "<d>").getroot())
        assert renaming is not None
        return renaming.key

    assert key("j", "m") == key("k", "n")
    assert key("j", "m") != key("n", "k")
    assert key("j", "m") != key("actuator1", "m")


def test_a_template_whose_text_would_not_parse_back_is_copied_as_an_element():
    """An element built with an empty text (``<offset></offset>``) parses back without one:
    such a template is not written as text, and the block comes out as built one by one."""
    from txtool.dialects.read import read_transmission
    from txtool.dialects.translate import translate
    from txtool.transform.placement.placer import Placer

    data = ('<robot name="r">\n' + "\n".join(
        f'  <transmission name="t{i}"><type>transmission_interface/SimpleTransmission</type>'
        f'<joint name="j{i}"><offset></offset></joint><actuator name="m{i}"/></transmission>'
        for i in range(3)) + "\n</robot>\n").encode()

    def placed(keyed: bool) -> bytes:
        tree = parse_bytes(data, "<doc>")
        placer = Placer(tree.getroot(), "x/Y")
        for element in list(tree.getroot()):
            t = translate(read_transmission(element, None), "ros2-p2").transmission
            placer.place(element, t, {}, renaming_of(element) if keyed else None)
        placer.finish()
        return etree.tostring(tree)

    assert b"<offset></offset>" in placed(keyed=True)
    assert placed(keyed=True) == placed(keyed=False)


@settings(max_examples=100, deadline=None)
@given(documents())
def test_a_memo_keys_each_element_as_renaming_of_does(data):
    """Matching an element against the records of its skeleton gives its key itself."""
    from txtool.dialects.read import read_transmission
    from txtool.transform.repeated.renamings import Follower, Memo

    memo = Memo()
    for element in parse_bytes(data, "<doc>").getroot().iter("{*}transmission"):
        keyed = memo.keyed(element)
        renaming = keyed.renaming() if isinstance(keyed, Follower) else keyed
        assert renaming == renaming_of(element)
        if isinstance(keyed, Follower):
            assert keyed.record is memo.records[renaming.key]
            assert keyed.translated().name == keyed.name
        elif renaming is not None:
            assert memo.records.get(renaming.key) is None
            t = read_transmission(element, None)
            memo.learn(renaming, t, t, clean=True)


@st.composite
def repeated_documents(draw) -> bytes:
    """Many transmissions of a few shapes, mostly under names of their own (the block
    generated for them is then written as text, :mod:`txtool.transform.repeated.block_text`), some under
    a name of the pool: colliding, shared or literal."""
    shapes = draw(st.lists(st.sampled_from([ros1_simple(), ros1_differential()]),
                           min_size=1, max_size=2))
    templates = [draw(shape) for shape in shapes]
    body = []
    for i in range(draw(st.integers(2, 12))):
        text = templates[draw(st.integers(0, len(templates) - 1))]
        for name in NAMES:  # names of their own, unless drawn from the pool
            if draw(st.integers(0, 9)):
                text = text.replace(f'name="{name}"', f'name="{name}_{i}"')
        body.append(text)
    if draw(st.booleans()):
        body.insert(draw(st.integers(0, len(body))), '<link name="l"/>')
    if draw(st.booleans()):
        body.append('<ros2_control name="hw" type="system"><hardware><plugin>x/Y</plugin>'
                    '</hardware><joint name="a_1"><command_interface name="effort"/></joint>'
                    "</ros2_control>")
    separator = draw(st.sampled_from(["\n  ", "\n\n  ", "", "\n\t"]))
    text = separator.join(body)
    if draw(st.booleans()):
        text = text.replace("><", ">\n    <")
    return ('<robot name="r">\n  ' + text + "\n</robot>\n").encode()


@settings(max_examples=150, deadline=None)
@given(repeated_documents(), st.sampled_from(["ros2-p1", "ros2-p2"]))
def test_a_block_written_as_text_is_what_converting_in_full_gives(data, target):
    assert converted(data, target) == converted(data, target, memo=False)


def chain(count: int, reduction: str = "50") -> bytes:
    return ('<robot name="r">\n' + "\n".join(
        f'  <transmission name="t{i}"><type>transmission_interface/SimpleTransmission</type>'
        f'<joint name="j{i}"><hardwareInterface>hardware_interface/EffortJointInterface'
        f'</hardwareInterface></joint><actuator name="m{i}"><mechanicalReduction>{reduction}'
        "</mechanicalReduction></actuator></transmission>" for i in range(count))
        + "\n</robot>\n").encode()


def test_a_chain_is_written_as_text(monkeypatch):
    """Repeats with names of their own: the generated block is never parsed."""
    from txtool.transform.placement import placer

    parsed = []
    monkeypatch.setattr(placer, "parse_children",
                        lambda pieces: parsed.append(1) or list(etree.fromstring(
                            b"<x>" + b"".join(pieces) + b"</x>")))
    data = chain(50)
    fast = converted(data, "ros2-p2")
    assert parsed == []
    assert fast == converted(data, "ros2-p2", memo=False)
    assert fast[0].count(b"<transmission ") == 50 and fast[4] == 50


def test_a_written_block_whose_marker_the_document_holds_is_parsed(monkeypatch):
    """The marker found other than once (here: a comment of the document reads the same):
    the block is parsed into the tree and written as a whole, with the same result."""
    from txtool.transform.repeated import block_text as written

    data = chain(5).replace(b"</robot>", b"<!--txtool-block-x-->\n</robot>")
    monkeypatch.setattr(written, "marker", lambda: etree.Comment("txtool-block-x"))
    assert converted(data, "ros2-p2") == converted(data, "ros2-p2", memo=False)


def test_each_written_transmission_is_read_back_when_its_shape_did_not_come_back(monkeypatch):
    """A judgement that finds a loss in every round trip: no shape comes back whole, so every
    transmission of the written block is read back on its own and judged, as in full."""
    monkeypatch.setattr(convert_module, "_lost", lambda a, b: {"offset": repr(b["offset"])})
    data = chain(6)
    fast = converted(data, "ros2-p2")
    assert fast == converted(data, "ros2-p2", memo=False)
    assert [loss.split(" did")[0] for loss in fast[1]] == [
        f"transmission 't{i}'" for i in range(6)]
