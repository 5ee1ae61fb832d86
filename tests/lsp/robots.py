"""The robot documents the language-server tests edit, as a user types them."""

from __future__ import annotations

# A ROS 1 transmission: an interface without its prefix (TX300, fixable; ros_control finds no
# valid interface, which TX300 says at TX205's severity) and a zero actuator reduction (TX106)
# on line 16.
ARM = """\
<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <link name="upper"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="upper"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <transmission name="shoulder_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="shoulder">
      <hardwareInterface>PositionJointInterface</hardwareInterface>
    </joint>
    <actuator name="shoulder_motor">
      <mechanicalReduction>0</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""
REDUCTION_LINE = 15  # 0-based, as the protocol counts
REDUCTION = "      <mechanicalReduction>0</mechanicalReduction>"

# The same robot written in xacro: the reduction is a property.
ARM_XACRO = (ARM.replace('<robot name="arm">',
                         '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                         '  <xacro:property name="ratio" value="0"/>')
             .replace("PositionJointInterface", "hardware_interface/PositionJointInterface")
             .replace(">0</mechanicalReduction>", ">${ratio}</mechanicalReduction>"))
