"""The GitHub Action's script and both pre-commit hooks, run the way CI and pre-commit run them."""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

from tests.lint.conftest import BROKEN, CLEAN
from txtool.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / ".github" / "txtool-action.sh"
LEGACY = """<robot name="r">
  <joint name="j" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <transmission name="t" type="transmission_interface/SimpleTransmission">
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def outside_an_event() -> dict[str, str]:
    """This process's environment without the event GitHub would be running the tests for
    (on a pull request, the action reads the base commit's configuration)."""
    return {k: v for k, v in os.environ.items()
            if k not in ("GITHUB_EVENT_NAME", "GITHUB_EVENT_PATH")}


def action_step(step: str, cwd: Path, **env: str) -> subprocess.CompletedProcess[str]:
    """Run one step of action.yml's script with a PATH whose txtool is this checkout's."""
    bin_dir = Path(sys.executable).parent
    variables = {**outside_an_event(), "PATH": f"{bin_dir}{os.pathsep}{os.environ['PATH']}",
                 **env}
    variables.pop("GITHUB_ACTIONS", None)
    return subprocess.run(["bash", str(SCRIPT), step], cwd=cwd, env=variables,
                          capture_output=True, text=True, timeout=120)


@pytest.fixture
def repo(tmp_path) -> Path:
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "broken.urdf").write_text(BROKEN)
    (tmp_path / "urdf" / "clean.urdf").write_text(CLEAN)
    return tmp_path


def test_action_is_a_composite_action_calling_its_script():
    action = yaml.safe_load((ROOT / "action.yml").read_text())
    assert action["runs"]["using"] == "composite"
    assert set(action["inputs"]) == {"paths", "args", "sarif-file", "version", "python-version",
                                     "config", "trust-xacro"}
    validate = next(step for step in action["runs"]["steps"] if step.get("id") == "validate")
    assert validate["env"]["TXTOOL_CONFIG"] == "${{ inputs.config }}"
    assert validate["env"]["TXTOOL_TRUST_XACRO"] == "${{ inputs.trust-xacro }}"
    assert action["inputs"]["trust-xacro"]["default"] == "false"
    cache = next(step for step in action["runs"]["steps"] if "actions/cache" in step.get("uses", ""))
    assert cache["with"] == {"path": "~/.cache/txtool-action",  # the script's default cache
                             "key": "${{ steps.cache-key.outputs.key }}",
                             "restore-keys": "${{ steps.cache-key.outputs.prefix }}"}
    key = next(step for step in action["runs"]["steps"] if step.get("id") == "cache-key")
    assert key["env"]["TXTOOL_VERSION"] == "${{ inputs.version }}"
    scripts = [step["run"] for step in action["runs"]["steps"] if "run" in step]
    assert scripts == [f'bash "$TXTOOL_ACTION_PATH/.github/txtool-action.sh" {step}'
                       for step in ("cache-key", "install", "validate")]
    assert action["outputs"]["exit-code"]["value"] == "${{ steps.validate.outputs.exit-code }}"


def test_action_leaves_the_job_s_python_alone():
    """setup-python changes nothing of the job (update-environment: false); txtool goes into
    a virtual environment of its own, made from that Python, which validate runs."""
    action = yaml.safe_load((ROOT / "action.yml").read_text())
    python = next(step for step in action["runs"]["steps"]
                  if step.get("uses", "").startswith("actions/setup-python"))
    assert python["with"]["update-environment"] is False
    for step in action["runs"]["steps"]:
        if "run" in step:
            assert step["env"]["TXTOOL_PYTHON"] == "${{ steps.python.outputs.python-path }}"
        if step.get("id") in ("validate",) or step.get("name") == "Install txtool":
            assert step["env"]["TXTOOL_VENV"] == "${{ runner.temp }}/txtool-venv"


def test_action_writes_a_job_summary_of_the_same_run(repo, tmp_path):
    summary = tmp_path / "summary.md"
    summary.write_text("earlier step\n")
    (repo / "urdf" / "odd.urdf").write_text(BROKEN.replace('name="t"', 'name="[x](http://e)|t"'))
    done = action_step("validate", repo, TXTOOL_PATHS="urdf", GITHUB_STEP_SUMMARY=str(summary),
                       RUNNER_TEMP=str(tmp_path))
    assert done.returncode == 1 and done.stdout.startswith("::")
    text = summary.read_text()
    assert text.startswith("earlier step\n## txtool validate\n\n2 errors, 2 warnings, 0 infos in "
                           "3 files; 0 unreadable; exit code 1.\n")
    assert "| urdf/broken.urdf:6:24 | error | TX106 zero-reduction | reduction of actuator " in text
    assert "'\\[x\\](http://e)\\|t'" in text  # no link, no extra cell
    assert not list(tmp_path.glob("txtool-summary.*"))  # the JSON report is removed


