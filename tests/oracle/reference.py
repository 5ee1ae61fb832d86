"""The loaders' own compiled code, run beside txtool (the programs of ``../shared/oracle``).

``.ci/run`` builds them once (``build.sh``) and exports their folder as ``TXTOOL_ORACLE``. A
test that needs them skips with the reason where they are absent, and fails instead under
``TXTOOL_REQUIRE_CORPUS=1``. Every program reads many inputs in one call, so a whole corpus
costs one process start.

``parser17`` and ``parser20`` run ros2_control's ``parse_control_resources_from_urdf``
(hardware_interface/src/component_parser.cpp) and the three standard transmission loaders, built
as Humble (C++17, numbers through ``std::istringstream``) and as Jazzy and later (C++20,
``std::from_chars``; hardware_interface/src/lexical_casts.cpp, ``impl::stod``). They print one
JSON line per file; numbers are C99 hexadecimal floats, so a comparison is bit for bit.
"""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
from pathlib import Path

import pytest

from txtool.model.distro import Distro

PROGRAMS = ("parser17", "parser20", "maths_ros1", "maths_ros2", "stod")
# The parser build each ROS 2 distribution runs (ros2_control's lexical_casts.cpp picks
# istringstream below C++20).
PARSER_OF = {Distro.HUMBLE: "parser17", Distro.JAZZY: "parser20", Distro.KILTED: "parser20",
             Distro.ROLLING: "parser20"}
TIMEOUT = 120


def oracle_dir() -> Path:
    """The built programs' folder, or a skip (a failure under ``TXTOOL_REQUIRE_CORPUS=1``)."""
    folder = os.environ.get("TXTOOL_ORACLE")
    if folder and all((Path(folder) / name).is_file() for name in PROGRAMS):
        return Path(folder)
    reason = ("the loaders' reference programs are not built: run "
              "`bash ../shared/oracle/build.sh DIR` and set TXTOOL_ORACLE=DIR"
              if not folder else f"TXTOOL_ORACLE={folder} lacks one of {', '.join(PROGRAMS)}")
    if os.environ.get("TXTOOL_REQUIRE_CORPUS") == "1":
        pytest.fail(reason + " (TXTOOL_REQUIRE_CORPUS=1)")
    pytest.skip(reason)


def run_lines(program: str, lines: list[str]) -> list[str]:
    """``program`` on one input line each, its output lines in the same order."""
    done = subprocess.run([str(oracle_dir() / program)], input="\n".join(lines) + "\n",
                          capture_output=True, text=True, timeout=TIMEOUT, check=True)
    output = done.stdout.splitlines()
    assert len(output) == len(lines), done.stderr
    return output


def run_parser(program: str, documents: list[bytes]) -> list[dict]:
    """The parser oracle's ``result`` for each document, in one process."""
    with tempfile.TemporaryDirectory() as scratch:
        paths = []
        for index, data in enumerate(documents):
            path = Path(scratch) / f"{index}.urdf"
            path.write_bytes(data)
            paths.append(str(path))
        done = subprocess.run([str(oracle_dir() / program), *paths], capture_output=True,
                              timeout=TIMEOUT, check=True)
    results = [json.loads(line) for line in done.stdout.decode().splitlines()]
    assert [r["file"] for r in results] == paths
    return [r["result"] for r in results]


def hex_float(text: str) -> float:
    """A number as the oracle prints it (``%a``, ``inf``, ``nan``)."""
    return float("nan") if text == "nan" else float.fromhex(text)
