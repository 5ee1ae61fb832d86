"""The transmission's linear map cannot be inverted reliably.

What it does: for a loadable standard transmission, builds the matrix ``A`` with ``actuator
velocity = A · joint velocity`` from the reductions the ROS loader actually binds
(:func:`txtool.model.semantics.effective`) and reports it when it is singular or its 2-norm
condition number exceeds ``max-condition``. Simple transmissions always pass (a 1x1 map).
Transmissions the loader refuses (a zero or non-numeric reduction) are TX106's and other rules'
business. Options (``[tool.txtool.rules.TX403]``): ``max-condition``, the largest acceptable
condition number (default ``1e12``).

Why it matters: ``actuator_to_joint`` applies ``A⁻¹`` and ``joint_to_actuator`` applies ``A``:
with a singular or near-singular ``A`` a tiny encoder reading becomes a huge joint value, or two
joints become indistinguishable from the actuators. A coupled transmission fails when its
reductions differ by many orders of magnitude or underflow.

Loader: the maps of ros_control (ros-controls/ros_control
transmission_interface/include/transmission_interface/differential_transmission.h
``DifferentialTransmission::actuatorToJointPosition``) and ros2_control
(ros-controls/ros2_control
transmission_interface/include/transmission_interface/differential_transmission.hpp
``actuator_to_joint``).

Failing example::

    <robot name="r">
      <transmission name="wrist">
        <type>transmission_interface/DifferentialTransmission</type>
        <joint name="j1">
          <role>joint1</role><mechanicalReduction>1</mechanicalReduction>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <joint name="j2">
          <role>joint2</role><mechanicalReduction>1</mechanicalReduction>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m1">
          <role>actuator1</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
        <actuator name="m2">
          <role>actuator2</role><mechanicalReduction>1e-13</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Expected finding: ``2:3 error TX403 transmission 'wrist': the velocity map A is ill-conditioned
(condition number 5e+14); the joint state cannot be recovered reliably from the actuators``

Passing example::

    <robot name="r">
      <transmission name="wrist">
        <type>transmission_interface/DifferentialTransmission</type>
        <joint name="j1">
          <role>joint1</role><mechanicalReduction>1</mechanicalReduction>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <joint name="j2">
          <role>joint2</role><mechanicalReduction>1</mechanicalReduction>
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

Fix: write the reductions as the mechanism has them (a reduction of ``1e-13`` is a typo for an
exponent, usually).
"""

from __future__ import annotations

from collections.abc import Iterator
from functools import cache
from typing import Any

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import label, per_transmission
from txtool.model.core import Transmission

CODE = "TX403"
NAME = "singular-transmission"
SEVERITY = "error"
FIXABLE = False


@cache
def options_model() -> Any:
    """The pydantic model of this rule's options (built when a configuration names them)."""
    from pydantic import BaseModel, ConfigDict, Field

    from txtool.mechanics.linear import MAX_CONDITION

    class Options(BaseModel):
        model_config = ConfigDict(extra="forbid", populate_by_name=True)

        max_condition: float = Field(default=MAX_CONDITION, gt=1.0, alias="max-condition")

    return Options


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    # A loadable simple map is one finite, non-zero number: never singular. The linear algebra
    # is loaded for documents with other standard transmissions only.
    coupled = [tx for tx in ctx.facts if tx.kind not in ("other", "simple")]
    if not coupled:
        return
    from txtool.mechanics.linear import MAX_CONDITION, condition_number, singular
    from txtool.model.semantics import NotLoadable, effective

    options = ctx.option(CODE)
    max_condition = options.max_condition if options else MAX_CONDITION
    for tx in coupled:
        found = tx.found
        t = found.transmission
        if _has_unknown_number(ctx, t):
            continue
        try:
            loaded = effective(t)
        except NotLoadable:
            continue
        reason = singular(loaded, max_condition)
        if reason is None:
            continue
        yield ctx.problem(
            CODE,
            found.element,
            f"{label(found)}: {reason} (condition number {condition_number(loaded):.3g}); "
            "the joint state cannot be recovered reliably from the actuators",
        )


def _has_unknown_number(ctx: LintContext, t: Transmission) -> bool:
    """A value only xacro can tell (ros2_control would read it as the default meanwhile)."""
    numbers = [
        number
        for member in t.joints + t.actuators
        for number in (member.mechanical_reduction, member.offset)
        if number is not None
    ]
    return any(ctx.unknown(number.text) for number in numbers)
