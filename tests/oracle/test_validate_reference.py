"""``validate`` never passes a file ros2_control's compiled parser or loaders refuse.

For every generated variant (tests/oracle/variants.py) and both parser builds (``parser17``:
Humble, ``parser20``: Jazzy and later), where the parser throws because of the transmissions,
a standard loader builds no transmission, or ``configure()`` with one handle per listed member
throws, ``txtool validate --ros-distro DISTRO`` reports an error. The one difference kept on
purpose: ``configure()`` without actuator handles, which a hardware plugin may create itself
(docs/loaders.md, ``configure-without-actuators``). An error on a file the loaders accept is
not a failure here: validate also reports what loads but reads other than written.
"""

from __future__ import annotations

import tempfile
from functools import cache
from pathlib import Path

import pytest

from tests.oracle.differential import NO_ACTUATOR_HANDLES
from tests.oracle.reference import PARSER_OF, oracle_dir, run_parser
from tests.oracle.variants import all_variants
from txtool.lint.api import LintOptions, lint_paths
from txtool.model.distro import Distro


def refusal(result: dict) -> str | None:
    """Why the compiled code refuses the document's transmissions, or None."""
    if not result["accepted"]:
        return result["error"] if result.get("accepted_without_transmissions") else None
    for hardware in result["hardware"]:
        for t in hardware["transmissions"]:
            loader = t.get("loader")
            if loader is None:
                continue
            if not loader["loaded"]:
                return f"{t['name']}: {loader['error']}"
            error = loader.get("configure_error")
            if not loader["configured"] and error != NO_ACTUATOR_HANDLES:
                return f"{t['name']}: configure() {error}"
    return None


@cache
def verdicts(distro: Distro) -> tuple[tuple[str, str | None, tuple[str, ...]], ...]:
    """(label, the loaders' refusal, validate's error codes) for every variant."""
    variants = all_variants()
    results = run_parser(PARSER_OF[distro], [text.encode() for _, text in variants])
    with tempfile.TemporaryDirectory(prefix="txtool-oracle-") as scratch:
        paths = []
        for index, (_, text) in enumerate(variants):
            path = Path(scratch) / f"{index}.urdf"
            path.write_text(text, encoding="utf-8")
            paths.append(str(path))
        linted = lint_paths(paths, LintOptions(ros_distro=distro.value, jobs=1))
    errors: dict[str, list[str]] = {}
    for problem in linted.problems:
        if problem.severity == "error":
            errors.setdefault(problem.path, []).append(problem.code)
    return tuple((label, refusal(result), tuple(errors.get(path, ())))
                 for (label, _), result, path in zip(variants, results, paths, strict=True))


@pytest.mark.parametrize("distro", [Distro.HUMBLE, Distro.JAZZY], ids=lambda d: d.value)
def test_validate_reports_an_error_wherever_the_loaders_refuse(distro: Distro) -> None:
    oracle_dir()
    passed = [f"{label}: {why}" for label, why, codes in verdicts(distro) if why and not codes]
    assert passed == []


@pytest.mark.parametrize("distro", [Distro.HUMBLE, Distro.JAZZY], ids=lambda d: d.value)
def test_the_variants_reach_every_kind_of_refusal(distro: Distro) -> None:
    """The comparison means something: the loaders refuse variants at each stage."""
    oracle_dir()
    reasons = " ".join(why for _, why, _ in verdicts(distro) if why)
    for words in ("There should be exactly one joint", "reduction ratio cannot be zero",
                  "unique joint names", "Actuator names given to transmissions should be",
                  "Not enough valid or required"):
        assert words in reasons, words
