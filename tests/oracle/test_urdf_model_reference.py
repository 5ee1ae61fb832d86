"""``validate`` errors (TX210) on exactly the robots urdfdom refuses to build.

ros2_control's compiled parser (``parser17``: Humble, ``parser20``: Jazzy and later) builds the
URDF model with urdfdom after reading the ``<ros2_control>`` blocks, and throws "Failed to
parse URDF file" when urdfdom refuses it. Each variant below changes one thing of a robot both
builds accept: where they refuse it, validate reports TX210 as an error; where they accept
it (a link with two parents, a cycle beside the root: urdfdom builds the tree from the root and
refuses neither), it does not.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest

from tests.oracle.reference import oracle_dir, run_parser
from txtool.lint.api import LintOptions, lint_paths

LIMIT = '<limit lower="-1" upper="1" effort="10" velocity="1"/>'
BASE = {
    "links": '<link name="base"/><link name="arm"/><link name="tool"/>',
    "shoulder": f'<joint name="shoulder" type="revolute"><parent link="base"/>'
                f'<child link="arm"/>{LIMIT}</joint>',
    "wrist": '<joint name="wrist" type="fixed"><parent link="arm"/><child link="tool"/></joint>',
    "extra": "",
}


def robot(name: str = ' name="r"', **parts: str) -> str:
    body = "\n  ".join({**BASE, **parts}.values())
    return f"""<robot{name}>
  {body}
  <ros2_control name="robot" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="shoulder"><command_interface name="position"/></joint>
  </ros2_control>
</robot>
"""


def shoulder(kind: str = "revolute", parent: str = '<parent link="base"/>',
             child: str = '<child link="arm"/>', limit: str = LIMIT, name: str = "shoulder") -> str:
    named = f' name="{name}"' if name else ""
    typed = f' type="{kind}"' if kind else ""
    return f"<joint{named}{typed}>{parent}{child}{limit}</joint>"


# (label, document, whether urdfdom refuses it)
VARIANTS = [
    ("as written", robot(), False),
    ("parent link missing", robot(shoulder=shoulder(parent='<parent link="torso"/>')), True),
    ("child link missing", robot(shoulder=shoulder(child='<child link="forearm"/>')), True),
    ("no <parent>", robot(shoulder=shoulder(parent="")), True),
    ("empty parent link", robot(shoulder=shoulder(parent='<parent link=""/>')), True),
    ("no <child>", robot(shoulder=shoulder(child="")), True),
    ("link without a name", robot(extra="<link/>"), True),
    ("two links of one name", robot(extra='<link name="arm"/>'), True),
    ("two joints of one name", robot(extra=BASE["wrist"]), True),
    ("joint without a name", robot(wrist='<joint type="fixed"><parent link="arm"/>'
                                         '<child link="tool"/></joint>'), True),
    ("joint without a type", robot(shoulder=shoulder(kind="")), True),
    ("unknown joint type", robot(shoulder=shoulder(kind="hinge")), True),
    ("revolute without limit", robot(shoulder=shoulder(limit="")), True),
    ("prismatic without limit", robot(shoulder=shoulder(kind="prismatic", limit="")), True),
    ("continuous without limit", robot(shoulder=shoulder(kind="continuous", limit="")), False),
    ("limit without effort", robot(shoulder=shoulder(limit='<limit velocity="1"/>')), True),
    ("limit without velocity", robot(shoulder=shoulder(limit='<limit effort="1"/>')), True),
    ("two roots", robot(extra='<link name="free"/>'), True),
    ("no root", robot(extra='<joint name="back" type="fixed"><parent link="tool"/>'
                            '<child link="base"/></joint>'), True),
    ("robot without a name", robot(name=""), True),
    ("a link with two parents", robot(extra='<joint name="again" type="fixed">'
                                            '<parent link="base"/><child link="tool"/></joint>'),
     False),
    ("a cycle beside the root", robot(extra='<link name="p"/><link name="q"/>'
                                            '<joint name="pq" type="fixed"><parent link="p"/>'
                                            '<child link="q"/></joint>'
                                            '<joint name="qp" type="fixed"><parent link="q"/>'
                                            '<child link="p"/></joint>'), False),
]


@pytest.mark.parametrize("program", ["parser17", "parser20"])
def test_validate_errors_where_urdfdom_refuses_the_robot(program: str) -> None:
    oracle_dir()
    results = run_parser(program, [text.encode() for _, text, _ in VARIANTS])
    refused = {label: result.get("error") for (label, _, _), result
               in zip(VARIANTS, results, strict=True) if not result["accepted"]}
    assert refused == {label: "Failed to parse URDF file" for label, _, no in VARIANTS if no}
    assert tx210_errors() == set(refused)


def tx210_errors() -> set[str]:
    """The labels of the variants validate reports TX210 for, as an error."""
    with tempfile.TemporaryDirectory(prefix="txtool-oracle-") as scratch:
        paths = {}
        for index, (label, text, _) in enumerate(VARIANTS):
            path = Path(scratch) / f"{index}.urdf"
            path.write_text(text, encoding="utf-8")
            paths[str(path)] = label
        linted = lint_paths(list(paths), LintOptions(jobs=1))
    return {paths[p.path] for p in linted.problems if p.code == "TX210" and p.severity == "error"}
