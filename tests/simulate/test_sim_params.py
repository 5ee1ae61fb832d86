"""Parameter files: the format, one-line errors that name the key, pyproject discovery."""

from __future__ import annotations

import os
import re

import pytest

from tests.simulate.robots import arm_ros1, write
from txtool.io.xmlio import InputError
from txtool.simulation.parameter_files import load_params
from txtool.simulation.run import Options, prepare

GOOD = """bandwidth = 30.0
duration = 2.0

[actuators.m_shoulder]
rotor_inertia = 1e-5
effort_limit = 2.5
velocity_limit = 400

[joints.elbow]
kp = 900
kd = 60
ki = 5
i_clamp = 0.5
"""


def test_params_file_values(tmp_path):
    params = load_params(write(tmp_path, "p.toml", GOOD), str(tmp_path / "robot.urdf"))
    assert params.run == {"bandwidth": 30.0, "duration": 2.0}
    assert params.actuators["m_shoulder"].effort_limit == 2.5
    assert params.actuators["m_shoulder"].velocity_limit == 400.0
    assert params.joints["elbow"].kp == 900.0 and params.joints["elbow"].i_clamp == 0.5
    assert params.joints["elbow"].kd == 60.0


def test_params_reach_the_run(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    p = prepare(Options(robot=robot, params=write(tmp_path, "p.toml", GOOD)), None)
    assert p.settings.bandwidth == 30.0 and p.duration == 2.0
    i = p.plant.actuators.index("m_shoulder")
    assert p.effort_limit[i] == 2.5 and p.speed_limit[i] == 400.0
    # Defaults elsewhere: URDF effort / |reduction|, velocity * |reduction|.
    assert p.plan.ctrl.armature[0] == pytest.approx(1e-5 * 2500)
    cli = prepare(Options(robot=robot, params=p.options.params, bandwidth=10.0), None)
    assert cli.settings.bandwidth == 10.0


def test_default_limits_follow_the_urdf_through_the_transmission(tmp_path):
    p = prepare(Options(robot=write(tmp_path, "arm.urdf", arm_ros1())), None)
    limits = dict(zip(p.plant.actuators, p.effort_limit, strict=True))
    speeds = dict(zip(p.plant.actuators, p.speed_limit, strict=True))
    assert limits["m_shoulder"] == pytest.approx(40 / 50)
    assert speeds["m_shoulder"] == pytest.approx(3 * 50)
    # Differential: tau_a = (tau_j0 +- tau_j1) / (2 ar); the largest over the URDF box.
    assert limits["m_left"] == pytest.approx((20 + 10) / (2 * 30))
    assert limits["m_right"] == pytest.approx((20 + 10) / (2 * 20))
    assert speeds["m_left"] == pytest.approx((3 + 3) * 30)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[actuators.m_shoulder]\neffort_limt = 2\n",
         "p.toml:2: actuators.m_shoulder.effort_limt: unknown key (expected rotor_inertia, "
         "effort_limit, velocity_limit)"),
        ("speed = 3\n", "p.toml:1: speed: unknown key"),
        ("[joints.elbow]\nkp = \"high\"\n", "p.toml:2: joints.elbow.kp: expected a number, "
         "got 'high'"),
        ("[joints.elbow]\nkd = -1\n", "p.toml:2: joints.elbow.kd: must be finite and zero or "
         "positive, got -1"),
        ("[actuators.m_left]\neffort_limit = 0\n", "p.toml:2: actuators.m_left.effort_limit: "
         "must be finite and positive"),
        ("[joints.elbow]\nkp = true\n", "joints.elbow.kp: expected a number, got True"),
        ("actuators = 3\n", "p.toml:1: actuators: must be a table of names"),
        ("[actuators]\nm_left = 2\n", "p.toml:2: actuators.m_left: must be a table"),
        ("[joints.elbow\nkp = 1\n", "p.toml:1: invalid TOML"),
    ],
)
def test_bad_params_are_one_line_errors_naming_the_key(tmp_path, text, message):
    path = write(tmp_path, "p.toml", text)
    with pytest.raises(InputError) as caught:
        load_params(path, str(tmp_path / "robot.urdf"))
    assert message in str(caught.value)
    assert "\n" not in str(caught.value)


def test_unknown_names_are_errors(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    params = write(tmp_path, "p.toml", "[actuators.m_shoulder]\nrotor_inertia = 0\n\n"
                                       "[actuators.m_elbow]\nrotor_inertia = 1e-5\n")
    with pytest.raises(InputError, match=r"p\.toml:4: actuators\.m_elbow: no actuator "
                                         r"'m_elbow' in .*arm\.urdf"):
        prepare(Options(robot=robot, params=params), None)
    params = write(tmp_path, "p.toml", "[joints.knee]\nkp = 1\n")
    with pytest.raises(InputError, match=r"p\.toml:1: joints\.knee: no moving joint 'knee'"):
        prepare(Options(robot=robot, params=params), None)


def test_pyproject_section_is_found_upward_from_the_robot(tmp_path):
    (tmp_path / "pyproject.toml").write_text(
        "[project]\nname = 'x'\n\n[tool.txtool.simulate]\nbandwidth = 12.0\n\n"
        "[tool.txtool.simulate.actuators.m_left]\neffort_limit = 3.0\n")
    folder = tmp_path / "robots" / "arm"
    folder.mkdir(parents=True)
    robot = write(folder, "arm.urdf", arm_ros1())
    p = prepare(Options(robot=robot), None)
    assert p.settings.bandwidth == 12.0
    assert p.effort_limit[p.plant.actuators.index("m_left")] == 3.0
    (tmp_path / "pyproject.toml").write_text(
        "[tool.txtool.simulate.actuators.m_left]\neffort_limt = 3.0\n")
    with pytest.raises(InputError, match=r"pyproject\.toml:2: tool\.txtool\.simulate\.actuators"
                                         r"\.m_left\.effort_limt: unknown key"):
        prepare(Options(robot=robot), None)


def test_a_pyproject_without_the_section_is_ignored(tmp_path):
    (tmp_path / "pyproject.toml").write_text("[project]\nname = 'x'\n")
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    assert prepare(Options(robot=robot), None).settings.bandwidth == 20.0


def test_a_pyproject_beside_the_robot_does_not_decide_inside_a_repository(tmp_path, monkeypatch):
    (tmp_path / ".git").mkdir()
    (tmp_path / "pyproject.toml").write_text("[tool.txtool.simulate]\nbandwidth = 12.0\n")
    folder = tmp_path / "robots"
    folder.mkdir()
    (folder / "pyproject.toml").write_text("[tool.txtool.simulate]\nbandwidth = 99.0\n")
    robot = write(folder, "arm.urdf", arm_ros1())
    monkeypatch.chdir(tmp_path)
    assert prepare(Options(robot=robot), None).settings.bandwidth == 12.0


@pytest.mark.parametrize(("text", "message"), [
    ("x = " + "[" * 50_000 + "]" * 50_000 + "\n", "configuration nested too deep"),
    (None, "is a named pipe (FIFO), not a regular file"),
])
def test_a_hostile_params_file_is_one_line(tmp_path, text, message):
    path = tmp_path / "p.toml"
    os.mkfifo(path) if text is None else path.write_text(text)
    with pytest.raises(InputError, match=rf"^{path}: {re.escape(message)}"):
        load_params(str(path), str(tmp_path / "robot.urdf"))
