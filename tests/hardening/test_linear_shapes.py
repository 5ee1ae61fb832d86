"""Shapes a pull request chooses that were quadratic: many attributes on one element, one
very long value. Each is measured at two sizes in the same run, by the processor time of the
command (the smallest of a few runs): four times the size may take about four times as long,
never the sixteen times a quadratic step takes."""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from pathlib import Path

from tests.hardening.conftest import Run

ROOT = Path(__file__).resolve().parents[2]
DEMO = (ROOT / "fixtures" / "demo_robot.urdf").read_text()
LINEAR = 8  # the bound on the ratio of times for four times the size (quadratic: 16)


def cost(step: Callable[[], object], repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.process_time()
        step()
        times.append(time.process_time() - start)
    return min(times)


def ratio(tmp_path: Path, run: Run, write: Callable[[Path, int], None], size: int,
          *command: str, repeats: int = 3) -> tuple[float, float]:
    small, large = tmp_path / "small.urdf", tmp_path / "large.urdf"
    write(small, size)
    write(large, 4 * size)

    def check(path: Path) -> Callable[[], object]:
        def step() -> None:
            code, out, err = run(*command, str(path))
            assert code in (0, 1) and not err, (code, out[-500:], err)
        return step

    return cost(check(small), repeats), cost(check(large), repeats)


def utf16_attributes(path: Path, count: int) -> None:
    """The demo robot in UTF-16 (read as a parsed document), its <robot> holding ``count``
    attributes."""
    attributes = " ".join(f'a{i}="{i}"' for i in range(count))
    text = DEMO.replace('<?xml version="1.0"?>', '<?xml version="1.0" encoding="UTF-16"?>')
    path.write_bytes(re.sub(r"<robot(?=\s)", f"<robot {attributes}", text, count=1)
                     .encode("utf-16"))


def long_reduction(path: Path, digits: int) -> None:
    """The demo robot with a reduction of ``digits`` digits (a value every cycle reports)."""
    path.write_text(DEMO.replace("<mechanicalReduction>-100</mechanicalReduction>",
                                 f"<mechanicalReduction>{'1' * digits}</mechanicalReduction>"))


def test_validate_is_linear_in_the_attributes_of_one_element(run: Run, tmp_path: Path):
    run("validate", str(ROOT / "fixtures" / "demo_robot.urdf"))  # (imports done)
    small, large = ratio(tmp_path, run, utf16_attributes, 10_000, "validate")
    assert large < LINEAR * small, (small, large)


def test_show_is_linear_in_the_attributes_of_one_element(run: Run, tmp_path: Path):
    run("show", str(ROOT / "fixtures" / "demo_robot.urdf"))
    small, large = ratio(tmp_path, run, utf16_attributes, 10_000, "show")
    assert large < LINEAR * small, (small, large)


def test_roundtrip_text_is_linear_in_the_length_of_a_value(run: Run, tmp_path: Path):
    run("roundtrip", str(ROOT / "fixtures" / "demo_robot.urdf"))
    small, large = ratio(tmp_path, run, long_reduction, 750_000, "roundtrip", "--color",
                         "always", repeats=1)
    assert large < LINEAR * small, (small, large)


def test_convert_and_roundtrip_are_linear_in_the_attributes_of_one_element(run: Run,
                                                                           tmp_path: Path):
    """The conversion records the root's attributes and compares them after: 20,000 took
    3 s to convert and 16 s to round-trip while each value was looked up by name."""
    run("roundtrip", str(ROOT / "fixtures" / "demo_robot.urdf"))
    for command in (("convert", "--to", "ros2-p2", "--hardware-plugin", "arm/Hardware"),
                    ("roundtrip", "--format", "json")):
        small, large = ratio(tmp_path, run, utf16_attributes, 5_000, *command)
        assert large < LINEAR * small, (command, small, large)
