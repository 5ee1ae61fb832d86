"""What the fuzz suite found, one focused test per fix, with the smallest document that showed it."""

from __future__ import annotations

import json
import textwrap
import time
from pathlib import Path

from click.testing import CliRunner, Result

from txtool.cli import cli


def run(tmp_path: Path, xml: str, *args: str, name: str = "robot.urdf") -> tuple[Result, str]:
    """Write ``xml`` (dedented) as ``name`` and run ``txtool ARGS[0] PATH ARGS[1:]``."""
    path = tmp_path / name
    path.write_text(textwrap.dedent(xml).lstrip("\n"), encoding="utf-8")
    command, *options = args
    result = CliRunner().invoke(cli, [command, str(path), *options], catch_exceptions=True)
    assert result.exception is None or isinstance(result.exception, SystemExit), (
        f"crash: {result.exception!r}"
    )
    return result, str(path)


def test_bb_export_of_a_document_without_transmissions_says_so(tmp_path):
    result, _ = run(tmp_path, """
        <robot name="r">
          <link name="base"/>
        </robot>
    """, "convert", "--to", "bb")
    assert (result.exit_code, result.stdout) == (0, "# no transmission to export\n")


def strict_json(text: str):
    def reject(name: str):
        raise ValueError(f"{name} is not JSON")

    return json.loads(text, parse_constant=reject)


HUGE_SIMPLE = """
    <robot name="r">
      <joint name="a" type="revolute">
        <limit lower="-1e308" upper="1e308" effort="1e308" velocity="1e308"/>
      </joint>
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="a">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>1e308</mechanicalReduction></actuator>
      </transmission>
    </robot>
"""

HUGE_DIFFERENTIAL = """
    <robot name="r">
      <joint name="a" type="revolute"><limit lower="-1e308" upper="1e308" effort="1" velocity="1"/></joint>
      <joint name="b" type="revolute"><limit lower="-1e308" upper="1e308" effort="1" velocity="1"/></joint>
      <transmission name="t">
        <type>transmission_interface/DifferentialTransmission</type>
        <joint name="a"><role>joint1</role><offset>1e308</offset>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
        <joint name="b"><role>joint2</role>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
        <actuator name="m1"><role>actuator1</role><mechanicalReduction>{reduction}</mechanicalReduction></actuator>
        <actuator name="m2"><role>actuator2</role><mechanicalReduction>1e308</mechanicalReduction></actuator>
      </transmission>
    </robot>
"""


def test_map_whose_result_overflows_is_a_one_line_error(tmp_path):
    # numpy's "overflow encountered in multiply" went to stderr and "inf" to the table.
    result, path = run(tmp_path, HUGE_SIMPLE, "map", "-t", "t", "--to", "actuator",
                       "--position", "10")
    assert result.exit_code == 2
    assert result.stderr == (f"txtool: {path}: --position: the result through transmission 't' "
                             "is not a finite number (values or reductions too large or too small)\n")


def test_map_through_reductions_whose_product_underflows_is_a_one_line_error(tmp_path):
    # jr0 * ar0 = 1e-200 * 1e-200 is 0.0: a division by zero in the four-bar formulas.
    # (Subnormal text such as 5e-324 is refused by ros_control's std::stod as out of range.)
    xml = HUGE_DIFFERENTIAL.replace("DifferentialTransmission", "FourBarLinkageTransmission")
    xml = xml.replace("<role>joint1</role>",
                      "<role>joint1</role><mechanicalReduction>1e-200</mechanicalReduction>")
    result, _ = run(tmp_path, xml.format(reduction="1e-200"), "map", "-t", "t", "--to", "joint",
                    "--velocity", "1,1")
    assert result.exit_code == 2 and "is not a finite number" in result.stderr


def test_actuator_limits_beyond_the_float_range_are_unbounded(tmp_path):
    result, _ = run(tmp_path, HUGE_SIMPLE, "show", "--actuator-limits", "--format", "json")
    assert result.exit_code == 0
    assert strict_json(result.stdout)["actuator_limits"] == [
        {"transmission": "t", "actuator": "m", "position": None, "velocity": None,
         "effort": 1.0},
    ]


def test_roundtrip_samples_joint_limits_wider_than_the_float_range(tmp_path):
    # np.linspace(-1e308, 1e308) overflowed computing the width of the range.
    result, _ = run(tmp_path, HUGE_DIFFERENTIAL.format(reduction="1e308"), "roundtrip")
    assert result.exit_code == 0
    assert "all cycles keep every field" in result.stdout


def test_roundtrip_against_reports_a_difference_that_overflows_as_null(tmp_path):
    other = tmp_path / "other.urdf"
    other.write_text(textwrap.dedent(HUGE_DIFFERENTIAL.format(reduction="2")), encoding="utf-8")
    result, _ = run(tmp_path, HUGE_DIFFERENTIAL.format(reduction="1e308"), "roundtrip",
                    "--format", "json", "--against", str(other))
    assert result.exit_code == 1
    row = strict_json(result.stdout)["transmissions"][0]
    assert row["status"] == "differs" and row["reason"].startswith("actuator 'm1' position")
    assert row["differences"]["position"] is None


def test_show_json_of_a_ros1_nan_reduction_is_json(tmp_path):
    result, _ = run(tmp_path, """
        <robot name="r">
          <transmission name="t">
            <type>transmission_interface/SimpleTransmission</type>
            <joint name="a"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
            <actuator name="m"><mechanicalReduction>nan</mechanicalReduction></actuator>
          </transmission>
        </robot>
    """, "show", "--format", "json")
    assert result.exit_code == 0
    reduction = strict_json(result.stdout)["transmissions"][0]["actuators"][0]["mechanical_reduction"]
    assert reduction == {"value": None, "text": "nan"}


def arm_with_transmissions(count: int) -> bytes:
    joints = "\n".join(f'<joint name="j{i}" type="revolute"/>' for i in range(count))
    transmissions = "\n".join(
        f'<transmission name="t{i}"><type>transmission_interface/SimpleTransmission</type>'
        f'<joint name="j{i}"><hardwareInterface>hardware_interface/EffortJointInterface'
        f'</hardwareInterface></joint><actuator name="m{i}"><mechanicalReduction>{i + 1}'
        "</mechanicalReduction></actuator></transmission>"
        for i in range(count)
    )
    return f'<robot name="r">\n{joints}\n{transmissions}\n</robot>\n'.encode()


def test_placing_converted_transmissions_takes_linear_time():
    # Each transmission moved into the new <ros2_control> listed every element of the document
    # and every joint declared so far: 400 transmissions took 7 s.
    from txtool.io.xmlio import Source, parse_bytes
    from txtool.transform import convert

    def cpu_seconds(count: int) -> float:
        data = arm_with_transmissions(count)
        source = Source("arm.urdf", data, parse_bytes(data, "arm.urdf"))
        start = time.process_time()
        result = convert.convert_source(source, "ros2-p2")
        elapsed = time.process_time() - start
        assert result.data.count(b"<transmission ") == count and not result.losses
        return elapsed

    small, large = cpu_seconds(250), cpu_seconds(2000)
    assert large < 30 * max(small, 0.01), (small, large)  # linear: 8x; it was over 100x
