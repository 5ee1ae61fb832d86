"""Property: every conversion cycle is the identity on the canonical model, bit for bit."""

from __future__ import annotations

import json
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree
from pydantic import ValidationError

from txtool import dialects
from txtool.dialects.read import read_source
from txtool.io.xmlio import Source, parse_bytes
from txtool.model.core import (
    Member,
    Number,
    Transmission,
    dump,
    pydantic_dump,
    standard_type,
    validate,
)
from txtool.model.numbers import format_float
from txtool.transform.convert import convert_source
from txtool.transform.roundtrip import cycles_from
from txtool.views.tables import view

reductions = st.one_of(
    st.floats(min_value=1e-300, max_value=1e300),
    st.floats(min_value=-1e300, max_value=-1e-300),
    st.sampled_from([1.0, -1.0, 2.2250738585072014e-308, 1e-12, 1e15, -50.0, 325.949]),
)
# std::stod refuses subnormal values (glibc reports the underflow): ros_control cannot load them
offsets = st.one_of(st.floats(allow_nan=False, allow_infinity=False, allow_subnormal=False,
                              width=64),
                    st.sampled_from([0.0, 0.5, -math.pi]))
interfaces = st.sampled_from(["position", "velocity", "effort"])


def number(value: float) -> Number:
    return Number(value=value, text=format_float(value))


# Names whose sorted order differs from their natural order ("joint_10" < "joint_2").
JOINT_NAMES = ["elbow", "joint_10", "joint_2", "Wrist", "a", "z_roll"]
ACTUATOR_NAMES = ["m10", "m2", "motor_b", "motor_a", "Z"]


@st.composite
def transmissions(draw) -> Transmission:
    """Names, XML order and roles drawn independently (ros2_control binds by XML order, sorts
    handles by name, and ROS 1 sorts by role: every combination of the three must survive)."""
    kind = draw(st.sampled_from(["simple", "differential", "four_bar"]))
    dialect = draw(st.sampled_from(["ros1", "ros2-p1", "ros2-p2"]))
    n = 1 if kind == "simple" else 2
    command = draw(interfaces)
    joint_names = draw(st.lists(st.sampled_from(JOINT_NAMES), min_size=n, max_size=n,
                                unique=True))
    actuator_names = draw(st.lists(st.sampled_from(ACTUATOR_NAMES), min_size=n, max_size=n,
                                   unique=True))
    joint_roles = draw(st.permutations([f"joint{i + 1}" for i in range(n)]))
    actuator_roles = draw(st.permutations([f"actuator{i + 1}" for i in range(n)]))
    joints, actuators = [], []
    for i in range(n):
        joint_reduction = None if kind == "simple" and dialect == "ros1" else number(draw(reductions))
        if kind != "simple" and dialect == "ros1" and draw(st.booleans()):
            joint_reduction = None  # optional in ROS 1 coupled transmissions
        ros1_interface = f"hardware_interface/{command.capitalize()}JointInterface"
        joints.append(Member(
            name=joint_names[i], role=joint_roles[i] if (n == 2 or dialect != "ros1") else None,
            mechanical_reduction=joint_reduction,
            offset=number(draw(offsets)) if draw(st.booleans()) else None,
            interfaces=(ros1_interface,) if dialect == "ros1" else (command,),
            state_interfaces=() if dialect == "ros1" else ("position", "velocity"),
        ))
        actuator_reduction = number(draw(reductions))
        if kind == "simple" and dialect != "ros1":
            actuator_reduction = None  # ros2_control ignores it
        actuators.append(Member(
            name=actuator_names[i],
            role=actuator_roles[i] if (n == 2 or dialect != "ros1") else None,
            mechanical_reduction=actuator_reduction,
        ))
    return Transmission(name="t", type=standard_type(kind), kind=kind, joints=tuple(joints),
                        actuators=tuple(actuators), dialect=dialect)


def document(t: Transmission) -> bytes:
    root = etree.Element("robot", name="r")
    parent = root
    if t.dialect != "ros1":
        parent = etree.SubElement(root, "ros2_control", name="hw", type="system")
        for joint in t.joints:
            declared = etree.SubElement(parent, "joint", name=joint.name)
            for name in joint.interfaces:
                etree.SubElement(declared, "command_interface", name=name)
            for name in joint.state_interfaces:
                etree.SubElement(declared, "state_interface", name=name)
    parent.append(dialects.build(t, t.dialect))
    return etree.tostring(root)


def read_one(data: bytes) -> Transmission:
    source = Source("t.urdf", data, parse_bytes(data, "t.urdf"))
    (found,) = [f for f in read_source(source)]
    return found.transmission


def orders_agree(t: Transmission) -> bool:
    """XML order is name order (ros2_control's std::set) and role order (ROS 1's sort)."""
    return all(
        [m.name for m in members] == sorted(m.name for m in members)
        and (not all(m.role for m in members)
             or [m.role for m in members] == sorted(m.role for m in members))
        for members in (t.joints, t.actuators)
    )


@settings(max_examples=150, deadline=None)
@given(transmissions())
def test_every_cycle_is_the_identity(t):
    """Identity bit for bit. Where XML, name and role order disagree (TX401), the loaders bind
    differently: convert may refuse a step, or write ROS 2 in role order (members reordered)."""
    data = document(t)
    original = read_one(data)
    for cycle in cycles_from(original.dialect):
        current = data
        for step in cycle[1:]:
            result = convert_source(Source("t.urdf", current, parse_bytes(current, "t")), step)
            if result.losses:
                assert not orders_agree(original), (cycle, result.losses)
                break
            current = result.data
        else:
            back = read_one(current)
            assert back.dialect == original.dialect
            assert view(back) == view(original), cycle
            if orders_agree(original):
                assert repr(view(back)) == repr(view(original)), cycle
            by_name = {m.name: m for m in back.joints + back.actuators}
            for before in original.joints + original.actuators:
                after = by_name[before.name]
                for field in ("mechanical_reduction", "offset"):
                    a, b = getattr(before, field), getattr(after, field)
                    if a is not None and b is not None:
                        assert a.value.hex() == b.value.hex()


@settings(max_examples=100, deadline=None)
@given(transmissions())
def test_the_json_of_show_is_the_model_through_its_schema(t):
    """``show --format json`` data validates back into the very transmission it came from."""
    read = read_one(document(t))
    data = json.loads(json.dumps(dump(read)))  # what a user of the JSON gets
    assert validate(Transmission, data) == read


@settings(max_examples=100, deadline=None)
@given(transmissions())
def test_the_plain_json_writer_writes_what_pydantic_writes(t):
    """``dump`` skips pydantic's serializer for speed; its JSON text is pydantic's, byte for
    byte (NaN and infinities as null, tuples as lists, fields in declaration order)."""
    read = read_one(document(t))
    assert json.dumps(dump(read)) == json.dumps(pydantic_dump(read))


def test_the_schema_refuses_what_is_not_a_transmission():
    data = dump(read_one(document(number_transmission())))
    data["kind"] = "planetary"
    with pytest.raises(ValidationError):
        validate(Transmission, data)
    del data["kind"]
    data["gear"] = 3
    with pytest.raises(ValidationError, match="gear"):
        validate(Transmission, data)


def number_transmission() -> Transmission:
    return Transmission(
        name="t", type=standard_type("simple"), kind="simple", dialect="ros1",
        joints=(Member(name="j", interfaces=("hardware_interface/EffortJointInterface",)),),
        actuators=(Member(name="m", mechanical_reduction=number(50.0)),),
    )
