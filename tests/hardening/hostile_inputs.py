"""Hostile and odd documents for the hardening tests, and a way to run every command on one.

The robot is small but complete (inertias, limits), so that every command, ``simulate``
included, gets as far as it can when the document is read at all.
"""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from click.testing import CliRunner

from txtool.cli import cli

XACRO_NS = "http://www.ros.org/wiki/xacro"

ROBOT = """\
<?xml version="1.0"?>
{doctype}
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
  </link>
  <link name="upper">
    <inertial><mass value="1"/><origin xyz="0 0 0.1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="{joint}" type="revolute">
    <parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="2"/>
  </joint>
  <!-- the elbow drive -->{comment}
  <transmission name="{transmission}">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="{joint}"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="elbow_motor"><mechanicalReduction>{reduction}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
PLAIN = {"doctype": "", "joint": "elbow", "transmission": "elbow_trans", "reduction": "50",
         "comment": ""}


def robot(**changes: str) -> str:
    """The robot with some spots replaced (see :data:`PLAIN` for the spots)."""
    return ROBOT.format(**{**PLAIN, **changes})


def billion_laughs(levels: int = 10, fan_out: int = 10) -> str:
    """The classic: ``levels`` entities, each referencing the previous one ``fan_out`` times."""
    declarations = ['<!ENTITY lol0 "lol">']
    for level in range(1, levels):
        declarations.append(f'<!ENTITY lol{level} "{f"&lol{level - 1};" * fan_out}">')
    doctype = "<!DOCTYPE robot [\n" + "\n".join(declarations) + "\n]>"
    return robot(doctype=doctype, reduction=f"&lol{levels - 1};")


def quadratic_blowup(size: int = 100_000, references: int = 20_000) -> str:
    """One big entity referenced many times (no nesting, so nesting limits do not catch it)."""
    doctype = f'<!DOCTYPE robot [<!ENTITY big "{"B" * size}">]>'
    return robot(doctype=doctype, reduction="&big;" * references)


@dataclass(frozen=True)
class Outcome:
    args: tuple[str, ...]
    code: int
    out: str
    err: str
    exception: BaseException | None


def invoke(*args: str) -> Outcome:
    """``txtool ARGS`` in-process; an exception other than an exit is kept, not raised."""
    result = CliRunner().invoke(cli, list(args))
    exception = result.exception
    if isinstance(exception, SystemExit):
        exception = None
    return Outcome(tuple(args), result.exit_code, result.stdout, result.stderr, exception)


def run(*args: str) -> tuple[int, str, str]:
    """``txtool ARGS`` in-process: (exit code, stdout, stderr); an exception fails the test."""
    outcome = invoke(*args)
    if outcome.exception is not None:
        raise outcome.exception
    return outcome.code, outcome.out, outcome.err


def command_lines(document: Path, scratch: Path) -> Iterator[tuple[list[str], Path | None]]:
    """Every command that reads a robot, run on ``document``; with the file it writes, if any.

    ``scratch`` is an empty folder for outputs and for the copies that ``migrate`` rewrites.
    """
    path = str(document)
    yield ["show", path], None
    yield ["show", "--format", "json", path], None
    for output_format in ("text", "json", "github", "sarif"):
        yield ["validate", "--format", output_format, path], None
    for target in ("ros2-p2", "ros1", "ros2-p1"):
        yield ["convert", "--to", target, path], None
        written = scratch / f"converted.{target}.{document.name}"
        yield ["convert", "--to", target, path, "-o", str(written)], written
    yield ["roundtrip", path], None
    yield ["map", path, "-t", "elbow_trans", "--to", "actuator", "--position", "0.5"], None
    yield ["simulate", path, "--duration", "0.02"], None
    for mode in ("--diff", "--write"):
        copy = scratch / f"migrated{mode}.{document.name}"
        shutil.copyfile(document, copy)
        yield ["migrate", "--to", "ros2-p2", mode, str(copy)], copy


def one_line_error(err: str) -> str:
    """The single line of ``err``; fails the test when there are more or none."""
    lines = err.splitlines()
    assert len(lines) == 1, f"expected one line on stderr, got {err!r}"
    return lines[0]


def xacro_robot(body: str) -> str:
    """A xacro robot of one link holding ``body``."""
    return ('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            f"  <link name=\"base\"/>\n{body}\n</robot>\n")
