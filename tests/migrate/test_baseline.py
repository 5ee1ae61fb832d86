"""The baseline a conversion splices against, rebuilt from the converted document
(txtool.transform.serialized_before) instead of serialized before the tree changes, is the very
serialization of the document as parsed: on real robots, and on documents made to break the
rebuild (formatting, encodings, references, comments, namespaces, runs, names)."""

from __future__ import annotations

import codecs

import pytest

from tests.corpus import corpus_files, workspace_dir
from txtool.io.xmlio import InputError, Source, parse_bytes, serialize
from txtool.transform import serialized_before as baseline_module
from txtool.transform.convert import convert_source

TRANSMISSION = (
    '<transmission name="t{i}"><type>transmission_interface/SimpleTransmission</type>'
    '<joint name="j{i}"><hardwareInterface>hardware_interface/EffortJointInterface'
    '</hardwareInterface></joint><actuator name="m{i}"><mechanicalReduction>{n}'
    "</mechanicalReduction></actuator></transmission>")


def arm(count: int = 12, *, pretty: bool = False, head: str = '<robot name="arm">',
        gap: str = "\n  ") -> str:
    joints = "".join(f'\n  <joint name="j{i}" type="revolute"><parent link="l{i}"/>'
                     f'<child link="l{i + 1}"/></joint>' for i in range(count))
    transmissions = gap.join(TRANSMISSION.format(i=i, n=10 + i % 3) for i in range(count))
    text = f"{head}{joints}\n  {transmissions}\n</robot>\n"
    return text.replace("><", ">\n<") if pretty else text


def converted(data: bytes, target: str = "ros2-p2") -> tuple[bytes | None, bytes]:
    """The rebuilt baseline (None where the conversion serialized it instead) and the true
    one, from converting a copy of the parsed tree."""
    tree = parse_bytes(data, "robot.urdf")
    expected = serialize(tree, data)
    rebuilt: list[bytes] = []
    real = baseline_module.Rebuild.baseline

    def spy(self, *args):
        rebuilt.append(real(self, *args))
        return rebuilt[-1]

    baseline_module.Rebuild.baseline = spy
    try:
        convert_source(Source("robot.urdf", data, tree), target)  # type: ignore[arg-type]
    finally:
        baseline_module.Rebuild.baseline = real
    assert serialize(tree, data) == expected  # a copy was converted
    return (rebuilt[0] if rebuilt else None), expected


REBUILT = {
    "one line each": arm().encode(),
    "one element per line": arm(pretty=True).encode(),
    "blank lines between": arm(gap="\n\n  ").encode(),
    "tabs": arm(gap="\n\t").encode(),
    "same line": arm(gap="").encode(),
    "CRLF": arm().replace("\n", "\r\n").encode(),
    "UTF-8 BOM": codecs.BOM_UTF8 + arm().encode(),
    "declaration": b'<?xml version="1.0" encoding="utf-8"?>\n' + arm().encode(),
    "Latin-1, non-ASCII outside": ('<?xml version="1.0" encoding="ISO-8859-1"?>\n'
                                   + arm().replace("l3", "l\u00e93")).encode("latin-1"),
    "single quotes and spaces": arm().replace('name="t1"', "name = 't1'").encode(),
    "escaped in the rest": arm().replace('"l3"', '"l&amp;3"').replace('"l4"', '"l&gt;4"'
                                                                       ).encode(),
    "a comment before": arm(head='<robot name="arm"><!-- <transmission> -->').encode(),
    "one transmission": arm(1).encode(),
    "a namespace declared on one": arm().replace(
        '<transmission name="t3">', '<transmission name="t3" xmlns:x="http://example.com/x">'
    ).encode(),
    "a default namespace on a joint": arm().replace(
        '<joint name="j3"', '<joint xmlns="http://example.com/d" name="j3"').encode(),
}
NOT_REBUILT = {
    "namespace": arm(head='<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                     ).encode(),
    "non-ASCII name": arm().replace('"m2"', '"m\u00e92"').encode(),
    "escaped name (converted in full)": arm().replace('"m2"', '"m&amp;2"').encode(),
    "character reference": arm().replace('"m2"', '"m&#233;2"').encode(),
    "a comment between": arm().replace('<transmission name="t5">',
                                       '<!-- c --><transmission name="t5">').encode(),
    "two runs": arm().replace('<transmission name="t5">',
                              '<link name="x"/><transmission name="t5">').encode(),
    "UTF-16": arm().encode("utf-16"),
    "a comment inside": arm().replace('<transmission name="t5">',
                                      '<transmission name="t5"><!-- c -->').encode(),
    "text between": arm().replace('</transmission>\n  <transmission name="t3">',
                                  '</transmission>x<transmission name="t3">').encode(),
    "the marker's text": arm(head='<robot name="arm"><!-- txtool-block- -->').encode(),
}


@pytest.mark.parametrize("name", REBUILT)
def test_the_rebuilt_baseline_is_the_serialization(name):
    rebuilt, expected = converted(REBUILT[name])
    assert rebuilt == expected


@pytest.mark.parametrize("name", NOT_REBUILT)
def test_documents_the_rebuild_cannot_read_are_serialized_first(name):
    rebuilt, _ = converted(NOT_REBUILT[name])
    assert rebuilt is None


@pytest.mark.parametrize("target", ["ros2-p1", "ros2-p2"])
def test_conversions_with_and_without_the_rebuild_write_the_same_bytes(target):
    for data in [*REBUILT.values(), *NOT_REBUILT.values()]:
        tree = parse_bytes(data, "robot.urdf")
        fast = convert_source(Source("robot.urdf", data, tree), target).data
        slow = convert_source(Source("robot.urdf", data, tree), target, repeats=False).data
        assert fast == slow


def test_real_robots_rebuild_their_baseline_exactly():
    """Every real robot whose conversion rebuilds the baseline rebuilds it exactly. Most real
    robots do not (their transmissions stand apart or the block is built as elements); a
    large generated one always does (above); UR5e's six transmissions do."""
    paths = [*corpus_files(), *sorted((workspace_dir() / "src").rglob("*.*"))]
    rebuilt = []
    for path in paths:
        data = path.read_bytes()
        try:
            parse_bytes(data, str(path))
        except InputError:
            continue
        for target in ("ros2-p1", "ros2-p2"):
            made, expected = converted(data, target)
            if made is not None:
                assert made == expected, path.name
                rebuilt.append(path.name)
    assert "universal_robot__ur5e.urdf" in rebuilt
