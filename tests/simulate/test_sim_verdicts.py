"""Three verdicts: a run that checked nothing of the config is inconclusive, never a pass.

A verifier that passes when it verified nothing is trusted wrongly in CI: a robot whose
transmissions are all of custom types, or that has none, gets ``inconclusive`` and exit 3,
before any motion is simulated. A run that checked part of the config says how much.
"""

from __future__ import annotations

import json
import time

from click.testing import CliRunner

from tests.simulate.robots import ARM_BODY, ARM_ROS1_SHOULDER, EFFORT, arm_ros1, write
from txtool.cli import cli
from txtool.simulation.report import overall_verdict
from txtool.simulation.result import Coverage, RunResult

CUSTOM = """
  <transmission name="{name}">
    <type>acme_mechanism_model/MagicTransmission</type>
    <joint name="{joint}">{effort}</joint>
    <actuator name="m_{joint}"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>"""


def customs(*joints: str) -> str:
    return "".join(CUSTOM.format(name=f"t_{j}", joint=j, effort=EFFORT) for j in joints)


def txtool(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def test_only_custom_transmissions_is_inconclusive_exit_3_without_simulating(tmp_path):
    robot = write(tmp_path, "custom.urdf",
                  f'<robot name="arm">{ARM_BODY}{customs("shoulder", "elbow", "wrist")}</robot>')
    started = time.perf_counter()
    code, out, err = txtool(robot)
    assert time.perf_counter() - started < 20  # nothing is simulated (it took over a minute)
    assert (code, err) == (3, "")
    assert "PASS" not in out
    assert out.splitlines()[-1] == (
        "INCONCLUSIVE: nothing checked: none of the config's 3 transmissions can be simulated "
        "(custom type 'acme_mechanism_model/MagicTransmission' has no standard maths)")
    code, out, err = txtool(robot, "--format", "json")
    doc = json.loads(out)["runs"][0]
    assert (code, doc["verdict"]) == (3, "inconclusive")
    assert doc["checked"] == {
        "transmissions": 3, "simulated": [], "joints": 3, "joints_checked": 0, "unread": {},
        "still": [],
        "units": {"transmissions": "1", "joints": "1", "joints_checked": "1"},
        "skipped": {f"t_{j}": "custom type 'acme_mechanism_model/MagicTransmission' has no "
                              "standard maths" for j in ("shoulder", "elbow", "wrist")}}


def test_a_robot_without_transmissions_is_inconclusive(tmp_path):
    robot = write(tmp_path, "bare.urdf", f'<robot name="arm">{ARM_BODY}</robot>')
    code, out, err = txtool(robot, "--duration", "1")
    assert (code, err) == (3, "")
    assert out.splitlines()[-1] == ("INCONCLUSIVE: nothing checked: the config has no "
                                    "transmission: every joint is driven directly")


def test_a_candidate_that_drops_the_robots_only_transmission_fails_naming_it(tmp_path):
    """The robot drives 'shoulder' through 't_shoulder'; the candidate drives it directly: the
    comparison shows the fault before any run (not inconclusive)."""
    robot = write(tmp_path, "one.urdf",
                  f'<robot name="arm">{ARM_BODY}{ARM_ROS1_SHOULDER.format(n=50)}</robot>')
    dropped = write(tmp_path, "dropped.urdf", f'<robot name="arm">{ARM_BODY}</robot>')
    code, out, err = txtool(robot, "--candidate", dropped)
    assert (code, err) == (1, "")
    assert out.splitlines()[0] == f"simulate {robot} with {dropped}: not simulated"
    assert out.splitlines()[-1] == (
        "FAIL: the config has no transmission 't_shoulder': joint 'shoulder' is driven "
        "directly where the robot has a simple transmission to actuator 'm_shoulder'")
    doc = json.loads(txtool(robot, "--candidate", dropped, "--format", "json")[1])
    assert (doc["verdict"], [c["kind"] for c in doc["runs"][0]["causes"]]) == (
        "fail", ["missing_transmission"])


def test_a_partial_run_says_how_much_it_checked(tmp_path):
    robot = write(tmp_path, "custom.urdf", arm_ros1(shoulder=False, extra=customs("shoulder")))
    code, out, err = txtool(robot, "--duration", "1")
    assert (code, err) == (0, "")
    verdict = out.splitlines()[-1]
    assert verdict.startswith("PASS: largest tracking error")
    assert verdict.endswith("; checked 1 of 2 transmissions and 2 of 3 joints")
    doc = json.loads(txtool(robot, "--duration", "1", "--format", "json")[1])["runs"][0]
    assert doc["checked"]["simulated"] == ["t_wrist"]
    assert (doc["checked"]["joints_checked"], doc["checked"]["joints"]) == (2, 3)


def test_limits_that_say_no_limit_still_move_the_joints(tmp_path):
    """±1e10 limits: 25% -> 75% of that range is no motion; the joints move as continuous
    ones do (a note says so) instead of being cut to 0% and passing unmoved."""
    text = arm_ros1()
    for limits in ('lower="-1.5" upper="1.5"', 'lower="-2" upper="2"', 'lower="-1" upper="1"'):
        text = text.replace(limits, 'lower="-1e10" upper="1e10"')
    assert text.count('"1e10"') == 3
    robot = write(tmp_path, "wide.urdf", text)
    code, out, err = txtool(robot, "--duration", "2")
    assert (code, err) == (0, "")
    assert ("note: limits more than 1000 apart taken as none: 'shoulder', 'elbow', 'wrist' "
            "move in a range of 2 near 0, as continuous joints do") in out
    assert "amplitude cut" not in out and out.splitlines()[-1].endswith("no limit exceeded")


def test_a_pass_names_the_joints_the_limits_keep_still(tmp_path):
    slow = arm_ros1().replace('effort="40" velocity="3"', 'effort="40" velocity="1e-3"')
    robot = write(tmp_path, "slow.urdf", slow)
    code, out, err = txtool(robot, "--duration", "1")
    assert (code, err) == (0, "")
    assert "'shoulder' 0%" in out
    assert out.splitlines()[-1].endswith(
        "no limit exceeded; checked 2 of 2 transmissions and 3 of 3 joints; the reference "
        "does not move 1 of them ('shoulder': see the notes)")
    doc = json.loads(txtool(robot, "--duration", "1", "--format", "json")[1])["runs"][0]
    assert doc["checked"]["still"] == ["shoulder"]


def test_a_complete_run_says_nothing_about_coverage(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    code, out, _ = txtool(robot, "--duration", "1")
    assert code == 0
    assert "checked" not in out.splitlines()[-1]


def test_several_configs_one_inconclusive_is_exit_3_and_named(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    blind = write(tmp_path, "blind.urdf",
                  f'<robot name="arm">{ARM_BODY}{customs("shoulder", "elbow", "wrist")}</robot>')
    code, out, err = txtool(robot, "--candidate", robot, "--candidate", blind, "--duration", "1")
    assert (code, err) == (3, "")
    assert out.splitlines()[-1] == f"INCONCLUSIVE: 1 of 2 configs could not be checked: {blind}"
    doc = json.loads(txtool(robot, "--candidate", robot, "--candidate", blind, "--duration", "1",
                            "--format", "json")[1])
    assert doc["verdict"] == "inconclusive"
    assert [r["verdict"] for r in doc["runs"]] == ["pass", "inconclusive"]


def test_a_failure_outranks_an_inconclusive_run():
    def run(reasons: list[str], simulated: tuple[str, ...]) -> RunResult:
        return RunResult("r", "c", 0.001, 0, 0.0, "", {}, {}, reasons, [],
                         coverage=Coverage(transmissions=1, simulated=simulated))
    failing, blind, good = run(["x"], ("t",)), run([], ()), run([], ("t",))
    assert [r.verdict for r in (failing, blind, good)] == ["fail", "inconclusive", "pass"]
    assert overall_verdict([good, blind, failing]) == "fail"
    assert overall_verdict([good, blind]) == "inconclusive"
    assert overall_verdict([good, good]) == "pass"


def test_an_inconclusive_run_writes_no_csv_or_plot(tmp_path):
    robot = write(tmp_path, "custom.urdf",
                  f'<robot name="arm">{ARM_BODY}{customs("shoulder", "elbow", "wrist")}</robot>')
    csv, plot = tmp_path / "run.csv", tmp_path / "run.png"
    code, out, err = txtool(robot, "--csv", str(csv), "--plot", str(plot))
    why = ("nothing was simulated (none of the config's 3 transmissions can be simulated "
           "(custom type 'acme_mechanism_model/MagicTransmission' has no standard maths))")
    assert (code, err) == (3, f"txtool: {csv}: not written (--csv): {why}\n"
                              f"txtool: {plot}: not written (--plot): {why}\n")
    assert out.splitlines()[-1].startswith("INCONCLUSIVE: nothing checked")
    assert not csv.exists() and not plot.exists()  # nothing was simulated: no time series
