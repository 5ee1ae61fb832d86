"""``txtool simulate`` through click: exit codes and output asserted together."""

from __future__ import annotations

import csv
import importlib.util
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.simulate.robots import arm_ros1, arm_ros2, write
from txtool.cli import cli

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"


def txtool(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture
def arm(tmp_path):
    return write(tmp_path, "arm.urdf", arm_ros1())


def test_own_config_passes(arm):
    code, out, err = txtool(arm)
    assert (code, err) == (0, "")
    assert "PASS: largest tracking error" in out
    assert "m_shoulder" in out and "t_wrist" in out and "margin" in out


def test_flipped_candidate_fails_naming_the_joint(tmp_path, arm):
    flipped = write(tmp_path, "flipped.urdf", arm_ros1(n=-50))
    code, out, err = txtool(arm, "--candidate", flipped, "--duration", "2")
    assert (code, err) == (1, "")
    assert "FAIL: joint 'shoulder': tracking error" in out


def test_json_report(tmp_path, arm):
    small = write(tmp_path, "p.toml", "[actuators.m_left]\neffort_limit = 0.01\n")
    code, out, err = txtool(arm, "--format", "json", "--duration", "1", "--params", small)
    assert (code, err) == (1, "")
    doc = json.loads(out)["runs"][0]
    assert doc["verdict"] == "fail" and doc["steps"] == 1000 and doc["dt"] == 0.001
    assert doc["duration"] == 1.0
    assert set(doc["joints"]) == {"shoulder", "elbow", "wrist"}
    assert set(doc["joints"]["elbow"]) >= {"max_error", "rms_error"}
    left = doc["actuators"]["m_left"]
    assert set(left) >= {"peak_effort", "effort_limit", "rms_effort", "peak_velocity",
                         "velocity_limit", "saturated_fraction"}
    assert left["effort_limit"] == 0.01 and left["saturated_fraction"] > 0
    assert any(r.startswith("actuator 'm_left': effort") for r in doc["reasons"])


def test_csv_time_series(tmp_path, arm):
    out_csv = tmp_path / "series.csv"
    code, _, err = txtool(arm, "--csv", str(out_csv))
    assert (code, err) == (0, "")
    with out_csv.open() as handle:
        rows = list(csv.reader(handle))
    assert rows[0][:4] == ["time", "shoulder.ref", "shoulder.pos", "shoulder.error"]
    assert "m_left.effort_demand" in rows[0] and "m_right.velocity" in rows[0]
    assert len(rows) == 1 + 5001
    assert float(rows[-1][0]) == pytest.approx(5.0)


def test_several_configs_give_one_comparison_table(tmp_path, arm):
    good = write(tmp_path, "ros2.urdf", arm_ros2())
    bad = write(tmp_path, "offset.urdf", arm_ros1(offset=0.4))
    code, out, err = txtool(arm, "--candidate", good, "--candidate", bad, "--jobs", "2")
    assert (code, err) == (1, "")
    assert out.count("comparison") == 1
    assert "ros2.urdf: PASS" in out and "offset.urdf: FAIL: joint 'elbow'" in out
    assert "FAIL: 1 of 2 configs fail" in out


def test_several_configs_json(tmp_path, arm):
    good = write(tmp_path, "ros2.urdf", arm_ros2())
    code, out, _ = txtool(arm, "--candidate", good, "--candidate", arm, "--format", "json")
    doc = json.loads(out)
    assert code == 0 and doc["verdict"] == "pass" and len(doc["runs"]) == 2


def test_bad_params_key_is_one_line_exit_2(tmp_path, arm):
    params = write(tmp_path, "bad.toml", "[actuators.m_left]\nefort_limit = 2\n")
    code, out, err = txtool(arm, "--params", params)
    assert code == 2 and out == ""
    assert err.count("\n") == 1
    assert err.startswith("txtool: ") and "bad.toml:2: actuators.m_left.efort_limit: " \
                                             "unknown key" in err


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["missing.urdf"], "missing.urdf: no such file"),
        (["{arm}", "--dt", "2", "--duration", "1"], "--dt: 2 s is longer than the run"),
        (["{arm}", "--tolerance", "-1"], "--tolerance: must be a positive number"),
        (["{arm}", "--trajectory", "{tmp}/none.csv"], "none.csv: no such file"),
        (["{arm}", "--plot", "{tmp}/x.jpg"], "--plot writes .png, .svg or .pdf files"),
        (["{bad_xml}"], "bad.urdf:1:"),
        (["{no_links}"], "pinocchio cannot build the model: No link elements found"),
    ],
)
def test_input_errors_exit_2_with_one_line(tmp_path, arm, args, message):
    bad_xml = write(tmp_path, "bad.urdf", "<robot><joint></robot>")
    no_links = write(tmp_path, "empty.urdf", '<robot name="empty"/>')
    filled = [a.format(arm=arm, tmp=tmp_path, bad_xml=bad_xml, no_links=no_links)
              for a in args]
    code, out, err = txtool(*filled)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and message in err, err


