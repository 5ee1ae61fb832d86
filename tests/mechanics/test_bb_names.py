"""BB's names for URDF names: lib/bb/urdf/importer.ex @64ab268, atom_name/1 (:485-493) and the
joint renames of prepare/1 (:93-98, :117-173)."""

from __future__ import annotations

import re

from hypothesis import given
from hypothesis import strategies as st
from lxml import etree

from txtool.transform.bb.names import atom_name, elixir_atom, robot_names, unique_name


def test_atom_name_replaces_every_other_byte_and_guards_a_leading_digit() -> None:
    assert atom_name("weird-name.1") == "weird_name_1"
    assert atom_name("2nd joint") == "_2nd_joint"
    assert atom_name("HeadYaw") == "HeadYaw"
    assert atom_name("gelenk_ä") == "gelenk___"  # BB's regex sees the two UTF-8 bytes of ä


@given(st.text())
def test_atom_name_is_always_a_plain_atom(name: str) -> None:
    text = atom_name(name)
    assert text == "" or re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", text)
    assert elixir_atom(text) == (':""' if text == "" else ":" + text)


def test_elixir_atom_quotes_what_is_not_an_identifier() -> None:
    assert elixir_atom('a"b\\c') == ':"a\\"b\\\\c"'


def test_joints_are_renamed_as_bb_importer_renames_them() -> None:
    root = etree.fromstring("""<robot name="r">
      <link name="base"/><link name="arm"/><link name="arm_joint"/>
      <joint name="anchor" type="fixed"><parent link="world"/><child link="base"/></joint>
      <joint name="arm" type="revolute"><parent link="base"/><child link="arm"/></joint>
      <joint name="arm" type="revolute"><parent link="arm"/><child link="arm_joint"/></joint>
    </robot>""")
    names = robot_names(root)
    assert names.dropped == {"anchor": "world"}
    # 'arm' is a link, and 'arm_joint' too: the first joint becomes arm_joint_2
    assert names.joints == {"arm": "arm_joint_2"}
    assert [(j.name, j.bb_name) for j in names.urdf_joints] == [
        ("arm", "arm_joint_2"), ("arm", "arm_joint_3")]
    assert unique_name("arm_joint", {"arm_joint", "arm_joint_2"}) == "arm_joint_3"