def test_action_validate_annotates_and_reports_its_exit_code(repo, tmp_path):
    output = tmp_path / "github_output"
    done = action_step("validate", repo, TXTOOL_PATHS="urdf", TXTOOL_ARGS="--select TX1",
                       GITHUB_OUTPUT=str(output))
    assert done.returncode == 1
    lines = done.stdout.splitlines()
    assert lines and all(line.startswith("::") for line in lines)
    assert all("file=urdf/broken.urdf" in line for line in lines)
    assert all(re.search(r"title=TX1\d\d ", line) for line in lines)
    assert output.read_text() == "exit-code=1\n"


def test_action_writes_sarif_and_still_annotates(repo, tmp_path):
    (repo / "taken").write_text("a file, not a folder")
    done = action_step("validate", repo, TXTOOL_PATHS="urdf/clean.urdf urdf/broken.urdf",
                       TXTOOL_SARIF="taken/txtool.sarif")
    assert done.returncode == 2  # no folder can be made for the SARIF file
    assert "taken/txtool.sarif" in done.stderr
    assert done.stdout.startswith("::error file=urdf/broken.urdf,")  # annotated all the same
    done = action_step("validate", repo, TXTOOL_PATHS="urdf/clean.urdf urdf/broken.urdf",
                       TXTOOL_SARIF="out/txtool.sarif")
    assert done.returncode == 1  # its folder made
    log = json.loads((repo / "out" / "txtool.sarif").read_text())
    assert {r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]
            for r in log["runs"][0]["results"]} == {"urdf/broken.urdf"}
    assert done.stdout.startswith("::")


def test_action_on_a_clean_tree_passes(repo):
    (repo / "urdf" / "broken.urdf").unlink()
    done = action_step("validate", repo)
    assert (done.returncode, done.stdout, done.stderr) == (0, "", "")


def recorded_argv(cwd: Path, tmp_path: Path, **env: str) -> tuple[int, list[list[str]], str]:
    """Run the validate step with a fake ``txtool`` first on PATH that records its arguments."""
    fake = tmp_path / "fake-bin"
    fake.mkdir(exist_ok=True)
    log = tmp_path / "argv.log"
    log.unlink(missing_ok=True)
    (fake / "txtool").write_text(
        f"#!{sys.executable}\nimport json, sys\n"
        f"open({str(log)!r}, 'a').write(json.dumps(sys.argv[1:]) + '\\n')\n")
    (fake / "txtool").chmod(0o755)
    variables = {**outside_an_event(), "PATH": f"{fake}{os.pathsep}{os.environ['PATH']}", **env}
    done = subprocess.run(["bash", str(SCRIPT), "validate"], cwd=cwd, env=variables,
                          capture_output=True, text=True, timeout=60)
    calls = [json.loads(line) for line in log.read_text().splitlines()] if log.exists() else []
    return done.returncode, calls, done.stderr


def test_action_paths_are_one_a_line_after_a_double_dash(repo, tmp_path):
    (repo / "my robot").mkdir()
    code, calls, _ = recorded_argv(repo, tmp_path,
                                   TXTOOL_PATHS="--exit-zero\nmy robot\n\n-\r\nurdf/clean.urdf\n")
    assert code == 0
    assert calls == [["validate", "--format", "github", "--",
                      "--exit-zero", "my robot", "./-", "urdf/clean.urdf"]]


@pytest.mark.parametrize(("paths", "expected"), [
    ("urdf/clean.urdf urdf/broken.urdf", ["urdf/clean.urdf", "urdf/broken.urdf"]),  # as before
    ("  my robot  ", ["my robot"]),  # one line naming an existing folder: taken whole
    ("", ["."]),
])
def test_action_one_line_of_paths(repo, tmp_path, paths, expected):
    (repo / "my robot").mkdir()
    _, calls, _ = recorded_argv(repo, tmp_path, TXTOOL_PATHS=paths)
    assert calls == [["validate", "--format", "github", "--", *expected]]


