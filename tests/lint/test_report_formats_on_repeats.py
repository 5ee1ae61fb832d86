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
