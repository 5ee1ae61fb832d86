"""A type under ``transmission_interface/`` that is not one of the three standard ones.

What it does: reports a ``<type>`` or ``<plugin>`` under ``transmission_interface/`` other
than ``SimpleTransmission``, ``DifferentialTransmission`` and ``FourBarLinkageTransmission``.
A near-miss of a standard name (``SimpleTansmission``) is a typo: an **error**, with a
suggestion. A name that a package of the workspace, of ``AMENT_PREFIX_PATH`` or of
``ROS_PACKAGE_PATH`` registers with pluginlib (its ``package.xml`` exports
``<transmission_interface plugin="..."/>`` and that file lists a ``<class>`` of that name whose
``base_class_type`` is a ``transmission_interface::`` class) loads: not reported. Any other
name is a **warning**: it loads only where a package registering it is installed, which txtool
cannot see (a vendor may register another name under the same prefix, PAL's
``transmission_interface/HalfDifferentialTransmission``). Types in other namespaces are
TX102's business.

Why it matters: ros_control fails on a name nobody registered with "Failed to load
transmission 'T'. Unsupported type" and stops loading the transmissions after it.
ros2_control's parser copies any text, but the hardware plugin's pluginlib lookup of the loader
fails, so the transmission never exists.

Loader: ros_control registers exactly the three (ros-controls/ros_control
transmission_interface/ros_control_plugins.xml:4-28 @23284e8) and looks the type up by name
(transmission_interface/src/transmission_interface_loader.cpp ``TransmissionInterfaceLoader::load``,
:126-129, :139-147 @0a09467; loader test ``UnsupportedTransmissionType``,
transmission_interface/test/transmission_interface_loader_test.cpp:125-135 @3e1dd9d);
ros2_control (ros-controls/ros2_control hardware_interface/src/component_parser.cpp:480-481
@157446a).

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTansmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``3:5 error TX113 transmission 't' has type
'transmission_interface/SimpleTansmission', not one of the three transmission_interface types:
ros_control refuses it ("Unsupported type"); did you mean
'transmission_interface/SimpleTransmission'?``

Passing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: write one of the three standard names, or install (and declare a dependency on) the
package that registers the type.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import per_transmission
from txtool.model.core import TYPE_PREFIX
from txtool.rules.tx102_unknown_type import STANDARD_NAMES, nearest_standard

CODE = "TX113"
NAME = "unknown-standard-type"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        text = tx.type_text
        if not text or not text.startswith(TYPE_PREFIX) or text in STANDARD_NAMES:
            continue
        if ctx.unknown(text) or ctx.readers.known_type(text) is not None:
            continue  # a value only xacro knows, or a type a package exports with pluginlib
        element = tx.type_element
        effect = (
            "ros_control refuses it (\"Unsupported type\")"
            if tx.ros1
            else "ros2_control parses it, but no transmission loader has that name"
        )
        suggestion = nearest_standard(text)
        if suggestion is None:
            loader = "ros_control" if tx.ros1 else "ros2_control"
            yield ctx.problem(
                CODE, element,
                f"{tx.label} has type '{text}', not one of the three standard "
                "transmission_interface types, and no package found here exports it with "
                f"pluginlib: {loader} loads it only where a package registering it is "
                "installed (\"Unsupported type\" otherwise)",
                loader_severity="warning",
            )
            continue
        yield ctx.problem(
            CODE,
            element,
            f"{tx.label} has type '{text}', not one of the three transmission_interface "
            f"types: {effect}; did you mean '{suggestion}'?",
        )
