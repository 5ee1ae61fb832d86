"""Report formats on findings the golden report has none of: two findings alike in one file
(GitLab tells them apart by how many alike came before), and a message whose first clause is
too short to stand alone in the concise format."""

from __future__ import annotations

import json

from tests.lint.conftest import BROKEN

TWICE = BROKEN.replace("""  <transmission name="u">
    <type>SimpleTansmission</type>
  </transmission>
""", BROKEN.split("\n", 1)[1].split("  <transmission name=\"u\">")[0])


def test_gitlab_gives_two_findings_alike_fingerprints_of_their_own(validate, tmp_path):
    (tmp_path / "robot.urdf").write_text(TWICE)
    code, out, _ = validate("--format", "gitlab", "--select", "TX106", str(tmp_path / "robot.urdf"))
    issues = json.loads(out)
    assert code == 1 and [(i["check_name"], i["location"]["lines"]["begin"]) for i in issues] \
        == [("TX106", 6), ("TX106", 12)]
    assert issues[0]["description"] == issues[1]["description"]
    assert issues[0]["fingerprint"] != issues[1]["fingerprint"]


def test_concise_keeps_the_reason_after_a_clause_that_only_names_the_tool(validate, tmp_path):
    (tmp_path / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="absent.xacro"/>\n</robot>\n')
    code, out, _ = validate("--format", "concise", str(tmp_path / "r.urdf.xacro"))
    assert code == 1
    assert out.splitlines()[0] == (
        f"{tmp_path / 'r.urdf.xacro'}:2:3: TX002 xacro: [Errno 2] No such file or directory")


TWO_BLOCKS = """<robot name="r">
  <link name="base"/><link name="arm"/>
  <joint name="wrist_roll" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <ros2_control name="arm" type="system">
    <hardware><plugin>my_hardware/ArmSystem</plugin></hardware>
    <joint name="wrist_roll"><command_interface name="position"/></joint>
  </ros2_control>
  <ros2_control name="mock" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="wrist_roll"><command_interface name="position"/></joint>
  </ros2_control>
</robot>
"""


def test_concise_cuts_a_long_headline_at_a_word_without_its_comma(validate, tmp_path,
                                                                  monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "r.urdf").write_text(TWO_BLOCKS)
    code, out, _ = validate("--format", "concise", "--select", "TX209", "r.urdf")
    assert (code, out.splitlines()[0]) == (1, (
        "r.urdf:13:5: TX209 joint 'wrist_roll' of <ros2_control> 'mock' exports command "
        "interface 'wrist_roll/position'…"))
