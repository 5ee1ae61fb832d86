"""Configuration: discovery, keys, per-rule severity and options, one-line errors (exit 2)."""

from __future__ import annotations

import os

import pytest
from hypothesis import given
from hypothesis import strategies as st

from tests.lint.conftest import BROKEN, WARNING_ONLY
from txtool.lint.config import Config, ConfigError, find_config, load_config, resolve
from txtool.lint.patterns import absolute_folder


def write(path, text):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def test_pyproject_table_is_found_upward_from_the_file(validate, tmp_path):
    write(tmp_path / "pyproject.toml", '[tool.txtool]\nignore = ["TX106"]\n')
    robot = write(tmp_path / "pkg" / "urdf" / "robot.urdf", BROKEN)
    code, out, _ = validate(str(robot))
    assert code == 0 and "TX106" not in out and "TX102" in out


def quiet_loud_and_a_link(tmp_path):
    """A folder ignoring TX106 (quiet), one that does not (loud) holding a link to quiet's robot."""
    write(tmp_path / "quiet" / ".txtool.toml", 'ignore = ["TX106"]\n')
    quiet = write(tmp_path / "quiet" / "robot.urdf", BROKEN)
    loud = write(tmp_path / "loud" / "robot.urdf", BROKEN)
    linked = tmp_path / "loud" / "linked.urdf"
    linked.symlink_to(quiet)
    find_config.cache_clear()
    return quiet, loud, linked


def tx106_paths(out):
    return [line.split(":")[0] for line in out.splitlines() if "TX106" in line]


def test_each_file_gets_its_own_folders_configuration_and_a_link_its_targets(validate, tmp_path):
    quiet, loud, linked = quiet_loud_and_a_link(tmp_path)
    code, out, _ = validate(str(linked), str(loud), str(quiet))  # quiet: the same file again
    assert code == 1 and tx106_paths(out) == [str(loud)]
    assert "in 2 files" in out


def test_a_link_found_in_a_folder_walk_gets_its_targets_configuration(validate, tmp_path):
    _, loud, _ = quiet_loud_and_a_link(tmp_path)
    code, out, _ = validate(str(loud.parent))
    assert code == 1 and tx106_paths(out) == [str(loud)]
    assert "in 2 files" in out


def test_txtool_toml_wins_and_a_pyproject_without_the_table_is_passed_over(validate, tmp_path):
    write(tmp_path / ".txtool.toml", 'select = ["TX106"]\n')
    write(tmp_path / "pkg" / "pyproject.toml", "[project]\nname = 'x'\n")
    robot = write(tmp_path / "pkg" / "robot.urdf", BROKEN)
    find_config.cache_clear()
    code, out, _ = validate(str(robot))
    assert code == 1 and "TX106" in out and "TX102" not in out


def test_per_rule_severity(validate, tmp_path):
    write(tmp_path / ".txtool.toml", '[severity]\nTX102 = "error"\n')
    robot = write(tmp_path / "robot.urdf", WARNING_ONLY)
    code, out, _ = validate(str(robot))
    assert code == 1 and "error TX102 unknown-type" in out


def test_command_line_ignore_extends_and_select_replaces(validate, tmp_path):
    write(tmp_path / ".txtool.toml", 'select = ["TX102"]\n')
    robot = write(tmp_path / "robot.urdf", BROKEN)
    assert validate("--ignore", "TX102", str(robot))[0:2] == (0, "No problems in 1 file.\n")
    assert "TX106" in validate("--select", "TX106", str(robot))[1]


def test_command_line_ignore_adds_to_the_configured_ignore_list(validate, tmp_path):
    """docs/commands.md: ``--ignore`` adds to the configuration's ``ignore``; both apply."""
    write(tmp_path / ".txtool.toml", 'ignore = ["TX106"]\n')
    robot = write(tmp_path / "robot.urdf", BROKEN)
    find_config.cache_clear()
    code, out, _ = validate(str(robot))
    assert code == 0 and "warning TX102" in out and "TX106" not in out
    assert validate("--ignore", "TX102", str(robot)) == (0, "No problems in 1 file.\n", "")


def test_explicit_config_replaces_the_search(validate, tmp_path):
    write(tmp_path / ".txtool.toml", 'ignore = ["TX106", "TX102"]\n')
    other = write(tmp_path / "elsewhere" / "strict.toml", 'select = ["TX106"]\n')
    robot = write(tmp_path / "robot.urdf", BROKEN)
    code, out, _ = validate("--config", str(other), str(robot))
    assert code == 1 and "TX106" in out


