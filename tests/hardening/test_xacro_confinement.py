"""What an untrusted xacro may read: the repository and the packages it names, links resolved.

Every way to name a file (``<xacro:include>``, ``xacro.load_yaml``, an include glob,
``$(find)``) is tried with the same hostile paths: folders beside the repository whose names
begin with its name, another case, ``..``, absolute paths, links out of it, hidden folders
(``.git`` holds the checkout's credentials). Each is refused, and nothing read outside, not
even a file's name, reaches a message. The guard runs in this process (the confinement is
its own); the configuration's part is run through the command line.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli
from txtool.io.packages import WORKSPACE_MARKS, packages_below
from txtool.io.xacro import expand_text
from txtool.io.xacro_guard import Refusal, XacroGuard
from txtool.io.xmlio import XacroError, XacroOptions

SECRET = "s3cr3t-9f8e7d"
OUTSIDE_NAME = "only_outside_name_5a"  # a file name that must never be printed


def robot(body: str) -> str:
    return ('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            f"  <link name=\"base\"/>\n{body}\n</robot>\n")


def secret_files(folder: Path) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "secret.xacro").write_text(robot(f'<link name="{SECRET}"/>'))
    (folder / "secret.yaml").write_text(f"token: {SECRET}\n")
    (folder / f"{OUTSIDE_NAME}.xacro").write_text(robot(f'<link name="{SECRET}"/>'))


@pytest.fixture
def tree(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """``repo`` (a git checkout) and, beside it, folders it must not read."""
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (repo / "sub").mkdir()
    secret_files(repo / "sub" / "fine")  # inside: read (shows the tests can fail)
    for name in ("repo-old", "repo2", "Repo", "outside"):
        secret_files(tmp_path / name)
    secret_files(repo / ".git" / "creds")
    secret_files(repo / "sub" / ".hidden")
    (repo / "link_dir").symlink_to(tmp_path / "outside")
    (repo / "link_file.xacro").symlink_to(tmp_path / "outside" / "secret.xacro")
    (repo / "link_file.yaml").symlink_to(tmp_path / "outside" / "secret.yaml")
    (repo / "loop").symlink_to(repo)  # a link inside, to inside: fine
    monkeypatch.chdir(repo)
    for name in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH", "TXTOOL_NO_XACRO"):
        monkeypatch.delenv(name, raising=False)
    packages_below.cache_clear()
    return tmp_path


def expand(repo: Path, body: str, options: XacroOptions | None = None) -> str:
    """The expansion under the guard, or ``refused: reason``, or ``failed: reason``."""
    options = options or XacroOptions()
    path = repo / "robot.urdf.xacro"
    path.write_text(robot(body))
    try:
        return expand_text(str(path), str(path), options, XacroGuard(str(path), options, {}))
    except Refusal as exc:
        return f"refused: {exc.reason}"
    except XacroError as exc:
        return f"failed: {exc.reason}"


# A name for the same file, relative to the repository ({tmp}: the folder holding it).
HOSTILE = {
    "a sibling whose name begins with the repository's": "../repo-old/secret",
    "the same, absolute": "{tmp}/repo-old/secret",
    "a sibling with a suffix": "../repo2/secret",
    "another case": "../Repo/secret",
    "up and out through a folder": "sub/../../outside/secret",
    "up through a link inside": "loop/../outside/secret",
    "absolute": "{tmp}/outside/secret",
    "a link to a folder outside": "link_dir/secret",
    "a link to a file outside": "link_file",
    "the checkout's .git": ".git/creds/secret",
    "a hidden folder": "sub/.hidden/secret",
}
ROUTES = {
    "include": lambda p: f'<xacro:include filename="{p}.xacro"/>',
    "load_yaml": lambda p: f'<link name="${{xacro.load_yaml(\'{p}.yaml\')}}"/>',
    "load_yaml, global": lambda p: f'<link name="${{load_yaml(\'{p}.yaml\')}}"/>',
    "include into a namespace": lambda p: f'<xacro:include filename="{p}.xacro" ns="n"/>',
    "include, optional": lambda p: f'<xacro:include filename="{p}.xacro" optional="true"/>',
}
CASES = [(route, name) for route in ROUTES for name in HOSTILE]


@pytest.mark.parametrize(("route", "name"), CASES, ids=[f"{r}: {n}" for r, n in CASES])
def test_every_route_refuses_every_hostile_name(tree, route, name):
    text = expand(tree / "repo", ROUTES[route](HOSTILE[name].format(tmp=tree)))
    assert text.startswith("refused: "), text
    assert SECRET not in text and OUTSIDE_NAME not in text


@pytest.mark.parametrize("route", ROUTES)
def test_every_route_reads_inside_the_repository(tree, route):
    text = expand(tree / "repo", ROUTES[route]("sub/fine/secret"))
    assert SECRET in text


# Include globs: the folder before the first wildcard must be inside, and nothing may climb
# out after it; no outside name is listed, even in a refusal.
GLOBS = {
    "a sibling's files": "../*/secret.xacro",
    "a prefix sibling by bracket": "../repo-ol[d]/*.xacro",
    "an absolute folder": "{tmp}/outside/*.xacro",
    "climbing after the wildcard": "sub/*/../../../outside/*.xacro",
    "a link to a folder outside": "link_dir/*.xacro",
    "every folder below the repository's parent": "{tmp}/*/*.xacro",
    "through a link below a wildcard": "*/secret.xacro",
    "a hidden folder": ".git/*/*.xacro",
}


@pytest.mark.parametrize("pattern", GLOBS.values(), ids=GLOBS.keys())
def test_an_include_glob_never_lists_outside(tree, pattern):
    text = expand(tree / "repo", f'<xacro:include filename="{pattern.format(tmp=tree)}"/>')
    assert text.startswith("refused: "), text
    assert SECRET not in text and OUTSIDE_NAME not in text


def test_an_include_glob_inside_is_read(tree):
    assert SECRET in expand(tree / "repo", '<xacro:include filename="sub/fine/secret*.xacro"/>')


# -- $(find): the package found must be inside, or given from outside the checkout -----------

def package(folder: Path, name: str) -> Path:
    secret_files(folder)
    (folder / "package.xml").write_text(f"<package><name>{name}</name></package>\n")
    return folder


FIND = '<xacro:include filename="$(find evil)/secret.xacro"/>'


def test_a_committed_link_to_a_package_outside_is_not_followed(tree):
    package(tree / "elsewhere" / "evil", "evil")
    (tree / "repo" / "deps").symlink_to(tree / "elsewhere")
    text = expand(tree / "repo", FIND)
    assert text.startswith("failed: package 'evil' not found") and SECRET not in text
    path = tree / "repo" / "robot.urdf.xacro"  # upstream follows it: the test can fail
    assert SECRET in expand_text(str(path), str(path), XacroOptions())


def test_a_package_from_the_command_line_or_the_environment_is_read(tree, monkeypatch):
    folder = package(tree / "elsewhere" / "evil", "evil")
    given = XacroOptions(pkg_dirs=(str(tree / "elsewhere"),), readable=(str(tree / "elsewhere"),))
    assert SECRET in expand(tree / "repo", FIND, given)
    named = XacroOptions(pkg_paths=(("evil", str(folder)),), readable=(str(folder),))
    assert SECRET in expand(tree / "repo", FIND, named)
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tree / "elsewhere"))
    assert SECRET in expand(tree / "repo", FIND)


def test_a_configured_folder_outside_the_repository_is_refused(tree):
    """The configuration's pkg-dirs and pkg-paths are folders alone, not ``readable``."""
    folder = package(tree / "elsewhere" / "evil", "evil")
    for options in (XacroOptions(pkg_dirs=(str(tree / "elsewhere"),)),
                    XacroOptions(pkg_paths=(("evil", str(folder)),))):
        text = expand(tree / "repo", FIND, options)
        assert text.startswith("refused: $(find evil) leads outside the repository"), text
        assert SECRET not in text and str(tree / "elsewhere") not in text


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, list(args), catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize("config", [
    'pkg-dirs = ["../elsewhere"]\n',
    '[pkg-paths]\nevil = "../elsewhere/evil"\n',
    'pkg-dirs = ["deps"]\n',  # a committed link to the same folder
])
def test_a_pull_requests_configuration_widens_nothing(tree, config):
    package(tree / "elsewhere" / "evil", "evil")
    repo = tree / "repo"
    (repo / "deps").symlink_to(tree / "elsewhere")
    (repo / ".txtool.toml").write_text(config)
    (repo / "robot.urdf.xacro").write_text(robot(FIND))
    for command in ("show", "validate"):
        code, out, err = run(command, "robot.urdf.xacro")
        assert code in (1, 2) and SECRET not in out + err
        assert "leads outside the repository" in out + err or "not found" in out + err
    code, out, err = run("show", "--pkg-path", "evil:=../elsewhere/evil", "robot.urdf.xacro")
    assert code == 0 and err == ""  # the command line may


