"""``txtool demo``: a tour of txtool on the bundled example robot (``fixtures/``, shipped
inside the wheel too)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

from rich.console import Console
from rich.rule import Rule

from txtool.dialects.read import read_source
from txtool.io.load import load
from txtool.io.resources import shipped
from txtool.io.xmlio import InputError, Source, parse_bytes
from txtool.transform.convert import convert_source
from txtool.transform.roundtrip import roundtrip
from txtool.views.render import print_table, transmissions_table


def run_demo(console: Console) -> int:
    console.print("Each heading below is the command whose result it shows; the commands run "
                  "as shown in a folder that `txtool demo --copy DIR` fills.", markup=False)
    robot = load(str(shipped("fixtures", "demo_robot.urdf")))
    _show(console, robot)
    _convert(console, robot)
    _roundtrip(console, robot)
    _validate(console, robot)
    if importlib.util.find_spec("pinocchio") is None:
        from txtool.io.resources import install_extra

        raise InputError(f"the demo's simulation step needs the 'sim' extra: "
                         f"{install_extra('sim')}")
    _simulate(console)
    console.print(Rule("done"))
    return 0


def _show(console: Console, robot: Source) -> None:
    console.print(Rule("txtool show fixtures/demo_robot.urdf"))
    transmissions = [f.transmission for f in read_source(robot)]
    print_table(console, transmissions_table(transmissions, "the demo arm's ROS 1 transmissions"))


def _convert(console: Console, robot: Source) -> None:
    for target in ("ros2-p2", "ros2-p1"):
        console.print(Rule(f"txtool convert fixtures/demo_robot.urdf --to {target}"))
        result = convert_source(robot, target)
        converted = Source(robot.path, result.data, parse_bytes(result.data, robot.path))
        print_table(console, transmissions_table([f.transmission for f in read_source(converted)],
                                                 f"converted to {target} (lossless: "
                                                 f"{'yes' if not result.losses else 'no'})"))
        back = convert_source(converted, "ros1")
        same = back.losses == [] and _fields(back.data) == _fields(robot.data)
        console.print(f"and back to ros1: {'same transmissions' if same else 'DIFFERENT'}")


def _fields(data: bytes) -> list:
    source = Source("x", data, parse_bytes(data, "x"))
    return [(t.name, t.kind, [(j.name, j.role, j.offset and j.offset.value) for j in t.joints],
             [(a.name, a.role, a.mechanical_reduction and a.mechanical_reduction.value)
              for a in t.actuators])
            for t in (f.transmission for f in read_source(source))]


def _roundtrip(console: Console, robot: Source) -> None:
    console.print(Rule("txtool roundtrip fixtures/demo_robot.urdf"))
    report = roundtrip(robot)
    for row in report.rows:
        kept = ", ".join(f for f, ok in row.fields.items() if ok)
        console.print(f"{row.transmission:15} {' → '.join(row.cycle):34} kept: {kept}; "
                      f"drives the actuators the same: {row.equivalent}")


def _validate(console: Console, robot: Source) -> None:
    from txtool.lint.engine import lint_source

    for source in (robot, load(str(shipped("fixtures", "broken_robot.urdf")))):
        shown = f"fixtures/{Path(source.path).name}"  # where --copy puts it
        console.print(Rule(f"txtool validate {shown}"))
        problems = lint_source(source)
        for p in problems:
            console.print(f"{shown}:{p.line}:{p.column}: {p.severity} {p.code} "
                          f"{p.name}: {p.message}", markup=False)
        console.print(f"{len(problems)} finding(s)")


def _simulate(console: Console) -> None:
    from txtool.simulation.demo import demo_runs

    demo_runs(console)
