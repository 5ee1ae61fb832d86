"""Reports a person reads: units in every header and in the JSON, tables within 100 columns,
the JSON's shape against a golden file, and the plot in each format.

Regenerate the golden file with ``TXTOOL_UPDATE_GOLDEN=1 pytest tests/simulate/test_sim_report.py``.
"""

from __future__ import annotations

import importlib.util
import json
import math
import os
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.simulate.robots import EFFORT, link, write
from txtool.cli import cli

GOLDEN = Path(__file__).parent / "golden"
FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"
needs_matplotlib = pytest.mark.skipif(importlib.util.find_spec("matplotlib") is None,
                                      reason="matplotlib (extra 'plot') is not installed")

LONG = "shoulder_lift_actuator_with_a_long_name"
# A linear axis (prismatic joint, linear actuator) carrying a revolute joint.
SLIDER = f"""<robot name="slider">
  <link name="base"/>
  {link("carriage", 3.0, 0.0, 0.01)}
  {link("arm", 1.0, 0.2, 0.01)}
  <joint name="rail" type="prismatic"><parent link="base"/><child link="carriage"/>
    <axis xyz="1 0 0"/><limit lower="-0.2" upper="0.2" effort="200" velocity="1"/></joint>
  <joint name="{LONG}_joint" type="revolute"><parent link="carriage"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="40" velocity="3"/></joint>
  <transmission name="t_rail"><type>transmission_interface/SimpleTransmission</type>
    <joint name="rail">{EFFORT}</joint>
    <actuator name="rail_motor"><mechanicalReduction>2</mechanicalReduction></actuator>
  </transmission>
  <transmission name="t_{LONG}"><type>transmission_interface/SimpleTransmission</type>
    <joint name="{LONG}_joint">{EFFORT}</joint>
    <actuator name="{LONG}"><mechanicalReduction>20</mechanicalReduction></actuator>
  </transmission>
</robot>"""


def simulate(*args: str, env: dict[str, str] | None = None) -> tuple[int, str, str]:
    result = CliRunner(env=env).invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture
def slider(tmp_path):
    return write(tmp_path, "slider.urdf", SLIDER)


def test_text_report_has_units_in_every_header_and_fits_100_columns(slider):
    code, out, err = simulate(slider, "--duration", "2", env={"COLUMNS": "160"})
    assert (code, err) == (0, ""), out
    assert "joints (rad)" in out and "prismatic joints (m)" in out
    assert "actuators (N·m, rad/s;" in out and "linear actuators (N, m/s;" in out
    headers = "".join(line for line in out.splitlines() if "┃" in line)
    for unit in ("(rad)", "(m)", "(N·m)", "(N)", "(rad/s)", "(m/s)", "(s)"):
        assert unit in headers, unit
    assert "gains: kp 400 1/s², kd 40 1/s, ki 0 for every joint" in out
    tables = [line for line in out.splitlines() if re.search("[┃│━]", line)]
    assert tables and max(len(line) for line in tables) <= 100
    assert LONG in out.replace("\n", "").replace(" ", "").replace("│", "")  # folded, not cut


def test_limit_reasons_carry_units(tmp_path, slider):
    small = write(tmp_path, "p.toml", "[actuators.rail_motor]\neffort_limit = 0.5\n"
                                      "velocity_limit = 0.01\n")
    # the default motion would be slowed to these limits; this trajectory is not
    moves = write(tmp_path, "moves.csv", "time,rail\n0,-0.1\n1,0.1\n2,-0.1\n")
    code, out, err = simulate(slider, "--trajectory", moves, "--params", small,
                              env={"COLUMNS": "300"})
    assert (code, err) == (1, "")
    assert re.search(r"actuator 'rail_motor': effort [\d.]+ N exceeds its limit 0\.5 N,", out)
    assert re.search(r"actuator 'rail_motor': speed [\d.]+ m/s exceeds its limit 0\.01 m/s",
                     out)


def test_json_units(slider):
    code, out, _ = simulate(slider, "--duration", "2", "--format", "json")
    doc = json.loads(out)["runs"][0]
    assert code == 0 and doc["tolerance"] == 0.01
    assert doc["units"] == {"tolerance": "rad|m", "steps": "1", "dt": "s", "duration": "s"}
    assert doc["joints"]["rail"]["units"] == {"max_error": "m", "rms_error": "m",
                                              "max_error_time": "s", "limit_margin": "m"}
    assert doc["joints"][f"{LONG}_joint"]["units"]["max_error"] == "rad"
    rail, arm = doc["actuators"]["rail_motor"]["units"], doc["actuators"][LONG]["units"]
    assert (rail["peak_effort"], rail["effort_limit"], rail["peak_velocity"]) == ("N", "N", "m/s")
    assert (arm["rms_effort"], arm["velocity_limit"]) == ("N·m", "rad/s")
    assert (arm["saturated_fraction"], arm["first_violation"]) == ("1", "s")
    assert doc["gains"]["rail"]["units"]["i_clamp"] == "m/s²"