def test_plot_without_matplotlib_says_how_to_get_it(tmp_path, arm, monkeypatch):
    import txtool.simulation.plot as plot

    real = plot.importlib.util.find_spec
    monkeypatch.setattr(plot.importlib.util, "find_spec",
                        lambda name, *a: None if name == "matplotlib" else real(name, *a))
    code, out, err = txtool(arm, "--plot", str(tmp_path / "p.png"))
    assert code == 2 and out == ""
    assert "needs matplotlib" in err and "txtool[plot]" in err


@pytest.mark.skipif(importlib.util.find_spec("matplotlib") is None,
                    reason="matplotlib (extra 'plot') is not installed")
def test_plot_is_written(tmp_path, arm):
    target = tmp_path / "p.svg"
    code, _, err = txtool(arm, "--plot", str(target))
    assert (code, err) == (0, "")
    assert target.read_text().lstrip().startswith(("<?xml", "<svg"))


@pytest.mark.skipif(importlib.util.find_spec("matplotlib") is None,
                    reason="matplotlib (extra 'plot') is not installed")
def test_plot_joints_chooses_the_joints_drawn(tmp_path, arm):
    target = tmp_path / "p.svg"
    code, out, err = txtool(arm, "--duration", "0.5", "--plot", str(target), "--joints",
                            "elbow,wri*")
    assert (code, err) == (0, "") and out.splitlines()[-1].startswith("PASS")
    svg = target.read_text()
    assert "<!-- elbow -->" in svg and "<!-- wrist -->" in svg and "shoulder" not in svg
    code, out, err = txtool(arm, "--duration", "0.5", "--plot", str(target), "--joints", "hand")
    assert (code, out, err) == (2, "", f"txtool: --joints: no joint of {arm} is named 'hand'\n")


def test_joints_without_plot_is_one_line(arm):
    assert txtool(arm, "--joints", "elbow") == (
        2, "", "txtool: --joints: only with --plot (it chooses the joints drawn)\n")


def test_demo_robot_against_its_conversions():
    robot = FIXTURES / "demo_robot.urdf"
    if not robot.is_file():
        pytest.skip("demo robot fixture not present")
    args = [str(robot)]
    for name in ("demo_robot.ros2-p2.urdf", "demo_robot.ros2-p1.urdf"):
        if (FIXTURES / name).is_file():
            args += ["--candidate", str(FIXTURES / name)]
    code, out, err = txtool(*args)
    assert (code, err) == (0, ""), out


def test_xacro_candidate_with_arguments(tmp_path, arm):
    text = arm_ros1(n="${n}").replace(
        '<robot name="arm" xmlns:drake="http://drake.mit.edu">',
        '<robot name="arm" xmlns:drake="http://drake.mit.edu" '
        'xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="n" default="50"/><xacro:property name="n" value="$(arg n)"/>')
    candidate = write(tmp_path, "arm.urdf.xacro", text)
    code, out, _ = txtool(arm, "--candidate", candidate)
    assert code == 0, out
    code, out, _ = txtool(arm, "--candidate", candidate, "--xacro-arg", "n:=-50")
    assert code == 1 and "FAIL: joint 'shoulder'" in out


def test_xacro_arguments_for_the_robot_are_no_warning_about_a_plain_candidate(tmp_path, arm):
    """--xacro-arg reaches the xacro robot: the plain candidate (and the robot in the other
    order) gets no "has no effect"; given where no file uses xacro, each is named once."""
    text = arm_ros1(n="${n}").replace(
        '<robot name="arm" xmlns:drake="http://drake.mit.edu">',
        '<robot name="arm" xmlns:drake="http://drake.mit.edu" '
        'xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="n" default="50"/><xacro:property name="n" value="$(arg n)"/>')
    robot = write(tmp_path, "arm.urdf.xacro", text)
    code, out, err = txtool(robot, "--candidate", arm, "--xacro-arg", "n:=50", "--duration",
                            "0.5")
    assert (code, err) == (0, ""), out
    code, out, err = txtool(arm, "--candidate", arm, "--xacro-arg", "n:=50", "--duration", "0.5")
    assert (code, err) == (0, f"txtool: warning: {arm}: --xacro-arg has no effect: it uses no "
                              "xacro (no xacro element, ${...} or $(...)) and is read as "
                              "written\n"), out


def test_an_element_of_absurdly_many_attributes_is_refused_before_pinocchio(tmp_path, arm):
    crowded = tmp_path / "crowded.urdf"
    attributes = " ".join(f'a{i}="1"' for i in range(20_000))
    text = Path(arm).read_text()
    crowded.write_text(text.replace("<robot ", f"<robot {attributes} ", 1))
    code, out, err = txtool(str(crowded))
    assert (code, out) == (2, "")
    line = text[:text.index("<robot ")].count("\n") + 1
    # the 20,000 and its name
    assert err == (f"txtool: {crowded}:{line}: <robot> has 20001 attributes; simulate refuses "
                   "more than 256 on one element (Pinocchio's URDF parser slows down "
                   "quadratically on them)\n")


def test_help_says_the_default_duration_stretches_to_what_the_robot_can_follow():
    result = CliRunner().invoke(cli, ["simulate", "--help"], terminal_width=200)
    assert result.exit_code == 0
    text = " ".join(result.output.split())
    assert ("--duration S Run length. Default: at least 5 s, stretched (up to 240 s) until the "
            "default motion is feasible for the robot's limits; given, the motion shrinks to "
            "fit it instead.") in text
