"""A transmission edited after ``convert --reversible`` keeps the edit on the way back: the
original it carries is put back only over what txtool generates from that original."""

from __future__ import annotations

import pytest
from lxml import etree

DIFFERENTIAL = """\
<?xml version="1.0"?>
<robot name="wrist">
  <transmission name="wrist_trans">
    <type>transmission_interface/DifferentialTransmission</type>
    <joint name="pitch">
      <role>joint1</role>
      <offset>0.25</offset>
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <joint name="roll">
      <role>joint2</role>
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="left_motor">
      <role>actuator1</role>
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
    <actuator name="right_motor">
      <role>actuator2</role>
      <mechanicalReduction>60</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""

# One field each, edited in the ROS 2 (Proposal 2) form.
EDITS = {
    "offset": (b"<offset>0.25</offset>", b"<offset>0.5</offset>"),
    "reduction": (b"<mechanical_reduction>60</mechanical_reduction>",
                  b"<mechanical_reduction>70</mechanical_reduction>"),
    "role": (b'<joint name="pitch" role="joint1">', b'<joint name="pitch" role="joint2">'),
}


def _fields(text: str) -> dict[str, tuple]:
    root = etree.fromstring(text.encode())
    (transmission,) = root.iter("transmission")
    return {m.get("name"): (m.findtext("role"), m.findtext("offset"),
                            m.findtext("mechanicalReduction"))
            for m in transmission if m.tag in ("joint", "actuator")}


@pytest.mark.parametrize("field", sorted(EDITS))
def test_an_edit_made_in_ros2_is_kept_not_the_carried_original(run, tmp_path, field):
    path = tmp_path / "wrist.urdf"
    path.write_text(DIFFERENTIAL)
    code, out, err = run("convert", str(path), "--to", "ros2-p2", "--reversible")
    assert code == 0, err
    before, after = EDITS[field]
    assert out.encode().count(before) == 1
    edited = tmp_path / "wrist.ros2.urdf"
    edited.write_bytes(out.encode().replace(before, after))
    code, back, err = run("convert", str(edited), "--to", "ros1", "--allow-lossy")
    assert code == 0
    assert ("note: transmission 'wrist_trans': changed since it was converted with "
            "--reversible; written as txtool writes it\n") in err
    assert "txtool-original" not in back
    expected = _fields(DIFFERENTIAL)
    if field == "offset":
        expected["pitch"] = ("joint1", "0.5", None)
    elif field == "reduction":
        expected["roll"] = ("joint2", None, None)
        expected["right_motor"] = ("actuator2", None, "70")
    else:
        expected["pitch"] = ("joint2", "0.25", None)
    assert _fields(back) == expected


def test_an_unedited_transmission_comes_back_byte_for_byte(run, tmp_path):
    path = tmp_path / "wrist.urdf"
    path.write_text(DIFFERENTIAL)
    _, out, _ = run("convert", str(path), "--to", "ros2-p2", "--reversible")
    converted = tmp_path / "wrist.ros2.urdf"
    converted.write_text(out)
    code, back, _ = run("convert", str(converted), "--to", "ros1")
    assert (code, back) == (0, DIFFERENTIAL)
