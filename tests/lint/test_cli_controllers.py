"""``txtool validate ROBOT --controllers FILE`` and a package walk: the controller files'
findings at the controller's line, with the exit code; a controller file that is not YAML is an
input error (exit 2, one line)."""

from __future__ import annotations

from click.testing import CliRunner

from txtool.cli import cli

ROBOT = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint><actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
CONTROLLERS = """\
robot:
  joint_state_controller:
    type: joint_state_controller/JointStateController
  arm:
    type: position_controllers/JointGroupPositionController
    joints: [j]
"""


def run(*args: str, folder) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["validate", "--color", "never", *args],
                                catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def test_controllers_named_on_the_command_line(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT)
    (tmp_path / "controllers.yaml").write_text(CONTROLLERS)
    code, out, err = run("robot.urdf", "--controllers", "controllers.yaml", folder=tmp_path)
    assert (code, err) == (1, "")
    assert out.splitlines()[0] == (
        "controllers.yaml:4:3: error TX501 controller-command-interface: controller 'arm' "
        "(position_controllers/JointGroupPositionController): joint 'j' has no hardware "
        "interface 'hardware_interface::PositionJointInterface' (it has: "
        "hardware_interface::EffortJointInterface, hardware_interface::JointStateInterface); "
        "the controller manager refuses the controller: This controller requires a hardware "
        "interface of type 'hardware_interface::PositionJointInterface'")
    assert out.splitlines()[-1] == "Found 1 error in 1 file."
    (tmp_path / "controllers.yaml").write_text(CONTROLLERS.replace("position_", "effort_")
                                               .replace("Position", "Effort"))
    code, out, err = run("robot.urdf", "--controllers", "controllers.yaml", folder=tmp_path)
    assert (code, out, err) == (0, "No problems in 1 file.\n", "")


def test_a_package_walk_finds_the_controller_files(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "package.xml").write_text('<package format="3"><name>p</name></package>')
    (tmp_path / "urdf").mkdir()
    (tmp_path / "config").mkdir()
    (tmp_path / "urdf" / "robot.urdf").write_text(ROBOT)
    (tmp_path / "config" / "controllers.yaml").write_text(CONTROLLERS)
    code, out, err = run(".", "--format", "github", folder=tmp_path)
    assert (code, err) == (1, "")
    assert out.startswith("::error file=config/controllers.yaml,line=4,")


def test_a_controller_file_that_is_not_yaml_is_an_input_error(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT)
    (tmp_path / "bad.yaml").write_text("arm: [\n")
    code, out, err = run("robot.urdf", "--controllers", "bad.yaml", folder=tmp_path)
    assert code == 2
    assert "bad.yaml:2: not valid YAML: expected the node content, but found '<stream end>'" in err
    code, out, err = run("robot.urdf", "--controllers", "missing.yaml", folder=tmp_path)
    assert (code, "missing.yaml: no such file" in err) == (2, True)


def test_hostile_controller_files(tmp_path, monkeypatch):
    """Aliases of aliases (a "billion laughs" of mappings) are read once each, and nesting
    too deep for the YAML parser is an input error, not a crash."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT)
    lines = ["a0: &a0 {type: effort_controllers/JointEffortController, joint: j}"]
    lines += [f"a{i}: &a{i} {{" + ", ".join(f"k{j}: *a{i - 1}" for j in range(10)) + "}"
              for i in range(1, 30)]
    (tmp_path / "laughs.yaml").write_text("\n".join(lines) + "\n")
    code, out, err = run("robot.urdf", "--controllers", "laughs.yaml", folder=tmp_path)
    assert (code, out, err) == (0, "No problems in 1 file.\n", "")
    (tmp_path / "deep.yaml").write_text("a: " + "[" * 100000 + "]" * 100000 + "\n")
    code, out, err = run("robot.urdf", "--controllers", "deep.yaml", folder=tmp_path)
    assert code == 2
    assert err.splitlines()[0] == (
        "txtool: deep.yaml: nested too deeply to be a controller configuration")


def test_a_robot_the_run_cannot_expand_may_be_the_one_the_controllers_are_for(
        tmp_path, monkeypatch):
    """A package holds a lower body (joint j) and a full robot whose xacro needs a package the
    run lacks; its controllers drive j and an arm joint: they are the full robot's, so the arm
    joint is not reported as missing from the lower body. Once the full robot is gone, the
    lower body is the only candidate and the missing joint is the manager's refusal."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "package.xml").write_text('<package format="3"><name>p</name></package>')
    (tmp_path / "urdf").mkdir()
    (tmp_path / "config").mkdir()
    (tmp_path / "urdf" / "lower_body.urdf").write_text(ROBOT)
    (tmp_path / "urdf" / "full.urdf.xacro").write_text(
        '<robot name="full" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find hand_description)/urdf/hand.xacro"/>\n</robot>\n')
    both = CONTROLLERS.replace("position_controllers/JointGroupPosition",
                               "effort_controllers/JointGroupEffort").replace(
        "joints: [j]", "joints: [j, arm_1_joint]")
    (tmp_path / "config" / "controllers.yaml").write_text(both)
    code, out, err = run(".", "--format", "concise", folder=tmp_path)
    assert "TX5" not in out and (code, err) == (0, "")
    assert out.splitlines()[0] == ("urdf/full.urdf.xacro:2:28: TX002 not expanded, checked as "
                                   "written only")
    (tmp_path / "urdf" / "full.urdf.xacro").unlink()
    code, out, err = run(".", folder=tmp_path)
    assert (code, err) == (1, "")
    assert out.splitlines()[0].startswith(
        "config/controllers.yaml:4:3: error TX500 controller-joint-not-driven: controller 'arm' "
        "(effort_controllers/JointGroupEffortController): joint 'arm_1_joint' is not a joint of "
        "the robot")


def test_of_robots_with_the_same_joints_the_controllers_own_package_is_chosen(
        tmp_path, monkeypatch):
    """A repository of examples (ros2_control_demos): every example's robot has joint j, and
    each example's bringup/config holds its own controllers. Each file is judged against the
    robot of its own example, not the first robot of the walk."""
    monkeypatch.chdir(tmp_path)
    for example, interface in (("example_1", "Effort"), ("example_2", "Position")):
        (tmp_path / example / "urdf").mkdir(parents=True)
        (tmp_path / example / "config").mkdir()
        (tmp_path / example / "package.xml").write_text(
            f'<package format="3"><name>{example}</name></package>')
        (tmp_path / example / "urdf" / "robot.urdf").write_text(
            ROBOT.replace("EffortJointInterface", f"{interface}JointInterface"))
        (tmp_path / example / "config" / "controllers.yaml").write_text(
            CONTROLLERS.replace("position_controllers/JointGroupPosition",
                                f"{interface.lower()}_controllers/JointGroup{interface}"))
    code, out, err = run(".", folder=tmp_path)
    assert (code, out, err) == (0, "No problems in 2 files.\n", "")


def test_a_controller_finding_spans_the_controllers_name_in_json(tmp_path, monkeypatch):
    import json

    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT)
    (tmp_path / "controllers.yaml").write_text(CONTROLLERS)
    code, out, err = run("robot.urdf", "--controllers", "controllers.yaml", "--format", "json",
                         folder=tmp_path)
    found = json.loads(out)["problems"]
    assert (code, err) == (1, "")
    assert [(p["line"], p["column"], p["end_line"], p["end_column"], p["code"])
            for p in found] == [(4, 3, 4, 6, "TX501")]  # 'arm'
