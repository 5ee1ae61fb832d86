"""A reduction or offset the loader refuses, or reads as a value that is not a finite number.

What it does: reports a reduction or offset the loader reads whose text is no number for it
(``fifty``, an empty element, one that starts with a comment), is out of the range of a
double (``1.8e308``, ``1e-400``), or is ``inf`` or ``nan``. Only values the loader reads are
checked (ROS 1: actuator reductions, joint offsets, and joint reductions of coupled types;
ROS 2: joint reductions and offsets, and actuator reductions of coupled types). Values
containing ``${...}`` in a literal xacro file are unknown and not checked. A valid number
followed by other text loads as that number: TX111's business. Text that Python reads as a
number but C++ does not counts as C++ has it: Arabic-Indic digits and a no-break space before
the number are no number for either loader, and ``1_000`` is none for ros2_control.

Why it matters: ros_control refuses the transmission (an error); ``inf`` and ``nan`` are
accepted and poison every value the transmission maps. ros2_control, on any failure (junk,
``inf``, ``nan``, out of range), **silently** uses the default: 1.0 for
``<mechanical_reduction>``, 0.0 for ``<offset>``. Humble reads with ``istringstream`` and Jazzy
and later with ``from_chars``, which read a few texts differently (``+-1`` is -1 from Jazzy on
and the default on Humble; ``1e-400`` is the default from Jazzy on and 0 on Humble, whose
loader then refuses the transmission: a reduction some build reads as 0 is TX106's): where
nothing says which distribution reads the file, such a value is a **warning** that gives each
distribution's reading; with ``--ros-distro`` (or ``ros-distro`` in the configuration) only that
distribution's reading counts. An empty element has no text for ``GetText()``, so
ros2_control passes over it and uses the default, as if the element were absent: a
**warning**. Both read the first text node only, so ``5<!-- x -->0`` reads as 5 (TX111).

Loader: ros_control converts with ``std::stod(element->GetText())`` and catches
``std::logic_error`` (ros-controls/ros_control transmission_interface/src/transmission_loader.cpp
:60-61, :95-96, :130-131 @63b6afd); ros2_control parses the whole stripped text in the classic
locale (ros-controls/ros2_control hardware_interface/src/component_parser.cpp:161-188,
``get_parameter_value_or`` @53b9999; hardware_interface/src/lexical_casts.cpp:65
``impl::stod``).

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>fifty</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``7:24 error TX105 reduction of actuator 'm' of transmission 't' is 'fifty',
not a number: ros_control refuses the transmission``

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

Fix: write the number in decimal (``50``, ``0.5``, ``-1``).
"""

from __future__ import annotations

import sys
from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import numbers_of, per_transmission, ros2_readings_of
from txtool.model.distro import NumberReading
from txtool.model.numbers import C_SPACE, format_float, parse_ros2, ros2_readings, stod

CODE = "TX105"
NAME = "invalid-number"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        for number in numbers_of(tx):
            if number.unknown:
                continue
            plain = number.strict
            if tx.ros1:
                if plain is not None and abs(plain) >= sys.float_info.min:
                    continue  # a plain number in the range of a double (the common case)
                problem = _ros1(number.text)
            else:
                if plain is not None:
                    continue
                default = "0.0" if number.field == "offset" else "1.0"
                if not number.all_text().strip(C_SPACE):  # empty: read as absent
                    message = (f"{number.describe()} of {tx.label} is empty: ros2_control reads "
                               f"it as absent and uses the default {default}; nothing written "
                               "is lost")
                    yield ctx.problem(CODE, number.element, message, loader_severity="warning")
                    continue
                readings = ros2_readings_of(ctx)
                if number.field == "reduction" and any(
                        parse_ros2(number.text, r) == 0.0 for r in readings):
                    continue  # a build reading zero refuses the transmission: TX106's
                problem = _ros2(number.text, default, readings)
            if problem:
                message = f"{number.describe()} of {tx.label} {problem}"
                readings = ros2_readings_of(ctx)
                differs = not tx.ros1 and any(
                    parse_ros2(number.text, r) is not None for r in readings)
                yield ctx.problem(CODE, number.element, message,
                                  loader_severity="warning" if differs else None)


def _shown(text: str | None) -> str:
    return f"'{text.strip(C_SPACE)}'" if text and text.strip(C_SPACE) else "empty"


def _ros1(text: str | None) -> str | None:
    plain = parse_ros2(text)
    if plain is not None and abs(plain) >= sys.float_info.min:
        return None  # a plain number in the range of a double (the common case)
    read = stod(text)
    if read.out_of_range:
        return (
            f"is '{read.read}', out of the range of a double: std::stod throws "
            "std::out_of_range and ros_control refuses the transmission"
        )
    if read.value is None:
        return f"is {_shown(text)}, not a number: ros_control refuses the transmission"
    if read.special:
        return (
            f"is '{read.read}': ros_control accepts it and every value the transmission maps "
            "becomes inf or nan"
        )
    return None


def _ros2(text: str | None, default: str, readings: tuple[NumberReading, ...]) -> str | None:
    values = {reading: parse_ros2(text, reading) for reading in readings}
    if len(set(values.values())) == 1 and None not in values.values():
        return None  # every distribution reading the file reads this one value
    if all(value is None for value in values.values()):
        return f"is {_shown(text)}, not a finite number: ros2_control silently uses {default}"
    humble, jazzy = (ros2_readings(text)[r] for r in (NumberReading.ISTRINGSTREAM,
                                                        NumberReading.FROM_CHARS))
    return (f"is {_shown(text)}, read differently by ROS 2 distributions: Humble's "
            f"ros2_control {_reads(humble, default)}, Jazzy's and later {_reads(jazzy, default)}")


def _reads(value: float | None, default: str) -> str:
    return f"silently uses {default}" if value is None else f"reads {format_float(value)}"
