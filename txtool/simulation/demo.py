"""The simulate part of ``txtool demo``: the demo robot against itself and a sign-flipped copy."""

from __future__ import annotations

import tempfile
from pathlib import Path

from rich.console import Console
from rich.markup import escape as escape_markup
from rich.rule import Rule

from txtool.dialects.read import read_source
from txtool.io.load import load
from txtool.io.printable import printable
from txtool.io.resources import shipped
from txtool.io.xmlio import InputError, serialize
from txtool.model.robot import children
from txtool.model.semantics import loader_of
from txtool.simulation import report
from txtool.simulation.run import Options, simulate_one


def escape(text: str) -> str:
    """A name or path from a file, printed through rich: one line, brackets as written."""
    return escape_markup(printable(text))


def demo_runs(console: Console, robot: Path | None = None) -> None:
    """Simulate the demo robot with its own config (passes), then with one sign flipped (fails)."""
    path = robot or shipped("fixtures", "demo_robot.urdf")
    shown = _display(path)
    console.print(Rule(f"txtool simulate {shown}"))
    own = simulate_one(Options(robot=str(path), keep_series=False), None, label=shown)
    own.robot = shown
    report.render_run(own, console)
    with tempfile.TemporaryDirectory(prefix="txtool-demo-") as folder:
        flipped, what = flipped_copy(str(path), Path(folder))
        label = f"{shown} with {what}"
        console.print(Rule(f"txtool simulate {shown} --candidate <{what}>"))
        run = simulate_one(Options(robot=str(path), keep_series=False), str(flipped),
                           label=label)
    console.print(f"{escape(label)}: {report.verdict_line(run)}", soft_wrap=True)
    causes = [r for r in run.reasons if r.startswith("likely cause: ")]
    symptoms = [r for r in run.reasons[1:] if r not in causes]
    for reason in symptoms[:2] + causes:  # the diagnosis is what the demo is for
        console.print(f"  - {escape(reason)}", soft_wrap=True)
    if len(symptoms) > 2:
        console.print(f"  - ... {len(symptoms) - 2} more symptoms")


def _display(path: Path) -> str:
    try:
        return str(path.resolve().relative_to(Path.cwd()))
    except ValueError:
        return path.name


def flipped_copy(robot: str, folder: Path) -> tuple[Path, str]:
    """Write ``robot`` with the first simple transmission's reduction negated; (path, what)."""
    source = load(robot)
    for found in read_source(source):
        t = found.transmission
        if t.kind != "simple":
            continue
        if loader_of(t) == "ros1":
            holders = children(found.element, "actuator")
            tag = "mechanicalReduction"
        else:
            holders = children(found.element, "joint")
            tag = "mechanical_reduction"
        for element in (children(holders[0], tag) if holders else []):
            value = float((element.text or "").strip())
            element.text = repr(-value).removesuffix(".0")
            target = folder / f"flipped-{Path(robot).name}"
            target.write_bytes(serialize(source.tree, source.data))
            return target, f"'{t.name}' reversed"
    raise InputError(f"{robot}: no simple transmission with a reduction to flip")