def test_action_config_and_trust_xacro_inputs(repo, tmp_path):
    _, calls, _ = recorded_argv(repo, tmp_path, TXTOOL_PATHS="urdf", TXTOOL_CONFIG="ci/txtool.toml",
                                TXTOOL_TRUST_XACRO="true", TXTOOL_ARGS="--strict",
                                TXTOOL_SARIF="out.sarif")
    assert calls == [  # one run for the annotations and the SARIF report
        ["validate", "--format", "github", "--format", "sarif:out.sarif", "--config",
         "ci/txtool.toml", "--trust-xacro", "--strict", "--", "urdf"],
    ]
    _, calls, _ = recorded_argv(repo, tmp_path, TXTOOL_PATHS="urdf", TXTOOL_TRUST_XACRO="false")
    assert calls == [["validate", "--format", "github", "--", "urdf"]]
    code, calls, err = recorded_argv(repo, tmp_path, TXTOOL_TRUST_XACRO="yes")
    assert (code, calls) == (2, [])
    assert err == "txtool action: trust-xacro: expected true or false, got 'yes'\n"


def fake_installers(tmp_path: Path, *, uv: bool) -> tuple[dict[str, str], Path]:
    """A PATH whose ``python`` (and ``uv``) log their arguments and cache folder to the log
    returned, one JSON line a call; ``pip wheel`` leaves a wheel in its --wheel-dir. Only the
    digest script (``python -``) runs for real. No uv of the machine's is on this PATH."""
    fake = tmp_path / "fake-bin"
    fake.mkdir()
    log = tmp_path / "install.log"
    (fake / "python").write_text(
        f"#!{sys.executable}\nimport json, os, sys\n"
        f"if sys.argv[1:2] == ['-']:\n    os.execv({sys.executable!r}, [{sys.executable!r}, *sys.argv[1:]])\n"
        f"open({str(log)!r}, 'a').write(json.dumps([os.environ.get('PIP_CACHE_DIR'), *sys.argv[1:]]) + '\\n')\n"
        "if sys.argv[1:3] == ['-m', 'venv']:\n"
        "    os.makedirs(os.path.join(sys.argv[-1], 'bin'))\n"
        "    os.symlink(sys.argv[0], os.path.join(sys.argv[-1], 'bin', 'python'))\n"
        "if sys.argv[2:4] == ['pip', 'wheel']:\n"
        "    folder = sys.argv[sys.argv.index('--wheel-dir') + 1]\n"
        "    open(os.path.join(folder, 'txtool-0.1.0-py3-none-any.whl'), 'w').close()\n")
    if uv:
        (fake / "uv").write_text(
            f"#!{sys.executable}\nimport json, os, sys\n"
            f"open({str(log)!r}, 'a').write(json.dumps(['uv', os.environ.get('UV_CACHE_DIR'), *sys.argv[1:]]) + '\\n')\n")
        (fake / "uv").chmod(0o755)
    (fake / "python").chmod(0o755)
    system = [d for d in os.environ["PATH"].split(os.pathsep) if not (Path(d) / "uv").exists()]
    return {**os.environ, "PATH": os.pathsep.join([str(fake), *system])}, log


def install(env: dict[str, str], log: Path, **inputs: str) -> tuple[int, str, list[list[str]]]:
    log.unlink(missing_ok=True)
    done = subprocess.run(["bash", str(SCRIPT), "install"], env={**env, **inputs},
                          capture_output=True, text=True, timeout=60)
    calls = [json.loads(line) for line in log.read_text().splitlines()] if log.exists() else []
    return done.returncode, done.stderr, calls


@pytest.fixture
def checkout(tmp_path) -> Path:
    """The action's checkout, in a folder whose name holds a space."""
    folder = tmp_path / "the action"
    (folder / "txtool" / "__pycache__").mkdir(parents=True)
    (folder / "pyproject.toml").write_text("[project]\nname = 'txtool'\n")
    (folder / "txtool" / "__init__.py").write_text("__version__ = '0.1.0'\n")
    return folder


