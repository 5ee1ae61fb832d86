"""gazebo_ros_control: the loader of a ROS 1 robot described for Gazebo.

A ``<gazebo><plugin filename="libgazebo_ros_control.so">`` hands the robot's transmissions to
a ``RobotHWSim`` plugin named by ``<robotSimType>``, by default
``gazebo_ros_control/DefaultRobotHWSim`` (ros-simulation/gazebo_ros_pkgs
gazebo_ros_control/src/gazebo_ros_control_plugin.cpp, ``Load``). Plugins built on it, such
as baxter_gazebo's ``libbaxter_gazebo_ros_control.so`` (RethinkRobotics/baxter_simulator
baxter_gazebo/src/baxter_gazebo_ros_control_plugin.cpp @1224c44: it derives from
``GazeboRosControlPlugin`` and calls its ``Load``), behave the same.

DefaultRobotHWSim does not use ros_control's ``TransmissionInterfaceLoader``
(gazebo_ros_control/src/default_robot_hw_sim.cpp, ``initSim`` @01c3a2c): it reads each
transmission's first joint and that joint's first ``<hardwareInterface>``; it accepts
``EffortJointInterface``, ``PositionJointInterface`` and ``VelocityJointInterface`` with or
without the ``hardware_interface/`` prefix (a deprecation warning for the unprefixed form),
takes the actuator's interface when the joint names none (with a warning), never reads
``<mechanicalReduction>``, and refuses the robot ("No matching hardware interface found") for
any other interface name.
"""

from __future__ import annotations

from lxml import etree

from txtool.io.xmlio import local

DEFAULT_SIM = "gazebo_ros_control/DefaultRobotHWSim"
ACCEPTED = frozenset(
    prefix + kind + "JointInterface"
    for prefix in ("", "hardware_interface/")
    for kind in ("Effort", "Position", "Velocity")
)


def default_robot_hw_sim(root: etree._Element) -> etree._Element | None:
    """The plugin element loading the robot through DefaultRobotHWSim, or None."""
    for plugin in root.iter("{*}plugin", "plugin"):
        parent = plugin.getparent()
        if parent is None or not isinstance(parent.tag, str) or local(parent) != "gazebo":
            continue
        if not (plugin.get("filename") or "").strip().endswith("gazebo_ros_control.so"):
            continue
        sim_type = [c for c in plugin if isinstance(c.tag, str) and local(c) == "robotSimType"]
        if not sim_type or (sim_type[0].text or "").strip() == DEFAULT_SIM:
            return plugin
    return None


def accepts(interface: str) -> bool:
    """Whether DefaultRobotHWSim drives a joint through this ``<hardwareInterface>`` text."""
    return interface.strip() in ACCEPTED


def loaded_here(plugin: etree._Element) -> str:
    """How a message names the plugin."""
    filename = (plugin.get("filename") or "").strip()
    return f"gazebo_ros_control (run by this robot's <gazebo> plugin {filename})"
