"""A ``.urdf`` file written in xacro is expanded as a ``.xacro`` one is, and ``--xacro-arg``
that reaches no expansion is said, never silently dropped.

Both kinds are real: turtlebot3_description/urdf/turtlebot3_burger.urdf (ROBOTIS-GIT/
turtlebot3) is, in one version, a plain URDF keeping ``xmlns:xacro`` and a commented-out
``<xacro:include filename="$(find ...)">``, and in a later one xacro (``xacro:arg``,
``xacro:property``, ``${namespace}`` in every name) that its launch file runs xacro on.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.corpus import corpus_files
from txtool.cli import cli
from txtool.io.load import needs_expansion, uses_xacro
from txtool.io.xmlio import parse_bytes, read_bytes

XACRO_URDF = """<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://ros.org/wiki/xacro">
  <xacro:arg name="prefix" default=""/>
  <xacro:property name="prefix" value="$(arg prefix)"/>
  <transmission name="${prefix}wheel_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="${prefix}wheel_joint">
      <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>
    </joint>
    <actuator name="${prefix}wheel_motor"><mechanicalReduction>${3*5}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""

PLAIN_URDF = """<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://ros.org/wiki/xacro">
  <!-- <xacro:include filename="$(find bot_description)/urdf/common.urdf"/> -->
  <!-- for "${prefix}wheel_joint" -->
  <transmission name="wheel_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="wheel_joint">
      <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>
    </joint>
    <actuator name="wheel_motor"><mechanicalReduction>15</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def run(*args: str, cwd: Path, monkeypatch, input: str | None = None) -> tuple[int, str, str]:
    monkeypatch.chdir(cwd)
    monkeypatch.delenv("TXTOOL_NO_XACRO", raising=False)
    result = CliRunner().invoke(cli, list(args), input=input)
    if result.exception and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


def shown(out: str) -> list[tuple[str, str, str]]:
    return [(t["name"], t["joints"][0]["name"], t["actuators"][0]["mechanical_reduction"]["text"])
            for t in json.loads(out)["transmissions"]]


@pytest.fixture
def robots(tmp_path) -> Path:
    (tmp_path / "xacro_bot.urdf").write_text(XACRO_URDF)
    (tmp_path / "plain_bot.urdf").write_text(PLAIN_URDF)
    return tmp_path


def test_a_urdf_file_written_in_xacro_is_expanded(robots, monkeypatch):
    code, out, err = run("show", "--format", "json", "xacro_bot.urdf", "--xacro-arg",
                         "prefix:=left_", cwd=robots, monkeypatch=monkeypatch)
    assert (code, err) == (0, "")
    assert shown(out) == [("left_wheel_trans", "left_wheel_joint", "15")]
    code, out, err = run("validate", "--format", "json", "xacro_bot.urdf", cwd=robots,
                         monkeypatch=monkeypatch)
    assert (code, err, json.loads(out)["problems"]) == (0, "", [])


def test_under_no_xacro_it_is_read_as_written_and_the_argument_is_said_unused(robots,
                                                                            monkeypatch):
    code, out, err = run("show", "--format", "json", "--no-xacro", "xacro_bot.urdf",
                         "--xacro-arg", "prefix:=left_", cwd=robots, monkeypatch=monkeypatch)
    assert code == 0
    assert shown(out) == [("${prefix}wheel_trans", "${prefix}wheel_joint", "${3*5}")]
    assert err == ("txtool: warning: xacro_bot.urdf: --xacro-arg has no effect: xacro is off "
                   "(--no-xacro, TXTOOL_NO_XACRO or no-xacro in the configuration)\n")


def test_converting_it_in_place_is_refused_as_for_a_xacro_file(robots, monkeypatch):
    before = (robots / "xacro_bot.urdf").read_bytes()
    code, out, err = run("convert", "--to", "ros2-p2", "xacro_bot.urdf", "-o", "xacro_bot.urdf",
                         "--write", cwd=robots, monkeypatch=monkeypatch)
    assert (code, out) == (2, "")
    assert "converting a xacro file in place would replace it with its expansion" in err
    assert (robots / "xacro_bot.urdf").read_bytes() == before


def test_a_generated_urdf_keeping_the_namespace_and_comments_is_not_expanded(robots,
                                                                          monkeypatch):
    code, out, err = run("show", "--format", "json", "plain_bot.urdf", "--xacro-arg", "a:=1",
                         cwd=robots, monkeypatch=monkeypatch)
    assert code == 0 and shown(out) == [("wheel_trans", "wheel_joint", "15")]
    assert err == ("txtool: warning: plain_bot.urdf: --xacro-arg has no effect: it uses no "
                   "xacro (no xacro element, ${...} or $(...)) and is read as written\n")


def test_standard_input_is_never_expanded_and_says_so(monkeypatch, tmp_path):
    code, out, err = run("show", "--format", "json", "-", "--xacro-arg", "prefix:=x",
                         cwd=tmp_path, monkeypatch=monkeypatch, input=XACRO_URDF)
    assert code == 0 and shown(out)[0][0] == "${prefix}wheel_trans"
    assert err == ("txtool: warning: <stdin>: --xacro-arg has no effect: standard input is "
                   "read as written, never expanded\n")


def test_validate_says_when_its_xacro_arguments_reach_nothing(robots, monkeypatch):
    code, _, err = run("validate", "plain_bot.urdf", "--xacro-arg", "a:=1", cwd=robots,
                       monkeypatch=monkeypatch)
    assert code == 0
    assert err == ("txtool: warning: plain_bot.urdf: --xacro-arg has no effect: it uses no "
                   "xacro (no xacro element, ${...} or $(...)) and is read as written\n")
    code, _, err = run("validate", "plain_bot.urdf", "--no-xacro", "--xacro-arg", "a:=1",
                       cwd=robots, monkeypatch=monkeypatch)
    assert code == 0 and err.startswith("txtool: warning: validate: --xacro-arg has no effect: "
                                        "xacro is off")
    # one input expanded, or a folder (that may hold xacro files): nothing to say
    for inputs in (["plain_bot.urdf", "xacro_bot.urdf"], ["."]):
        code, _, err = run("validate", *inputs, "--xacro-arg", "prefix:=x", cwd=robots,
                           monkeypatch=monkeypatch)
        assert (code, err) == (0, ""), inputs


def test_an_expression_or_substitution_alone_makes_a_file_xacro():
    for body in ('<link name="${p}base"/>', "<link name='b'><x>$(arg p)</x></link>",
                 '<xacro:macro xmlns:xacro="http://www.ros.org/wiki/xacro" name="m"/>',
                 "<link name='b'/>text ${x} after"):
        data = f"<robot name='r'>{body}</robot>".encode()
        assert uses_xacro(data, parse_bytes(data, "r.urdf")), body
    data = b"<robot name='r'><?pi ${x}?><!-- $(find p) --><link name='$ {x}'/></robot>"
    assert not uses_xacro(data, parse_bytes(data, "r.urdf"))
    for text in (XACRO_URDF, PLAIN_URDF):  # UTF-16: read on the parsed document
        data = text.replace('"1.0"?>', '"1.0" encoding="UTF-16"?>', 1).encode("utf-16")
        assert uses_xacro(data, parse_bytes(data, "r.urdf")) == (text == XACRO_URDF)


def test_no_corpus_urdf_is_taken_for_xacro():
    """Generated URDF files of the corpus keep xmlns:xacro and ${...} in comments."""
    for path in corpus_files():
        display, data = read_bytes(str(path))
        if path.suffix == ".xacro":
            continue
        assert not needs_expansion(display, data, parse_bytes(data, display)), path.name


def test_map_under_no_xacro_refuses_it_as_a_xacro_file(robots, monkeypatch):
    code, out, err = run("map", "--no-xacro", "xacro_bot.urdf", "-t", "wheel_trans", "--to",
                         "actuator", "--position", "1", cwd=robots, monkeypatch=monkeypatch)
    assert (code, out) == (2, "")
    assert err.startswith("txtool: xacro_bot.urdf: map needs the xacro expansion, and xacro "
                          "is off")
    code, out, err = run("map", "--no-xacro", "plain_bot.urdf", "-t", "wheel_trans", "--to",
                         "actuator", "--position", "1", cwd=robots, monkeypatch=monkeypatch)
    assert (code, err) == (0, "")