def test_action_install_builds_the_checkout_once_and_installs_its_wheel(tmp_path, checkout):
    env, log = fake_installers(tmp_path, uv=False)
    cache = tmp_path / "cache"
    inputs = {"TXTOOL_VERSION": "", "TXTOOL_ACTION_PATH": str(checkout), "TXTOOL_CACHE": str(cache)}
    code, err, calls = install(env, log, **inputs)
    assert (code, err) == (0, "")
    [wheel_call, install_call] = calls
    assert wheel_call[:6] == [str(cache / "pip"), "-m", "pip", "wheel", "--quiet",
                              "--disable-pip-version-check"]
    assert wheel_call[-2:] == ["--", str(checkout)]
    [folder] = (cache / "wheels").iterdir()
    wheel = folder / "txtool-0.1.0-py3-none-any.whl"
    assert install_call == [str(cache / "pip"), "-m", "pip", "install", "--quiet",
                            "--disable-pip-version-check", "--", str(wheel)]
    (checkout / "txtool" / "__pycache__" / "__init__.cpython-311.pyc").write_bytes(b"\0")
    assert install(env, log, **inputs)[2] == [install_call]  # built once: the cached wheel
    (checkout / "txtool" / "__init__.py").write_text("__version__ = '0.1.1'\n")
    code, _, calls = install(env, log, **inputs)
    assert code == 0 and [call[3] for call in calls] == ["wheel", "install"]  # a new checkout
    assert len(list((cache / "wheels").iterdir())) == 2


def cache_key(tmp_path: Path, **env: str) -> dict[str, str]:
    output = tmp_path / "github_output"
    output.unlink(missing_ok=True)
    variables = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
                 "GITHUB_OUTPUT": str(output), "RUNNER_OS": "Linux", **env}
    subprocess.run(["bash", str(SCRIPT), "cache-key"], env=variables, check=True, timeout=60)
    return dict(line.split("=", 1) for line in output.read_text().splitlines())


def test_action_cache_key_holds_no_comma_and_changes_with_the_version(tmp_path):
    version = "{}.{}.{}".format(*sys.version_info[:3])
    pinned = cache_key(tmp_path, TXTOOL_VERSION="txtool>=0.1,<0.2", TXTOOL_ACTION_REF="v0.1.0")
    assert pinned["prefix"] == f"txtool-action-Linux-py{version}-"
    assert re.fullmatch(re.escape(pinned["prefix"]) + "[0-9a-f]{16}", pinned["key"])
    other = cache_key(tmp_path, TXTOOL_VERSION="txtool==0.1.0", TXTOOL_ACTION_REF="v0.1.0")
    moved = cache_key(tmp_path, TXTOOL_VERSION="txtool>=0.1,<0.2", TXTOOL_ACTION_REF="v0.2.0")
    assert len({pinned["key"], other["key"], moved["key"]}) == 3
    assert cache_key(tmp_path, TXTOOL_VERSION="txtool>=0.1,<0.2",
                     TXTOOL_ACTION_REF="v0.1.0") == pinned


def test_action_install_makes_and_fills_a_virtual_environment_of_its_own(tmp_path):
    env, log = fake_installers(tmp_path, uv=False)
    venv = tmp_path / "runner temp" / "txtool-venv"
    python = str(tmp_path / "fake-bin" / "python")
    inputs = {"TXTOOL_VERSION": "txtool==0.1.0", "TXTOOL_CACHE": str(tmp_path / "cache"),
              "TXTOOL_PYTHON": python, "TXTOOL_VENV": str(venv)}
    code, err, calls = install(env, log, **inputs)
    assert (code, err) == (0, "")
    assert calls == [[None, "-m", "venv", "--", str(venv)],
                     [str(tmp_path / "cache" / "pip"), "-m", "pip", "install", "--quiet",
                      "--disable-pip-version-check", "--", "txtool==0.1.0"]]
    assert install(env, log, **inputs)[2] == calls[1:]  # made once


def test_action_install_uses_uv_where_it_is(tmp_path, checkout):
    env, log = fake_installers(tmp_path, uv=True)
    cache = tmp_path / "cache"
    code, _, calls = install(env, log, TXTOOL_VERSION="txtool==0.1.0; os_name == 'posix'",
                             TXTOOL_CACHE=str(cache))
    assert code == 0
    assert calls == [["uv", str(cache / "uv"), "pip", "install", "--quiet", "--python",
                      str(tmp_path / "fake-bin" / "python"), "--",
                      "txtool==0.1.0; os_name == 'posix'"]]  # one argument, as written