# -- what a workspace is -----------------------------------------------------------------------

@pytest.fixture
def home(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """``home/src/robot`` (a clone) and ``home/src/other`` (a package beside it)."""
    repo = tmp_path / "home" / "src" / "robot"
    (repo / ".git").mkdir(parents=True)
    package(tmp_path / "home" / "src" / "other", "other")
    (repo / "robot.urdf.xacro").write_text(robot(
        '<xacro:include filename="$(find other)/secret.xacro"/>'))
    for name in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH"):
        monkeypatch.delenv(name, raising=False)
    packages_below.cache_clear()
    return tmp_path / "home"


def expand_file(path: Path) -> str:
    try:
        return expand_text(str(path), str(path), XacroOptions(),
                           XacroGuard(str(path), XacroOptions(), {}))
    except (Refusal, XacroError) as exc:
        return f"not read: {exc}"


def test_a_folder_named_src_is_no_workspace(home):
    text = expand_file(home / "src" / "robot" / "robot.urdf.xacro")
    assert "package 'other' not found" in text and SECRET not in text


@pytest.mark.parametrize("mark", [*WORKSPACE_MARKS, "build", "install/setup.bash"])
def test_a_workspace_is_known_by_its_build_tools_marks(home, mark):
    target = home / mark
    target.parent.mkdir(parents=True, exist_ok=True)
    if mark == ".catkin_tools" or mark == "build":
        target.mkdir()
    else:
        target.write_text("")
    text = expand_file(home / "src" / "robot" / "robot.urdf.xacro")
    counted = mark in WORKSPACE_MARKS  # a bare build/ or a setup file alone is no mark
    assert (SECRET in text) == counted, text


# -- messages never quote what was refused or what is not what it claims ----------------------

@pytest.mark.parametrize("content", [
    f"key: value\n{SECRET}: [unclosed\n",
    f"a: *{SECRET}\n",
    f"a: !{SECRET} 1\n",
    f"[core]\n\textraheader = AUTHORIZATION: basic {SECRET}\n",
    f"\t{SECRET}\n",
])
def test_a_file_that_is_no_yaml_is_never_quoted(tree, content):
    repo = tree / "repo"
    (repo / "config.yaml").write_text(content)
    text = expand(repo, '<link name="${xacro.load_yaml(\'config.yaml\')}"/>')
    assert text.startswith("failed: load_yaml('config.yaml'): not a YAML document"), text
    assert SECRET not in text


def test_an_included_file_that_is_no_xml_is_never_quoted(tree):
    repo = tree / "repo"
    (repo / "notes.xacro").write_text(f"{SECRET} = 1\n")
    text = expand(repo, '<xacro:include filename="notes.xacro"/>')
    assert text.startswith("failed: ") and SECRET not in text
