"""Controllers as the controller managers read them, and the interfaces each one claims.

A :class:`Controller` is one entry of a controller configuration: its name, its ``type`` (the
pluginlib class name the manager loads) and, worked out from its parameters the way the
controller itself works them out, the joint interfaces it claims (:class:`Claim`).

ROS 1 (ros_control, ros-controls/ros_controllers @678b92a): a controller asks the robot's
``RobotHW`` for one hardware interface class and a handle per joint in it
(controller_interface/include/controller_interface/controller.h:111 in
ros-controls/ros_control @633c374: "This controller requires a hardware interface of type ..."
when the class is not registered; hardware_interface/include/hardware_interface/internal/
resource_manager.h:119: "Could not find resource '...' in '...'" when the joint has no handle).
The class of each standard type is in :data:`ROS1_TYPES`, with the plugin file that exports it.

ROS 2 (ros2_control, ros-controls/ros2_controllers @94e74de): a controller claims
``JOINT/INTERFACE`` command and state interfaces by name (its
``command_interface_configuration``/``state_interface_configuration``); the controller manager
refuses to activate it when one is not available (controller_manager/src/controller_manager.cpp
:4381 and :4416 in ros-controls/ros2_control @53b9999). :func:`ros2_claims` works them out
from the parameters, with each standard controller's defaults.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

ROS1 = "ros1"
ROS2 = "ros2"


@dataclass(frozen=True)
class Claim:
    """One interface a controller needs for one joint: ``command`` (claimed, exclusive) or
    state (read); ``interface`` is a ROS 1 hardware interface class
    (``hardware_interface::EffortJointInterface``) or a ROS 2 interface name (``effort``)."""

    joint: str
    interface: str
    command: bool


@dataclass(frozen=True)
class Controller:
    """One controller of a configuration file, at the 1-based ``line:column`` of its name."""

    name: str
    type: str
    generation: str  # ROS1 or ROS2
    line: int
    column: int
    params: Mapping[str, Any] = field(default_factory=dict, compare=False)
    known: bool = True  # a standard type (or one exported in the workspace)
    claims: tuple[Claim, ...] = ()

    @property
    def joints(self) -> tuple[str, ...]:
        seen: dict[str, None] = {}
        for claim in self.claims:
            seen.setdefault(claim.joint, None)
        return tuple(seen)


HW = "hardware_interface::"
POSITION = HW + "PositionJointInterface"
VELOCITY = HW + "VelocityJointInterface"
EFFORT = HW + "EffortJointInterface"
STATE = HW + "JointStateInterface"
POS_VEL = HW + "PosVelJointInterface"
POS_VEL_ACC = HW + "PosVelAccJointInterface"

# ROS 1: type -> (hardware interface class, parameter naming the joints or None, source).
# The parameter: "joint" a single name, "joints" a list; None: the controller takes no joints
# from its parameters (it reads every handle of the interface, or its joints are elsewhere).
_RC = "ros-controls/ros_controllers"
ROS1_TYPES: dict[str, tuple[str, str | None, str]] = {
    "position_controllers/JointPositionController":
        (POSITION, "joint", "position_controllers/position_controllers_plugins.xml:3"),
    "position_controllers/JointGroupPositionController":
        (POSITION, "joints", "position_controllers/position_controllers_plugins.xml:9"),
    "velocity_controllers/JointVelocityController":
        (VELOCITY, "joint", "velocity_controllers/velocity_controllers_plugins.xml:3"),
    "velocity_controllers/JointPositionController":
        (VELOCITY, "joint", "velocity_controllers/velocity_controllers_plugins.xml:9"),
    "velocity_controllers/JointGroupVelocityController":
        (VELOCITY, "joints", "velocity_controllers/velocity_controllers_plugins.xml:15"),
    "effort_controllers/JointPositionController":
        (EFFORT, "joint", "effort_controllers/effort_controllers_plugins.xml:3"),
    "effort_controllers/JointVelocityController":
        (EFFORT, "joint", "effort_controllers/effort_controllers_plugins.xml:9"),
    "effort_controllers/JointEffortController":
        (EFFORT, "joint", "effort_controllers/effort_controllers_plugins.xml:15"),
    "effort_controllers/JointGroupEffortController":
        (EFFORT, "joints", "effort_controllers/effort_controllers_plugins.xml:21"),
    "effort_controllers/JointGroupPositionController":
        (EFFORT, "joints", "effort_controllers/effort_controllers_plugins.xml:27"),
    # The trajectory controller's hardware-interface adapters (hardware_interface_adapter.h).
    "position_controllers/JointTrajectoryController":
        (POSITION, "joints", "joint_trajectory_controller/ros_control_plugins.xml:3"),
    "velocity_controllers/JointTrajectoryController":
        (VELOCITY, "joints", "joint_trajectory_controller/ros_control_plugins.xml:12"),
    "effort_controllers/JointTrajectoryController":
        (EFFORT, "joints", "joint_trajectory_controller/ros_control_plugins.xml:21"),
    "pos_vel_controllers/JointTrajectoryController":
        (POS_VEL, "joints", "joint_trajectory_controller/ros_control_plugins.xml:30"),
    "pos_vel_acc_controllers/JointTrajectoryController":
        (POS_VEL_ACC, "joints", "joint_trajectory_controller/ros_control_plugins.xml:39"),
    "position_controllers/GripperActionController":
        (POSITION, "joint", "gripper_action_controller/ros_control_plugins.xml:3"),
    "effort_controllers/GripperActionController":
        (EFFORT, "joint", "gripper_action_controller/ros_control_plugins.xml:10"),
    # Reads every handle of JointStateInterface (joint_state_controller.cpp init).
    "joint_state_controller/JointStateController":
        (STATE, None, "joint_state_controller/joint_state_plugin.xml:2"),
    # Wheels from left_wheel/right_wheel (a name or a list): diff_drive_controller.cpp init.
    "diff_drive_controller/DiffDriveController":
        (VELOCITY, None, "diff_drive_controller/diff_drive_controller_plugins.xml:3"),
    # Known types whose joints txtool does not work out (sensors, steering).
    "ackermann_steering_controller/AckermannSteeringController":
        ("", None, "ackermann_steering_controller/ackermann_steering_controller_plugins.xml:3"),
    "four_wheel_steering_controller/FourWheelSteeringController":
        ("", None, "four_wheel_steering_controller/four_wheel_steering_controller_plugins.xml:3"),
    "force_torque_sensor_controller/ForceTorqueSensorController":
        ("", None, "force_torque_sensor_controller/force_torque_sensor_plugin.xml:2"),
    "imu_sensor_controller/ImuSensorController":
        ("", None, "imu_sensor_controller/imu_sensor_plugin.xml:2"),
}

# ROS 2: every controller type ros2_controllers exports (its plugin description files,
# ros-controls/ros2_controllers @94e74de), and those its releases exported before (the
# position/velocity/effort_controllers JointGroup*Controller until 27ea539, the
# gripper_controllers until 0095ef1): a distribution's release may still carry them.
ROS2_TYPES: frozenset[str] = frozenset({
    "ackermann_steering_controller/AckermannSteeringController",
    "admittance_controller/AdmittanceController",
    "battery_state_broadcaster/BatteryStateBroadcaster",
    "bicycle_steering_controller/BicycleSteeringController",
    "chained_filter_controller/ChainedFilter",
    "diff_drive_controller/DiffDriveController",
    "force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster",
    "forward_command_controller/ForwardCommandController",
    "forward_command_controller/MultiInterfaceForwardCommandController",
    "gpio_controllers/GpioCommandController",
    "gps_sensor_broadcaster/GPSSensorBroadcaster",
    "imu_sensor_broadcaster/IMUSensorBroadcaster",
    "joint_state_broadcaster/JointStateBroadcaster",
    "joint_trajectory_controller/JointTrajectoryController",
    "magnetometer_broadcaster/MagnetometerBroadcaster",
    "mecanum_drive_controller/MecanumDriveController",
    "motion_primitives_controllers/MotionPrimitivesForwardController",
    "omni_wheel_drive_controller/OmniWheelDriveController",
    "parallel_gripper_action_controller/GripperActionController",
    "pid_controller/PidController",
    "pose_broadcaster/PoseBroadcaster",
    "range_sensor_broadcaster/RangeSensorBroadcaster",
    "state_interfaces_broadcaster/StateInterfacesBroadcaster",
    "tricycle_controller/TricycleController",
    "tricycle_steering_controller/TricycleSteeringController",
    "position_controllers/JointGroupPositionController",
    "velocity_controllers/JointGroupVelocityController",
    "effort_controllers/JointGroupEffortController",
    "position_controllers/GripperActionController",
    "effort_controllers/GripperActionController",
})

# The interface a forward-command variant fixes (joint_group_position_controller.cpp:27 and its
# velocity/effort siblings, @27ea539^).
_GROUP_INTERFACE = {
    "position_controllers/JointGroupPositionController": "position",
    "velocity_controllers/JointGroupVelocityController": "velocity",
    "effort_controllers/JointGroupEffortController": "effort",
}


def _names(value: Any) -> list[str]:
    """A parameter naming joints or interfaces: one name or a list of names (anything else:
    none). A name holding a launch substitution (``$(var prefix)joint1``, which a launch file
    resolves when it loads the file with substitutions allowed) is unknown: left out."""
    if isinstance(value, str):
        value = [value]
    if isinstance(value, list):
        return [v for v in value if isinstance(v, str) and v and "$(" not in v]
    return []


def ros1_claims(type_: str, params: Mapping[str, Any]) -> tuple[Claim, ...]:
    """The hardware interface handles a ROS 1 controller of ``type_`` asks for."""
    known = ROS1_TYPES.get(type_)
    if known is None or not known[0]:
        return ()
    interface, key, _ = known
    command = interface != STATE
    if type_ == "diff_drive_controller/DiffDriveController":
        joints = _names(params.get("left_wheel")) + _names(params.get("right_wheel"))
    elif key is None:
        joints = []
    else:
        joints = _names(params.get(key))
    return tuple(Claim(joint, interface, command) for joint in joints)


def ros2_claims(type_: str, params: Mapping[str, Any]) -> tuple[Claim, ...]:
    """The ``JOINT/INTERFACE`` command and state interfaces a ROS 2 controller of ``type_``
    claims, from its parameters and the controller's defaults (none for a type txtool does
    not work out)."""
    commands: list[tuple[str, str]] = []
    states: list[tuple[str, str]] = []
    joints = _names(params.get("joints"))
    if type_ == "joint_trajectory_controller/JointTrajectoryController":
        # joint_trajectory_controller/src/joint_trajectory_controller_parameters.yaml:2-48:
        # command_joints (default: joints) x command_interfaces; joints x state_interfaces.
        commanded = _names(params.get("command_joints")) or joints
        commands = [(j, i) for j in commanded for i in _names(params.get("command_interfaces"))]
        states = [(j, i) for j in joints for i in _names(params.get("state_interfaces"))]
    elif type_ == "forward_command_controller/ForwardCommandController":
        # forward_command_controller/src/forward_command_controller_parameters.yaml:2-17.
        commands = [(j, i) for j in joints for i in _names(params.get("interface_name"))]
    elif type_ in _GROUP_INTERFACE:
        commands = [(j, _GROUP_INTERFACE[type_]) for j in joints]
    elif type_ == "forward_command_controller/MultiInterfaceForwardCommandController":
        # multi_interface_forward_command_controller_parameters.yaml: joint, interface_names.
        joint = _names(params.get("joint"))
        commands = [(j, i) for j in joint for i in _names(params.get("interface_names"))]
    elif type_ == "joint_state_broadcaster/JointStateBroadcaster":
        # joint_state_broadcaster.cpp:66: every state interface unless both joints and
        # interfaces are given (then each pair, joint_state_broadcaster_parameters.yaml:8-36).
        interfaces = _names(params.get("interfaces"))
        if joints and interfaces:
            states = [(j, i) for j in joints for i in interfaces]
    elif type_ in ("parallel_gripper_action_controller/GripperActionController",
                   "position_controllers/GripperActionController",
                   "effort_controllers/GripperActionController"):
        # parallel_gripper_action_controller_impl.hpp:431-452 (position command; state
        # default [position, velocity], gripper_action_controller_parameters.yaml:18-20);
        # gripper_controllers' impl.hpp:322-336 @0095ef1^ (its HardwareInterface's command).
        command = "effort" if type_.startswith("effort_") else "position"
        joint = _names(params.get("joint"))
        commands = [(j, command) for j in joint]
        given = params.get("state_interfaces")
        wanted = _names(given) if given is not None and type_.startswith("parallel") else [
            "position", "velocity"]
        states = [(j, i) for j in joint for i in wanted]
    elif type_ == "diff_drive_controller/DiffDriveController":
        # diff_drive_controller.cpp:82-105: velocity command; position state, or velocity
        # with position_feedback false (diff_drive_controller_parameter.yaml:98).
        wheels = _names(params.get("left_wheel_names")) + _names(params.get("right_wheel_names"))
        feedback = "velocity" if params.get("position_feedback") is False else "position"
        commands = [(j, "velocity") for j in wheels]
        states = [(j, feedback) for j in wheels]
    elif type_ == "admittance_controller/AdmittanceController":
        # admittance_controller_parameters.yaml: joints x command_interfaces, state_interfaces.
        commands = [(j, i) for j in joints for i in _names(params.get("command_interfaces"))]
        states = [(j, i) for j in joints for i in _names(params.get("state_interfaces"))]
    return tuple([Claim(j, i, True) for j, i in commands]
                 + [Claim(j, i, False) for j, i in states])


def known_type(type_: str, generation: str, exported: frozenset[str] = frozenset()) -> bool:
    """Whether a standard package, or a package of the workspace (``exported``), provides
    ``type_`` for the controller manager of ``generation``."""
    if type_ in exported:
        return True
    return type_ in (ROS1_TYPES if generation == ROS1 else ROS2_TYPES)


@dataclass(frozen=True)
class Ros2Equivalent:
    """What a ROS 1 controller becomes in ros2_controllers: the type, the parameters that
    say its interfaces, and the ``JOINT/INTERFACE`` claims they make for its joints."""

    type: str
    params: Mapping[str, Any]
    claims: tuple[Claim, ...]
    note: str = ""


_TRAJECTORY = "joint_trajectory_controller/JointTrajectoryController"
_FORWARD = "forward_command_controller/ForwardCommandController"
_PID = "pid_controller/PidController"
# ROS 1 type -> (ROS 2 type, command interfaces, state interfaces, note). The ROS 2 types are
# those ros2_controllers exports (ROS2_TYPES); a PID inside a ROS 1 controller is
# pid_controller's job in ROS 2 (a chainable controller of its own).
_ROS2_OF: dict[str, tuple[str, tuple[str, ...], tuple[str, ...], str]] = {
    "joint_state_controller/JointStateController":
        ("joint_state_broadcaster/JointStateBroadcaster", (), (), ""),
    "position_controllers/JointTrajectoryController":
        (_TRAJECTORY, ("position",), ("position", "velocity"), ""),
    "velocity_controllers/JointTrajectoryController":
        (_TRAJECTORY, ("velocity",), ("position", "velocity"), ""),
    "effort_controllers/JointTrajectoryController":
        (_TRAJECTORY, ("effort",), ("position", "velocity"), ""),
    "pos_vel_controllers/JointTrajectoryController":
        (_TRAJECTORY, ("position", "velocity"), ("position", "velocity"), ""),
    "pos_vel_acc_controllers/JointTrajectoryController":
        (_TRAJECTORY, ("position", "velocity", "acceleration"), ("position", "velocity"), ""),
    "position_controllers/JointPositionController": (_FORWARD, ("position",), (), ""),
    "position_controllers/JointGroupPositionController": (_FORWARD, ("position",), (), ""),
    "velocity_controllers/JointVelocityController": (_FORWARD, ("velocity",), (), ""),
    "velocity_controllers/JointGroupVelocityController": (_FORWARD, ("velocity",), (), ""),
    "effort_controllers/JointEffortController": (_FORWARD, ("effort",), (), ""),
    "effort_controllers/JointGroupEffortController": (_FORWARD, ("effort",), (), ""),
    "effort_controllers/JointPositionController":
        (_PID, ("effort",), ("position",), "its pid gains go to pid_controller's gains"),
    "effort_controllers/JointGroupPositionController":
        (_PID, ("effort",), ("position",), "its pid gains go to pid_controller's gains"),
    "effort_controllers/JointVelocityController":
        (_PID, ("effort",), ("velocity",), "its pid gains go to pid_controller's gains"),
    "velocity_controllers/JointPositionController":
        (_PID, ("velocity",), ("position",), "its pid gains go to pid_controller's gains"),
    "position_controllers/GripperActionController":
        ("parallel_gripper_action_controller/GripperActionController", ("position",),
         ("position", "velocity"), ""),
    "effort_controllers/GripperActionController":
        ("effort_controllers/GripperActionController", ("effort",), ("position", "velocity"),
         "gripper_controllers' type, which ros2_controllers' newest releases no longer ship"),
    "diff_drive_controller/DiffDriveController":
        ("diff_drive_controller/DiffDriveController", ("velocity",), ("position",),
         "its wheels go to left_wheel_names and right_wheel_names"),
}


def ros2_equivalent(controller: Controller) -> Ros2Equivalent | None:
    """What the ROS 1 ``controller`` becomes in ROS 2 (None: no ros2_controllers type does
    its work)."""
    known = _ROS2_OF.get(controller.type)
    if known is None:
        return None
    type_, commands, states, note = known
    joints = controller.joints
    if type_ == _FORWARD:
        params: dict[str, Any] = {"joints": list(joints), "interface_name": commands[0]}
    elif type_ == _PID:
        params = {"dof_names": list(joints), "command_interface": commands[0],
                  "reference_and_state_interfaces": list(states)}
    elif type_ == "diff_drive_controller/DiffDriveController" or not commands:
        params = {}
    elif "GripperActionController" in type_:
        params = {"joint": joints[0] if joints else ""}
    else:
        params = {"joints": list(joints), "command_interfaces": list(commands),
                  "state_interfaces": list(states)}
    claims = tuple([Claim(j, i, True) for j in joints for i in commands]
                   + [Claim(j, i, False) for j in joints for i in states])
    return Ros2Equivalent(type_, params, claims, note)