def test_action_install_refuses_a_version_that_is_an_option(tmp_path):
    env, log = fake_installers(tmp_path, uv=False)
    code, err, calls = install(env, log, TXTOOL_VERSION="--index-url=https://example.invalid/")
    assert (code, calls) == (2, [])
    assert err == ("txtool action: version: expected a requirement such as txtool==0.1.0, got "
                   "'--index-url=https://example.invalid/'\n")


def test_action_install_without_version_or_checkout_fails(tmp_path):
    env, log = fake_installers(tmp_path, uv=False)
    env.pop("TXTOOL_ACTION_PATH", None)
    code, err, calls = install(env, log, TXTOOL_VERSION="")
    assert code != 0 and calls == []
    assert "TXTOOL_ACTION_PATH is not set" in err


def test_action_one_run_gives_annotations_and_sarif_for_hostile_names(repo, tmp_path):
    """One validate run writes both reports; a SARIF file named like an option, holding a
    space or a colon is a file; one naming an input is refused, the input left as it was."""
    calls = recorded_argv(repo, tmp_path, TXTOOL_PATHS="urdf", TXTOOL_SARIF="--exit-zero")[1]
    assert calls == [["validate", "--format", "github", "--format", "sarif:--exit-zero", "--",
                      "urdf"]]
    for name in ("--exit-zero", "my report.sarif", "a:b.sarif"):
        done = action_step("validate", repo, TXTOOL_PATHS="urdf", TXTOOL_SARIF=name)
        assert done.returncode == 1, done.stderr
        results = json.loads((repo / name).read_text())["runs"][0]["results"]
        annotated = [line for line in done.stdout.splitlines() if line.startswith("::")]
        assert len(results) == len(annotated) > 0
    broken = (repo / "urdf" / "broken.urdf").read_text()
    done = action_step("validate", repo, TXTOOL_PATHS="urdf", TXTOOL_SARIF="urdf/broken.urdf")
    assert done.returncode == 2 and "urdf/broken.urdf" in done.stderr
    assert done.stdout.startswith("::")  # the annotations are written all the same
    assert (repo / "urdf" / "broken.urdf").read_text() == broken


def hooks() -> dict[str, dict]:
    return {hook["id"]: hook for hook in yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())}


def run_hook(hook_id: str, *files: Path) -> tuple[int, str]:
    program, *args = shlex.split(hooks()[hook_id]["entry"])
    assert program == "txtool"
    result = CliRunner().invoke(cli, [*args, *map(str, files)])
    return result.exit_code, result.output


def test_both_hooks_run_on_urdf_xacro_and_xml_files():
    for hook in hooks().values():
        assert hook["language"] == "python"
        assert hook["types_or"] == ["urdf", "xacro", "xml"]
    assert set(hooks()) == {"txtool-validate", "txtool-migrate"}


def test_validate_hook_checks_a_file_staged_twice_once(tmp_path):
    robot = tmp_path / "robot.urdf"
    robot.write_text(BROKEN)
    code, out = run_hook("txtool-validate", robot, robot)
    assert code == 1 and out.splitlines()[-1].endswith(" in 1 file.")


def test_migrate_hook_fixes_staged_files_in_place(tmp_path):
    """pre-commit then stops the commit because a file changed, for the user to review."""
    robot = tmp_path / "robot.urdf"
    robot.write_text(LEGACY)
    code, _ = run_hook("txtool-migrate", robot)
    assert code == 0
    fixed = robot.read_text()
    assert "<type>transmission_interface/SimpleTransmission</type>" in fixed
    assert run_hook("txtool-migrate", robot)[0] == 0 and robot.read_text() == fixed
    assert run_hook("txtool-validate", robot)[0] == 0


def test_hooks_leave_xml_that_is_no_robot_alone(tmp_path):
    package = tmp_path / "package.xml"
    text = "<?xml version=\"1.0\"?>\n<package>\n  <name>my_robot</name>\n</package>\n"
    package.write_text(text)
    assert run_hook("txtool-migrate", package)[0] == 0
    assert package.read_text() == text
    code, out = run_hook("txtool-validate", package)
    assert (code, out) == (0, "No problems in 0 files.\n")


