"""A transmission without a type: no ``<type>`` (ROS 1) or ``<plugin>`` (ROS 2), or an empty one.

ros_control logs "No type element found in transmission 'T'." (or "Skipping empty type
element") and skips the transmission. ros2_control throws "Missing <plugin> tag of
<transmission> element for 'T' in your URDF." for a missing ``<plugin>``; an empty one only
prints "text not specified in the plugin tag" and leaves an empty type no loader matches.
A ROS 1 transmission that has only the pre-Hydro ``type=`` attribute is left to TX302.

Failing example::

    <ros2_control name="arm" type="system">
      <transmission name="t">
        <joint name="j" role="joint1"/>
      </transmission>
    </ros2_control>

Passing example::

    <ros2_control name="arm" type="system">
      <transmission name="t">
        <plugin>transmission_interface/SimpleTransmission</plugin>
        <joint name="j" role="joint1"/>
      </transmission>
    </ros2_control>
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import per_transmission

CODE = "TX101"
NAME = "missing-type"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        element = tx.type_element
        ros1 = tx.ros1
        if element is None:
            if ros1 and tx.element.get("type") is not None:
                continue  # the legacy attribute form: TX302
            if ros1:
                message = f"{tx.label} has no <type>: ros_control skips it"
            else:
                message = (
                    f"{tx.label} has no <plugin>: ros2_control throws "
                    '"Missing <plugin> tag of <transmission> element"'
                )
            yield ctx.problem(CODE, tx.element, message)
        elif not (element.text or "").strip():
            if ros1:
                message = f"{tx.label} has an empty <type>: ros_control skips it"
            else:
                message = f"{tx.label} has an empty <plugin>: no ros2_control loader matches it"
            yield ctx.problem(CODE, element, message)
