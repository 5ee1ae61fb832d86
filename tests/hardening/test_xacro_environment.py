"""What of the environment an untrusted xacro may read: only the names the command line gives.

Every substitution that reads a variable (``$(env)``, ``$(optenv)``, with or without a
default, through a property, an argument's default, an include's file name) is
tried with the same names, secret-looking or not: none is read unless ``--xacro-env`` names
it, and each is read when it does (no name is judged by how it looks). A configuration file,
which a pull request may change, cannot name one.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli
from txtool.io.xacro import expand_text
from txtool.io.xacro_guard import Refusal, XacroGuard
from txtool.io.xacro_sandbox import expand_in_sandbox
from txtool.io.xmlio import XacroError, XacroOptions

SECRET = "s3cr3t-4b1d"
# Real secrets' names: many look like nothing in particular.
NAMES = ["GITHUB_TOKEN", "GH_PAT", "DATABASE_URL", "SLACK_WEBHOOK", "SENTRY_DSN", "NETRC",
         "PGPASSWORD", "X", "ROBOT_MODEL", "lower_case", "AWS_SECRET_ACCESS_KEY"]
ROUTES = {  # how a file reads NAME; a refusal or the default when NAME is not given
    "env": ('<link name="$(env NAME)"/>', "refused"),
    "optenv": ('<link name="v$(optenv NAME)"/>', 'name="v"'),
    "optenv with a default": ('<link name="$(optenv NAME fallback)"/>', 'name="fallback"'),
    "a property": ('<xacro:property name="p" value="$(env NAME)"/><link name="${p}"/>',
                   "refused"),
    "an argument's default": ('<xacro:arg name="a" default="$(optenv NAME none)"/>'
                              '<link name="$(arg a)"/>', 'name="none"'),
    "an include's name": ('<xacro:include filename="$(env NAME).xacro"/>', "refused"),
}
CASES = [(route, name) for route in ROUTES for name in NAMES]


def robot(body: str) -> str:
    return ('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            f"  <link name=\"base\"/>\n{body}\n</robot>\n")


@pytest.fixture
def repo(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    root = tmp_path / "repo"
    (root / ".git").mkdir(parents=True)
    monkeypatch.chdir(root)
    monkeypatch.delenv("TXTOOL_NO_XACRO", raising=False)
    for name in NAMES:
        monkeypatch.setenv(name, f"{SECRET}-{name}")
    return root


def expand(repo: Path, body: str, given: tuple[str, ...] = ()) -> str:
    path = repo / "robot.urdf.xacro"
    path.write_text(robot(body))
    options = XacroOptions(env=given)
    try:  # the guard sees the whole environment: its own filter is what is tested
        return expand_text(str(path), str(path), options,
                           XacroGuard(str(path), options, dict(os.environ)))
    except Refusal as exc:
        return f"refused: {exc.reason}"
    except XacroError as exc:
        return f"failed: {exc.reason}"


@pytest.mark.parametrize(("route", "name"), CASES, ids=[f"{r}: {n}" for r, n in CASES])
def test_no_variable_is_read_unless_the_command_line_names_it(repo, route, name):
    body, expected = ROUTES[route]
    text = expand(repo, body.replace("NAME", name))
    assert SECRET not in text
    assert text.startswith("refused: ") if expected == "refused" else expected in text, text


@pytest.mark.parametrize(("route", "name"), CASES, ids=[f"{r}: {n}" for r, n in CASES])
def test_a_variable_the_command_line_names_is_read_whatever_its_name(repo, route, name):
    body, _ = ROUTES[route]
    if route == "an include's name":
        (repo / f"{SECRET}-{name}.xacro").write_text(robot(f'<link name="{name}_included"/>'))
        assert f"{name}_included" in expand(repo, body.replace("NAME", name), (name,))
        return
    assert f"{SECRET}-{name}" in expand(repo, body.replace("NAME", name), (name,))


def test_one_name_given_reads_that_name_only(repo):
    text = expand(repo, '<link name="$(optenv GH_PAT x)"/><link name="$(optenv X y)"/>',
                  ("X",))
    assert f'name="{SECRET}-X"' in text and 'name="x"' in text


def test_the_child_receives_only_the_names_given(repo):
    """The sandbox's child has an empty environment: a variable not given never reaches it,
    whatever the guard would do."""
    path = repo / "robot.urdf.xacro"
    path.write_text(robot('<link name="$(optenv HOME none)"/><link name="$(optenv X none)"/>'))
    text = expand_in_sandbox(str(path), "robot.urdf.xacro", XacroOptions(env=("X",)))
    assert f'name="{SECRET}-X"' in text and 'name="none"' in text


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, list(args), catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize(("file", "text", "key"), [
    (".txtool.toml", 'xacro-env = ["GH_PAT"]\n', "xacro-env"),
    ("pyproject.toml", '[tool.txtool]\nxacro-env = ["GH_PAT"]\n', "tool.txtool.xacro-env"),
    (".txtool.toml", "xacro-env = []\n", "xacro-env"),
])
@pytest.mark.parametrize("command", ["validate", "show", "roundtrip"])
def test_no_configuration_file_names_a_variable(repo, file, text, key, command):
    (repo / file).write_text(text)
    (repo / "robot.urdf.xacro").write_text(robot('<link name="$(env GH_PAT)"/>'))
    code, out, err = run(command, "robot.urdf.xacro")
    assert (code, SECRET in out + err) == (2, False)
    assert err.splitlines()[-1] == (
        f"txtool: {repo / file}: key '{key}': the environment variables $(env) may read are named "
        "on the command line (--xacro-env NAME), never in a file of the repository")


def test_show_and_validate_read_the_same_names(repo):
    (repo / "robot.urdf.xacro").write_text(robot('<link name="$(env ROBOT_MODEL)_base"/>'))
    for command in ("show", "validate"):
        code, out, err = run(command, "robot.urdf.xacro")
        assert code == 2 or "TX002" in out, (command, out, err)
        code, out, err = run(command, "--xacro-env", "ROBOT_MODEL", "robot.urdf.xacro")
        assert code in (0, 1) and "TX002" not in out and err == "", (command, out, err)