LAUNCH = """<launch>
  <arg name="use_sim_time" default="false"/>
  <node pkg="robot_state_publisher" exec="robot_state_publisher">
    <param name="robot_description"
           value="$(command 'xacro $(find-pkg-share demo_description)/urdf/robot.urdf.xacro')"/>
    <param name="use_sim_time" value="$(var use_sim_time)"/>
  </node>
</launch>
"""
PACKAGE = """<?xml version="1.0"?>
<package format="3">
  <name>demo_description</name>
  <version>0.1.0</version>
  <description>A robot</description>
  <maintainer email="m@example.com">M</maintainer>
  <license>BSD</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <export><build_type>ament_cmake</build_type></export>
</package>
"""
GOOD_XACRO = """<?xml version="1.0"?>
<robot name="demo" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="prefix" default=""/>
  <link name="base"/>
  <link name="arm"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <ros2_control name="demo" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="j1"><command_interface name="position"/><state_interface name="position"/></joint>
    <transmission name="t1">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="j1" role="joint1"><mechanical_reduction>2.0</mechanical_reduction></joint>
      <actuator name="a1" role="actuator1"/>
    </transmission>
  </ros2_control>
</robot>
"""


@pytest.fixture
def ros2_package(tmp_path, monkeypatch) -> list[Path]:
    """A ROS 2 description package as pre-commit stages it: every .xml, .urdf and .xacro."""
    files = {"package.xml": PACKAGE, "launch/robot.launch.xml": LAUNCH,
             "launch/display.xml": LAUNCH, "worlds/empty.sdf":
             '<?xml version="1.0"?>\n<sdf version="1.6"><world name="w"/></sdf>\n',
             "urdf/robot.urdf.xacro": GOOD_XACRO}
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "controllers.yaml").write_text("controller_manager: {}\n")
    monkeypatch.chdir(tmp_path)
    return [Path(name) for name in files]


def test_validate_hook_passes_a_ros2_package_whose_robot_is_good(ros2_package):
    """Launch files (``$(find-pkg-share ...)``, ``$(var ...)``), package.xml and an SDF world
    are no robot descriptions: their root elements say so, and they are passed over quietly."""
    code, out = run_hook("txtool-validate", *ros2_package)
    assert (code, out) == (0, "No problems in 1 file.\n")


def test_validate_hook_still_reports_the_robot_of_that_package(ros2_package):
    robot = Path("urdf/robot.urdf.xacro")
    robot.write_text(GOOD_XACRO.replace("2.0</mechanical", "0</mechanical"))
    code, out = run_hook("txtool-validate", *ros2_package)
    assert code == 1
    assert [line.split(":")[0] for line in out.splitlines()[:-1]] == ["urdf/robot.urdf.xacro"]


def test_a_xacro_library_of_any_root_is_still_checked_when_named(tmp_path):
    library = tmp_path / "arm.xacro"
    library.write_text(BROKEN.replace('<robot name="r">',
                                      '<root xmlns:xacro="http://www.ros.org/wiki/xacro">')
                       .replace("</robot>", "</root>"))
    code, out = run_hook("txtool-validate", library)
    assert code == 1 and "TX106" in out


def test_the_validate_hook_applies_the_configuration_exclude_to_files_named(ros2_package):
    """As ruff's hook passes --force-exclude: pre-commit names files one by one."""
    Path("urdf/old.urdf").write_text(GOOD_XACRO.replace("2.0</mechanical", "0</mechanical"))
    Path(".txtool.toml").write_text('exclude = ["urdf/old.urdf"]\n')
    assert run_hook("txtool-validate", *ros2_package, Path("urdf/old.urdf")) == (
        0, "No problems in 1 file.\n")
    result = CliRunner().invoke(cli, ["validate", "urdf/old.urdf"])
    assert result.exit_code == 1 and "urdf/old.urdf:" in result.output


def test_no_page_sends_users_to_a_release_that_does_not_exist():
    """txtool has no release tag and no release on a package index yet: the action, the
    pre-commit hooks and pip are pointed at the repository's main branch."""
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    for page in pages:
        text = page.read_text()
        assert re.findall(r"rev: (\S+)", text) in ([], ["main"]), page
        assert set(re.findall(r"txtool/txtool@(\S+)", text)) <= {"main"}, page
        # "pip install txtool", "pip install 'txtool[sim]'": from an index that has no txtool
        assert not re.search(r"pip install (['\"]?)txtool(\[[a-z,]+\])?\1(\s|`|$)", text), page


