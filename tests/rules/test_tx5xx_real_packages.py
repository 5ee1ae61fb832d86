"""Real controller configurations against the real robots they drive: nothing the controller
manager accepts is an error, and what it refuses is.

rrbot: the workspace's ``rrbot_description`` (../shared/workspace, gazebo_ros_demos) with
``rrbot_control/config/rrbot_control.yaml`` of the same repository (ros-simulation/
gazebo_ros_demos @64e9200, BSD), written beside it here as its package keeps it.
"""

from __future__ import annotations

import shutil

import txtool
from tests.corpus import workspace_dir

RRBOT_CONTROL = """\
rrbot:
  # Publish all joint states -----------------------------------
  joint_state_controller:
    type: joint_state_controller/JointStateController
    publish_rate: 50

  # Position Controllers ---------------------------------------
  joint1_position_controller:
    type: effort_controllers/JointPositionController
    joint: joint1
    pid: {p: 100.0, i: 0.01, d: 10.0}
  joint2_position_controller:
    type: effort_controllers/JointPositionController
    joint: joint2
    pid: {p: 100.0, i: 0.01, d: 10.0}
"""
CONTROL_PACKAGE = """<?xml version="1.0"?>
<package><name>rrbot_control</name><version>0.0.0</version><description>d</description>
<maintainer email="m@example.com">m</maintainer><license>BSD</license>
<buildtool_depend>catkin</buildtool_depend></package>
"""


def rrbot_workspace(tmp_path, control: str):
    """The workspace's rrbot_description beside an rrbot_control package holding
    ``control``, as gazebo_ros_demos keeps them."""
    src = tmp_path / "src"
    shutil.copytree(workspace_dir() / "src" / "rrbot_description", src / "rrbot_description")
    (src / "rrbot_control" / "config").mkdir(parents=True)
    (src / "rrbot_control" / "package.xml").write_text(CONTROL_PACKAGE)
    (src / "rrbot_control" / "config" / "rrbot_control.yaml").write_text(control)
    return src


def test_rrbot_with_its_controllers_has_no_controller_finding(tmp_path):
    src = rrbot_workspace(tmp_path, RRBOT_CONTROL)
    found = txtool.validate([str(src)], pkg_dirs=[str(src)])
    assert [p for p in found if p.code >= "TX500"] == []


def test_rrbot_with_position_controllers_is_refused(tmp_path):
    """Its transmissions give effort handles only: ros_control's manager refuses a
    position_controllers controller ("This controller requires a hardware interface of type
    'hardware_interface::PositionJointInterface'")."""
    src = rrbot_workspace(tmp_path, RRBOT_CONTROL.replace("effort_controllers/",
                                                          "position_controllers/"))
    found = [p for p in txtool.validate([str(src)], pkg_dirs=[str(src)]) if p.code >= "TX500"]
    assert [(p.path.rsplit("/", 1)[-1], p.line, p.column, p.code, p.severity) for p in found] == [
        ("rrbot_control.yaml", 8, 3, "TX501", "error"),
        ("rrbot_control.yaml", 12, 3, "TX501", "error")]
    assert found[0].message.endswith("This controller requires a hardware interface of type "
                                     "'hardware_interface::PositionJointInterface'")