EXACT = ("given", "bandwidth", "tolerance", "dt", "duration")  # settings, not results


def _shape(value, key=""):
    """Keys, strings, integers and settings as they are; results as "<number>"; files by name;
    the reference's description (:mod:`txtool.simulation.reference`'s) as "<text>"."""
    if key in EXACT:
        return value
    if key == "reference":
        return "<text>"
    if isinstance(value, dict):
        return {k: _shape(v, k) for k, v in value.items()}
    if isinstance(value, list):
        return [_shape(v) for v in value]
    if isinstance(value, float):
        return "<number>"
    if isinstance(value, str) and key in ("file", "robot", "config", "path"):
        return Path(value).name
    if isinstance(value, str):
        return re.sub(r"\S*/(\w+\.yaml)", r"\1", value)
    return value


def test_json_shape_matches_golden(tmp_path):
    robot = FIXTURES / "demo_robot.urdf"
    gains = write(tmp_path, "ct.yaml", "ct:\n  joints:\n    shoulder: {p: 400, d: 40, i: 1}\n")
    code, out, err = simulate(str(robot), "--params", gains, "--format", "json")
    assert (code, err) == (0, "")
    text = json.dumps(_shape(json.loads(out)), indent=2, ensure_ascii=False) + "\n"
    path = GOLDEN / "simulate_report_shape.json"
    if os.environ.get("TXTOOL_UPDATE_GOLDEN") == "1":
        path.parent.mkdir(exist_ok=True)
        path.write_text(text, encoding="utf-8")
    assert text == path.read_text(encoding="utf-8")


def test_json_shape_with_controllers_matches_golden(tmp_path):
    """--controllers: each joint's controller (or null: held) and the gains it carries."""
    robot = FIXTURES / "demo_robot.ros2-p2.urdf"
    control = write(tmp_path, "controllers.yaml", """\
controller_manager:
  ros__parameters:
    arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController
arm_controller:
  ros__parameters:
    joints: [shoulder, wrist_pitch]
    command_interfaces: [effort]
    state_interfaces: [position, velocity]
    gains:
      shoulder: {p: 1.0, d: 0.1}
""")
    code, out, err = simulate(str(robot), "--controllers", control, "--duration", "0.5",
                              "--format", "json")
    assert (code, err) == (0, "")
    text = json.dumps(_shape(json.loads(out)), indent=2, ensure_ascii=False) + "\n"
    path = GOLDEN / "simulate_controllers_shape.json"
    if os.environ.get("TXTOOL_UPDATE_GOLDEN") == "1":
        path.write_text(text, encoding="utf-8")
    assert text == path.read_text(encoding="utf-8")


@needs_matplotlib
@pytest.mark.parametrize(("suffix", "magic"),
                         [(".png", b"\x89PNG"), (".svg", b"<?xml"), (".PDF", b"%PDF")])
def test_plot_formats_by_suffix(tmp_path, slider, suffix, magic):
    target = tmp_path / f"plot{suffix}"
    code, out, err = simulate(slider, "--duration", "2", "--plot", str(target))
    assert (code, err) == (0, "") and "PASS" in out
    assert target.read_bytes().startswith(magic)


@needs_matplotlib
def test_plot_overlays_the_configs_in_one_file(tmp_path):
    robot = str(FIXTURES / "demo_robot.urdf")
    target = tmp_path / "compare.svg"
    code, _, err = simulate(robot, "--candidate", robot, "--candidate", robot, "--plot", str(target))
    assert (code, err) == (0, "")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["compare.svg"]
    svg = target.read_text(encoding="utf-8")
    for label in ("demo_robot.urdf (pass)", "reference", "limit", "tolerance",
                  "position (rad)", "error (rad)", "effort (N·m)", "speed (rad/s)"):
        assert label in svg, label


@pytest.mark.parametrize("name", ["p.jpg", "p", "p.png.txt"])
def test_unknown_plot_suffix_is_one_line_exit_2(tmp_path, slider, name):
    code, out, err = simulate(slider, "--plot", str(tmp_path / name))
    assert (code, out) == (2, "")
    assert err == f"txtool: {tmp_path / name}: --plot writes .png, .svg or .pdf files " \
                  "(by the suffix)\n"


@pytest.mark.parametrize(("value", "shown"), [
    (None, "-"), (math.inf, "none"), (-math.inf, "-inf"), (math.nan, "nan"),
    (123456.0, "1.235e5"), (0.0001234, "1.234e-4"), (0.0, "0"), (12.5, "12.5"),
])
def test_numbers_in_tables_are_short_and_say_what_is_not_a_number(value, shown):
    from txtool.simulation.report import _num

    assert _num(value) == shown