def test_action_on_a_hostile_pull_request(tmp_path):
    """A pull request's files chosen to turn the check green or stall it: a file named like an
    option, a configuration silencing every rule dropped beside its files, a symbolic link loop,
    a FIFO named .gitignore, a folder with a space. Its findings are still reported, the run
    fails, and no name becomes an option."""
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)  # the top of the checkout
    (repo / "urdf").mkdir()
    (repo / "urdf" / "broken.urdf").write_text(BROKEN)
    (repo / "urdf" / ".txtool.toml").write_text('ignore = ["ALL"]\nexclude = ["*"]\n')
    (repo / "urdf" / "l1.urdf").symlink_to("l2.urdf")
    (repo / "urdf" / "l2.urdf").symlink_to("l1.urdf")
    os.mkfifo(repo / "urdf" / ".gitignore")
    (repo / "--exit-zero").write_text(BROKEN)
    (repo / "my robot").mkdir()
    (repo / "my robot" / "arm.urdf").write_text(BROKEN)
    output = tmp_path / "github_output"
    done = action_step("validate", repo, TXTOOL_PATHS="--exit-zero\nurdf\nmy robot\n",
                       GITHUB_OUTPUT=str(output))
    assert done.returncode == 2 and output.read_text() == "exit-code=2\n"
    found = {re.search(r"file=([^,]+),.*title=(\w+)", line).groups()
             for line in done.stdout.splitlines() if line.startswith("::error ")}
    assert {file for file, title in found if title.startswith("TX")} == {
        "--exit-zero", "urdf/broken.urdf", "my robot/arm.urdf"}  # checked, each one
    assert {file for file, title in found if title == "txtool"} == {
        "urdf/.gitignore", "urdf/l1.urdf", "urdf/l2.urdf"}  # could not be read: exit 2
    config = repo / "urdf" / ".txtool.toml"
    assert done.stderr.splitlines() == [
        f"txtool: note: {config}: not read: a configuration below the repository's root is "
        "passed over (the defaults apply; --config names the file to use)",
        "txtool: urdf/l1.urdf: symbolic link loop (too many levels of symbolic links)",
        "txtool: urdf/l2.urdf: symbolic link loop (too many levels of symbolic links)",
        "txtool: urdf/.gitignore: is a named pipe (FIFO), not a regular file; txtool reads only "
        "regular files (or '-')",
    ]


def test_action_on_a_pull_request_whose_xacro_attacks_the_runner(tmp_path):
    """A pull request's xacro that tries to run code and to read the runner's secret into the
    report: with the Action's defaults nothing runs, the secret is in no output (annotations,
    log, SARIF), the attacks are refused one line each, and the other findings are reported."""
    secret = "ghp_not_a_real_token_0123456789"
    marker = tmp_path / "pwned"
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (repo / "urdf").mkdir()
    (repo / "urdf" / "broken.urdf").write_text(BROKEN)
    head = '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
    (repo / "urdf" / "run.urdf.xacro").write_text(
        f"""{head}<link name="${{open('{marker}', 'w').write('x')}}"/></robot>""")
    (repo / "urdf" / "leak.urdf.xacro").write_text(
        f'{head}<link name="$(env GITHUB_TOKEN)"/><link name="$(optenv GITHUB_TOKEN none)"/>'
        "</robot>")
    (repo / "urdf" / "escape.urdf.xacro").write_text(
        head + "<link name=\"${''.__class__.__mro__[1].__subclasses__()}\"/></robot>")
    sarif = tmp_path / "report.sarif"
    done = action_step("validate", repo, TXTOOL_PATHS="urdf", TXTOOL_SARIF=str(sarif),
                       GITHUB_TOKEN=secret)
    assert not marker.exists()
    assert secret not in done.stdout + done.stderr + sarif.read_text()
    assert done.returncode == 2  # the refused files could not be checked
    refused = {re.search(r"file=([^,]+),", line).group(1) for line in done.stdout.splitlines()
               if line.startswith("::error ") and "title=txtool::" in line}
    assert refused == {"urdf/leak.urdf.xacro", "urdf/escape.urdf.xacro"}
    # open is no name the restricted evaluator knows: the expansion fails as any other would
    assert any("title=TX002" in line and "file=urdf/run.urdf.xacro" in line
               and "name 'open' is not defined" in line for line in done.stdout.splitlines())
    assert any("title=TX106" in line and "file=urdf/broken.urdf" in line
               for line in done.stdout.splitlines())
    results = json.loads(sarif.read_text())["runs"][0]["results"]
    assert {r["ruleId"] for r in results} >= {"TX106"}
