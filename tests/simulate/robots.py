"""Tiny robots for the simulate tests, written inline."""

from __future__ import annotations

from pathlib import Path

EFFORT = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"


def link(name: str, mass: float, com: float, inertia: float = 1e-3, axis_inertia: str = "iyy"
         ) -> str:
    values = {"ixx": 1e-4, "iyy": 1e-4, "izz": 1e-4}
    values[axis_inertia] = inertia
    return (f'<link name="{name}"><inertial><origin xyz="{com} 0 0"/><mass value="{mass}"/>'
            f'<inertia ixx="{values["ixx"]}" iyy="{values["iyy"]}" izz="{values["izz"]}" '
            'ixy="0" ixz="0" iyz="0"/></inertial></link>')


def pendulum(mass: float, length: float, reduction: float) -> str:
    """A point mass on a massless rod, joint about -y (positive angle lifts the mass)."""
    return f"""<robot name="pendulum">
  <link name="base"/>
  <link name="rod"><inertial><origin xyz="{length} 0 0"/><mass value="{mass}"/>
    <inertia ixx="1e-9" iyy="1e-9" izz="1e-9" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="swing" type="revolute"><parent link="base"/><child link="rod"/>
    <axis xyz="0 -1 0"/><limit lower="-3" upper="3" effort="100" velocity="5"/></joint>
  <transmission name="t_swing">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="swing">{EFFORT}</joint>
    <actuator name="m_swing"><mechanicalReduction>{reduction}</mechanicalReduction></actuator>
  </transmission>
</robot>"""


def planar_two_link(m1: float, m2: float, l1: float, lc1: float, lc2: float, i1: float,
                    i2: float) -> str:
    """Two links in the x-z plane, both joints about -y, no transmissions."""
    return f"""<robot name="planar">
  <link name="base"/>
  {link("a", m1, lc1, i1)}
  {link("b", m2, lc2, i2)}
  <joint name="q1" type="revolute"><parent link="base"/><child link="a"/>
    <axis xyz="0 -1 0"/><limit lower="-3" upper="3" effort="100" velocity="5"/></joint>
  <joint name="q2" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="{l1} 0 0"/><axis xyz="0 -1 0"/>
    <limit lower="-3" upper="3" effort="100" velocity="5"/></joint>
</robot>"""


ARM_BODY = f"""
  <link name="base"/>
  {link("l1", 1.0, 0.25, 0.02)}
  {link("l2", 0.8, 0.2, 0.01)}
  {link("l3", 0.3, 0.1, 0.002, "izz")}
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="40" velocity="3"/>
    <dynamics damping="0.05"/></joint>
  <joint name="elbow" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.5 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="20" velocity="3"/></joint>
  <joint name="wrist" type="revolute"><parent link="l2"/><child link="l3"/>
    <origin xyz="0.4 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="3"/></joint>
"""

ARM_ROS1_SHOULDER = f"""
  <transmission name="t_shoulder">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="shoulder">{EFFORT}</joint>
    <actuator name="m_shoulder"><mechanicalReduction>{{n}}</mechanicalReduction></actuator>
  </transmission>"""

ARM_ROS1_WRIST = f"""
  <transmission name="t_wrist">
    <type>transmission_interface/{{kind}}</type>
    <joint name="{{j1}}"><role>joint1</role><offset>{{offset}}</offset>{EFFORT}</joint>
    <joint name="{{j2}}"><role>joint2</role>{EFFORT}</joint>
    <actuator name="m_left"><role>actuator1</role><mechanicalReduction>30</mechanicalReduction>
    </actuator>
    <actuator name="m_right"><role>actuator2</role><mechanicalReduction>20</mechanicalReduction>
    </actuator>
  </transmission>
"""

# The same transmissions as ros2_control writes them (joint reduction for simple, roles as
# attributes, handles ordered by name: elbow < wrist, m_left < m_right).
ARM_ROS2_TRANSMISSIONS = """
  <ros2_control name="arm" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="shoulder"><command_interface name="effort"/><state_interface name="position"/>
    </joint>
    <joint name="elbow"><command_interface name="effort"/><state_interface name="position"/>
    </joint>
    <joint name="wrist"><command_interface name="effort"/><state_interface name="position"/>
    </joint>
    <transmission name="t_shoulder">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <actuator name="m_shoulder" role="actuator1"/>
      <joint name="shoulder" role="joint1"><mechanical_reduction>50</mechanical_reduction></joint>
    </transmission>
    <transmission name="t_wrist">
      <plugin>transmission_interface/DifferentialTransmission</plugin>
      <actuator name="m_left" role="actuator1"><mechanical_reduction>30</mechanical_reduction>
      </actuator>
      <actuator name="m_right" role="actuator2"><mechanical_reduction>20</mechanical_reduction>
      </actuator>
      <joint name="elbow" role="joint1"><offset>0.1</offset></joint>
      <joint name="wrist" role="joint2"/>
    </transmission>
  </ros2_control>
"""


def arm_ros1(n: float | str = 50, offset: float = 0.1, swap: bool = False, extra: str = "",
             shoulder: bool = True, kind: str = "DifferentialTransmission") -> str:
    """3-DoF arm: simple shoulder, differential elbow/wrist (roles swapped with ``swap``)."""
    j1, j2 = ("wrist", "elbow") if swap else ("elbow", "wrist")
    transmissions = ARM_ROS1_SHOULDER.format(n=n) if shoulder else ""
    transmissions += ARM_ROS1_WRIST.format(j1=j1, j2=j2, offset=offset, kind=kind)
    return f'<robot name="arm" xmlns:drake="http://drake.mit.edu">{ARM_BODY}' \
           f"{transmissions}{extra}</robot>"


def arm_ros2() -> str:
    return f'<robot name="arm">{ARM_BODY}{ARM_ROS2_TRANSMISSIONS}</robot>'


def arm_both() -> str:
    """The arm with its ROS 1 transmissions and the ros2_control block."""
    return arm_ros1(extra=ARM_ROS2_TRANSMISSIONS)


def with_transmission(robot: str, joint: str, reduction: float = 1.0) -> str:
    """``robot`` with a simple transmission on ``joint``: something for a run to check (a
    robot without any is inconclusive and not simulated)."""
    return robot.replace("</robot>", f"""
  <transmission name="t_{joint}">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="{joint}">{EFFORT}</joint>
    <actuator name="m_{joint}"><mechanicalReduction>{reduction}</mechanicalReduction></actuator>
  </transmission>
</robot>""")


def write(folder: Path, name: str, text: str) -> str:
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return str(path)
