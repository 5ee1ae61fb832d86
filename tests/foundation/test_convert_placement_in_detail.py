"""ROS 1 -> ROS 2 placement decisions in the cases tests/foundation/test_convert_accepted.py
leaves out: a joint whose type a xacro condition decides, a file that binds the xacro prefix
to a namespace of its own, and a mimic joint that commands nothing."""

from __future__ import annotations

from tests.foundation.test_convert_accepted import _declarations, _joint, _robot, _transmission


def test_a_joint_under_a_xacro_condition_is_not_judged_by_its_type(run, tmp_path):
    """The condition decides whether the fixed joint is the robot's: the transmission is
    converted, not left as written for a refusal that may not happen."""
    flange = _joint("flange", "fixed", 1, 2)
    robot = _robot(_joint("shoulder"), flange, _transmission("flange_trans", "flange")).replace(
        '<robot name="gripper">', '<robot name="arm" xmlns:xacro="http://ros.org/wiki/xacro">'
    ).replace(flange, f'  <xacro:if value="$(arg tool)">{flange.strip()}</xacro:if>\n')
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(robot)
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert code == 0 and "left as written" not in err
    assert list(_declarations(out)) == ["flange"]


def test_a_file_with_the_xacro_prefix_bound_elsewhere_may_get_its_joints_elsewhere(
        run, tmp_path):
    """Old files bind xacro: to Gazebo's schema URI; xacro reads the prefix all the same, so
    the file is no whole robot and a joint it lacks may come from its includer."""
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(_robot(_joint("shoulder"), _transmission("elbow_trans", "elbow")).replace(
        '<robot name="gripper">', '<robot name="arm" xmlns:xacro='
        '"http://playerstage.sourceforge.net/gazebo/xmlschema/#interface">'))
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert code == 0 and "not found in URDF" not in err
    assert list(_declarations(out)) == ["elbow"]


def test_a_mimic_joint_that_only_reads_is_declared_as_it_is(run, tmp_path):
    path = tmp_path / "gripper.urdf"
    path.write_text(_robot(
        _joint("left", "prismatic", 0, 1), _joint("right", "prismatic", 0, 2, mimic="left"),
        _transmission("left_trans", "left"),
        _transmission("right_trans", "right", "hardware_interface/JointStateInterface")))
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert code == 0 and "mimics" not in err
    assert _declarations(out) == {"left": (None, ["effort"]), "right": (None, [])}


def test_the_next_steps_of_an_ament_package_whose_robot_names_its_gazebo_plugin(
        run, tmp_path, monkeypatch):
    """The plugin is said once, by the file that holds it (an empty <robotNamespace> says no
    namespace); an ament package needs no new build type."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "arm").mkdir()
    (tmp_path / "arm" / "package.xml").write_text(
        '<package format="3"><name>arm</name><buildtool_depend>ament_cmake</buildtool_depend>'
        "<export><build_type>ament_cmake</build_type></export></package>\n")
    plugin = ('  <gazebo><plugin name="control" filename="libgazebo_ros_control.so">'
              "<robotNamespace> </robotNamespace></plugin></gazebo>\n")
    (tmp_path / "arm" / "arm.urdf").write_text(
        _robot(_joint("shoulder"), _transmission("shoulder_trans", "shoulder"), plugin))
    code, _, err = run("migrate", "--write", "--to", "ros2-p2", "arm")
    assert code == 0, err
    steps = [line for line in err.splitlines() if "gazebo_ros_control" in line
             or "builds with" in line]
    assert len(steps) == 1 and steps[0].startswith(
        "warning: arm/arm.urdf: the robot's <gazebo> plugin 'libgazebo_ros_control.so' (line 9) "
        "is ROS 1's gazebo_ros_control")
    assert steps[0].endswith("hardware gz_ros2_control/GazeboSimSystem)")
