"""Beam Bots DSL export of simple transmissions."""

from __future__ import annotations

from pathlib import Path

from txtool.dialects.read import read_source
from txtool.io.load import load
from txtool.model.core import Transmission
from txtool.model.robot import robot_joints
from txtool.transform.bb import elixir_float, export_bb

ROBOT = """<robot name="r">
  <joint name="shoulder" type="revolute"><limit lower="-1" upper="1" velocity="1" effort="1"/>
  </joint>
  <joint name="slide" type="prismatic"><limit lower="0" upper="0.2" velocity="1" effort="1"/>
  </joint>
  <joint name="wheel" type="continuous"/>
  {body}
</robot>"""


def ros1(name: str, joint: str, actuator: str, reduction: str, offset: str | None = None) -> str:
    off = f"<offset>{offset}</offset>" if offset is not None else ""
    return f"""<transmission name="{name}"><type>transmission_interface/SimpleTransmission</type>
      <joint name="{joint}"><hardwareInterface>hardware_interface/EffortJointInterface
      </hardwareInterface>{off}</joint>
      <actuator name="{actuator}"><mechanicalReduction>{reduction}</mechanicalReduction>
      </actuator></transmission>"""


def read(tmp_path: Path, body: str) -> tuple[list[Transmission], dict]:
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT.format(body=body))
    source = load(str(path))
    return [f.transmission for f in read_source(source)], robot_joints(source.root)


def test_simple_blocks(tmp_path: Path) -> None:
    transmissions, joints = read(tmp_path, "".join([
        ros1("shoulder_trans", "shoulder", "shoulder_motor", "101"),
        ros1("slide_trans", "slide", "slide_motor", "-12.5", "0.01"),
        ros1("wheel_trans", "wheel", "wheel_motor", "-1", "0.5"),
    ]))
    export = export_bb(transmissions, joints)
    assert export.not_representable == [] and export.lossless
    assert export.text == """\
# joint 'shoulder', actuator 'shoulder_motor' (transmission 'shoulder_trans')
transmission do
  reduction 101.0
end

# joint 'slide', actuator 'slide_motor' (transmission 'slide_trans')
transmission do
  reduction 12.5
  offset ~u(0.01 meter)
  reversed? true
end

# joint 'wheel', actuator 'wheel_motor' (transmission 'wheel_trans')
transmission do
  reduction 1.0
  offset ~u(0.5 radian)
  reversed? true
end
"""


def test_ros2_reduction_comes_from_the_joint(tmp_path: Path) -> None:
    body = """<ros2_control name="hw" type="system"><hardware><plugin>x/Y</plugin></hardware>
      <joint name="shoulder"/>
      <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>
        <actuator name="m" role="actuator1"><mechanical_reduction>7</mechanical_reduction>
        </actuator>
        <joint name="shoulder" role="joint1"><mechanical_reduction>-3</mechanical_reduction>
        <offset>-0.25</offset></joint>
      </transmission></ros2_control>"""
    export = export_bb(*read(tmp_path, body))
    assert export.text == """\
# joint 'shoulder', actuator 'm' (transmission 't')
transmission do
  reduction 3.0
  offset ~u(-0.25 radian)
  reversed? true
end
"""


def test_coupled_custom_and_unloadable_are_not_representable(tmp_path: Path) -> None:
    diff = """<transmission name="diff"><type>transmission_interface/DifferentialTransmission
      </type></transmission>
      <transmission name="odd"><type>acme/WristTransmission</type></transmission>"""
    transmissions, joints = read(tmp_path, diff + ros1("zero", "shoulder", "m", "0"))
    export = export_bb(transmissions, joints)
    assert export.text == "" and not export.lossless
    assert export.not_representable == [
        "transmission 'diff': differential type 'transmission_interface/DifferentialTransmission'"
        " is not representable in BB (BB has simple transmissions only)",
        "transmission 'odd': custom type 'acme/WristTransmission' is not representable in BB "
        "(BB has simple transmissions only)",
        "transmission 'zero': not loadable: reduction ratio cannot be zero",
    ]


def test_elixir_float_literals() -> None:
    assert [elixir_float(v) for v in (50.0, -3.0, 0.5, 1e-05, 1.5e20, 325.949)] == [
        "50.0", "-3.0", "0.5", "1.0e-05", "1.5e20", "325.949"]
