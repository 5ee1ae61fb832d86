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
any other interface name. franka_gazebo's ``FrankaHWSim``, named by ``<robotSimType>``, does
not read reductions either, but takes only prefixed interface names.
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


FRANKA_SIM = "franka_gazebo/FrankaHWSim"
# RobotHWSim plugins whose source says how they read transmissions. franka_gazebo's
# FrankaHWSim (frankaemika/franka_ros franka_gazebo/src/franka_hw_sim.cpp ``initSim``
# @005ff25) reads SimpleTransmission joints and their prefixed interfaces, never reductions.
KNOWN_SIMS = (DEFAULT_SIM, FRANKA_SIM)


class Sim:
    """The ``<gazebo>`` plugin that loads the robot, and the RobotHWSim type it runs."""

    def __init__(self, plugin: etree._Element, sim_type: str) -> None:
        self.plugin = plugin
        self.sim_type = sim_type

    @property
    def default(self) -> bool:
        return self.sim_type == DEFAULT_SIM

    def describe(self) -> str:
        filename = (self.plugin.get("filename") or "").strip()
        loader = "gazebo_ros_control" if self.default else self.sim_type
        return f"{loader} (run by this robot's <gazebo> plugin {filename})"


def robot_hw_sim(root: etree._Element) -> Sim | None:
    """The plugin loading the robot through a RobotHWSim whose rules are known, or None."""
    for plugin in root.iter("{*}plugin", "plugin"):
        parent = plugin.getparent()
        if parent is None or not isinstance(parent.tag, str) or local(parent) != "gazebo":
            continue
        if not (plugin.get("filename") or "").strip().endswith("gazebo_ros_control.so"):
            continue
        named = [c for c in plugin if isinstance(c.tag, str) and local(c) == "robotSimType"]
        sim_type = (named[0].text or "").strip() if named else DEFAULT_SIM
        if sim_type in KNOWN_SIMS:
            return Sim(plugin, sim_type)
    return None


def accepts(interface: str) -> bool:
    """Whether DefaultRobotHWSim drives a joint through this ``<hardwareInterface>`` text."""
    return interface.strip() in ACCEPTED