@pytest.mark.parametrize(
    ("text", "error"),
    [
        ('[tool.txtool]\nselct = ["TX106"]\n',
         "key 'tool.txtool.selct': unknown key; did you mean 'select'?\n"),
        ('[tool.txtool]\nper-file-ignore = {}\n',
         "key 'tool.txtool.per-file-ignore': unknown key; did you mean 'per-file-ignores'?\n"),
        ('[tool.txtool]\nzzz = 1\n', "key 'tool.txtool.zzz': unknown key\n"),
        ('[tool.txtool]\nselect = ["TX999"]\n', "key 'tool.txtool.select': unknown rule code 'TX999'"),
        ('[tool.txtool]\nignore = "TX106"\n', "key 'tool.txtool.ignore': Input should be a valid"),
        ('[tool.txtool.severity]\nTX106 = "fatal"\n', "key 'tool.txtool.severity.TX106': Input"),
        ('[tool.txtool.severity]\nTX9 = "error"\n', "key 'tool.txtool.severity.TX9': unknown rule code"),
        ('[tool.txtool.rules.TX106]\nx = 1\n', "key 'tool.txtool.rules.TX106': TX106 takes no options"),
        ('[tool.txtool.rules.TX102]\nfamilies = []\n', "key 'tool.txtool.rules.TX102.families': unknown key"),
        ('[tool.txtool.rules.TX102]\nknown-family = []\n',
         "key 'tool.txtool.rules.TX102.known-family': unknown key; did you mean 'known-families'?"),
        ("[tool.txtool\n", "invalid TOML"),
    ],
)
def test_bad_configuration_is_one_line_naming_the_key(validate, tmp_path, text, error):
    config = write(tmp_path / "pyproject.toml", text)
    robot = write(tmp_path / "robot.urdf", BROKEN)
    find_config.cache_clear()
    code, out, err = validate(str(robot))
    assert (code, out) == (2, "")
    assert err.startswith(f"txtool: {config}") and error in err
    assert err.count("\n") == 1


def test_missing_explicit_config_is_exit_2(validate, tmp_path):
    robot = write(tmp_path / "robot.urdf", BROKEN)
    code, _, err = validate("--config", str(tmp_path / "none.toml"), str(robot))
    assert code == 2 and "no such configuration file" in err


def test_xacro_args_and_package_folders_relative_to_the_config(validate, tmp_path):
    (tmp_path / ".git").mkdir()  # a repository: its configuration's folders inside it are read
    write(tmp_path / "deps" / "COLCON_IGNORE", "")  # found by pkg-dirs only, not by the crawl
    write(tmp_path / "deps" / "my_pkg" / "package.xml", "<package><name>my_pkg</name></package>")
    write(tmp_path / "deps" / "my_pkg" / "inc.xacro",
          '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="inc"/></robot>')
    write(tmp_path / "pyproject.toml",
          '[tool.txtool]\npkg-dirs = ["deps"]\n[tool.txtool.xacro-args]\nside = "left_"\n')
    robot = write(tmp_path / "urdf" / "r.urdf.xacro", """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find my_pkg)/inc.xacro"/>
  <link name="$(arg side)base"/>
</robot>
""")
    find_config.cache_clear()
    assert validate(str(robot)) == (0, f"{robot}:1:1: info TX006 no-transmission: no <transmission> in this file: nothing to check\nFound 1 info in 1 file.\n", "")  # expanded: the package and the argument found
    empty = write(tmp_path / "empty.toml", "")
    code, out, _ = validate("--config", str(empty), str(robot))
    assert code == 0  # the package is not at fault, the run lacks it: an info
    assert "info TX002 xacro-failed: not expanded, checked as written only: xacro: package 'my_pkg' not found" in out


def test_no_xacro_checks_the_file_as_written(validate, tmp_path):
    write(tmp_path / ".txtool.toml", "no-xacro = true\n")
    robot = write(tmp_path / "r.urdf.xacro", '<robot name="r"><link name="$(arg x)"/></robot>\n')
    find_config.cache_clear()
    assert validate(str(robot)) == (0, f"{robot}:1:1: info TX006 no-transmission: no <transmission> in this file: nothing to check\nFound 1 info in 1 file.\n", "")
    (tmp_path / ".txtool.toml").unlink()
    find_config.cache_clear()
    assert "TX002" in validate(str(robot))[1]
    assert validate("--no-xacro", str(robot))[0] == 0


def test_resolve_expands_prefixes_and_stamps_options(tmp_path):
    settings = resolve(Config.model_validate(
        {"select": ["TX10"], "ignore": ["TX105"], "rules": {"tx102": {"known-families": ["a/"]}}}
    ))
    assert "TX106" in settings.enabled and "TX105" not in settings.enabled
    assert "TX110" not in settings.enabled and "TX002" not in settings.enabled
    assert settings.options["TX102"].known_families == ["a/"]


def test_load_config_reads_a_txtool_toml(tmp_path):
    path = write(tmp_path / ".txtool.toml", 'ignore = ["TX3"]\n[severity]\nTX102 = "info"\n')
    assert load_config(path) == Config(ignore=["TX3"], severity={"TX102": "info"})
    with pytest.raises(ConfigError, match="unknown rule code"):
        resolve(Config(select=["XX"]), origin=str(path))


@given(st.lists(st.sampled_from(["a", "b.urdf", ".", "..", "", ".x", "..y"]), min_size=1,
                max_size=5), st.booleans())
def test_folders_made_absolute_once_are_those_of_abspath(parts: list[str], rooted: bool) -> None:
    """The folder walk and the settings normalise each folder once; any path gets the folder
    ``os.path.dirname(os.path.abspath(path))`` gives, asked once or twice."""
    path = ("/" if rooted else "") + "/".join(parts)
    known: dict[str, str] = {}
    for _ in range(2):
        assert absolute_folder(path, known) == os.path.dirname(os.path.abspath(path))
