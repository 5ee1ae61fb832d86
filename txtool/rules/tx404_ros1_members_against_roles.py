"""A ROS 1 coupled transmission whose members are listed against their roles.

What it does: reports a ROS 1 Differential or FourBarLinkage transmission whose two joints, or
two actuators, have valid distinct roles written in the reverse order (``joint2`` listed before
``joint1``, ``actuator2`` before ``actuator1``). ``txtool show --effective`` shows the binding;
``map``, ``equivalence`` and ``simulate`` use it.

Why it matters: ros_control takes the reductions and offsets by ``<role>`` ("Indices sorted
according to role"), but fills the data vectors the maths maps in XML order:
``jnt_state_data.position[i]`` is ``transmission_info.joints_[i]``, and nothing reorders
``joints_`` in between. So the member listed first is driven with the values written on the
``joint1`` member: the reduction and offset land on the other joint, silently.

Loader: ros_control (ros-controls/ros_control
transmission_interface/src/four_bar_linkage_transmission_loader.cpp:49 @17b626a and the
differential loader's ``getJointConfig``;
transmission_interface/src/joint_state_interface_provider.cpp:132 @133d768, actuators through
``getActuatorHandles(transmission_info.actuators_)`` in the same file;
transmission_interface_loader.cpp ``TransmissionInterfaceLoader::load``).

Failing example::

    <robot name="r">
      <transmission name="wrist">
        <type>transmission_interface/DifferentialTransmission</type>
        <joint name="wrist_flex">
          <role>joint2</role><mechanicalReduction>-2</mechanicalReduction>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <joint name="wrist_roll">
          <role>joint1</role><mechanicalReduction>2</mechanicalReduction>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m1">
          <role>actuator1</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
        <actuator name="m2">
          <role>actuator2</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Expected finding: ``4:5 error TX404 transmission 'wrist': joint 'wrist_flex' (role joint2) is
listed before 'wrist_roll' (role joint1); ros_control takes the values by role but the joint
data in XML order, so 'wrist_flex' is driven with the values written on 'wrist_roll' and the
other way round: list the joints in role order``

Passing example::

    <robot name="r">
      <transmission name="wrist">
        <type>transmission_interface/DifferentialTransmission</type>
        <joint name="wrist_roll">
          <role>joint1</role><mechanicalReduction>2</mechanicalReduction>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <joint name="wrist_flex">
          <role>joint2</role><mechanicalReduction>-2</mechanicalReduction>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m1">
          <role>actuator1</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
        <actuator name="m2">
          <role>actuator2</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Fix: list the members in the order of their roles (``joint1`` first, ``actuator1`` first).
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import coupled_groups, label, per_transmission

CODE = "TX404"
NAME = "ros1-members-against-roles"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if not tx.ros1 or tx.kind not in ("differential", "four_bar"):
            continue
        from txtool.model.semantics import against_roles  # for coupled transmissions only

        found = tx.found
        for noun, members, elements, roles in coupled_groups(tx):
            if len(members) != 2 or not against_roles(members, roles):
                continue
            first, second = members
            yield ctx.problem(
                CODE,
                elements[0],
                f"{label(found)}: {noun} '{first.name}' (role {first.role}) is listed before "
                f"'{second.name}' (role {second.role}); ros_control takes the values by role "
                f"but the {noun} data in XML order, so '{first.name}' is driven with the "
                f"values written on '{second.name}' and the other way round: list the "
                f"{noun}s in role order",
            )
