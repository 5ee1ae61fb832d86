"""``simulate --campaign``: candidates on perturbed robots, run one after the other (--serial).

The same campaigns on a Dask cluster are in test_campaign_dask.py.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import jsonschema
import numpy as np
import pinocchio as pin
import pytest
from click.testing import CliRunner

from tests.lint.test_imports import PROBE
from tests.simulate.robots import arm_ros1, pendulum, write
from txtool.cli import cli
from txtool.io.xmlio import InputError
from txtool.simulation import loop
from txtool.simulation.campaign_file import Payload, draw, read_campaign
from txtool.simulation.campaign_task import Task, perturbed_plan, plant_robot, run_sample
from txtool.simulation.params import parse_toml
from txtool.simulation.run import Options, prepare

PENDULUM = pendulum(2.0, 0.5, 40.0)
FLIPPED = pendulum(2.0, 0.5, -40.0)


def simulate(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture
def robots(tmp_path, monkeypatch):
    """The pendulum and a copy with its reduction reversed, named from the working folder."""
    monkeypatch.chdir(tmp_path)
    write(tmp_path, "p.urdf", PENDULUM)
    write(tmp_path, "flipped.urdf", FLIPPED)
    return "p.urdf", "flipped.urdf"


def campaign(tmp_path, text: str) -> str:
    """The campaign file, named from the working folder (tmp_path in the CLI tests)."""
    write(tmp_path, "campaign.toml", text)
    return "campaign.toml"


def test_a_campaign_counts_each_candidate_s_samples_and_shows_the_first_failure(tmp_path,
                                                                                robots):
    robot, _ = robots
    path = campaign(tmp_path, """seed = 5
samples = 3
candidates = ["p.urdf", "flipped.urdf"]
[bounds]
gains = [0.9, 1.1]
[bounds.payload]
link = "rod"
mass = [0.0, 0.2]
xyz = [0.5, 0.0, 0.0]
""")
    code, out, err = simulate(robot, "--campaign", path, "--serial", "--duration", "0.3")
    assert (code, err) == (1, "")
    rows = [line for line in out.splitlines() if "urdf" in line and "│" in line]
    assert "p.urdf" in rows[0] and "pass" in rows[0] and "│       3 │    3 │    0 │" in rows[0]
    assert "flipped.urdf" in rows[1] and "│       3 │    0 │    3 │" in rows[1]
    assert "flipped.urdf: first failure at sample 0 (payload_mass 0.1" in out
    assert "joint 'swing': tracking error" in out
    assert out.rstrip().endswith("FAIL: 3 of 6 samples fail")


def test_the_table_fits_the_columns_given(tmp_path, robots, monkeypatch):
    path = campaign(tmp_path, "samples = 1\n")
    _, wide, _ = simulate(robots[0], "--campaign", path, "--serial", "--duration", "0.3")
    monkeypatch.setenv("COLUMNS", "72")
    _, narrow, _ = simulate(robots[0], "--campaign", path, "--serial", "--duration", "0.3")
    assert max(map(len, wide.splitlines())) > 72 >= max(map(len, narrow.splitlines()))
    assert "77.8% (swing, sample 0)" in wide and "PASS: the 1 sample passes" in wide


def test_the_json_has_the_same_numbers_with_units(tmp_path, robots):
    robot, _ = robots
    path = campaign(tmp_path, """seed = 5
samples = 2
candidates = ["p.urdf", "flipped.urdf"]
[bounds]
friction = [0.0, 0.5]
""")
    code, out, _ = simulate(robot, "--campaign", path, "--serial", "--duration", "0.3",
                            "--format", "json")
    document = json.loads(out)
    assert code == 1 and document["verdict"] == "fail"
    assert document["bounds"] == {"friction": [0.0, 0.5]}
    assert document["units"] == {"friction": "N·m (N)"}
    good, bad = document["candidates"]
    assert (good["verdict"], good["passed"], good["failed"]) == ("pass", 2, 0)
    assert good["first_failure"] is None
    assert 0 < good["worst"]["margin"] < 1 and good["worst"]["joint"] == "swing"
    assert good["worst"]["units"] == "rad"
    assert min(r["margin"] for r in good["runs"]) == good["worst"]["margin"]
    assert (bad["verdict"], bad["failed"]) == ("fail", 2)
    assert bad["first_failure"]["sample"] == 0
    samples = draw(read_campaign(path))
    assert [r["perturbation"] for r in good["runs"]] == samples
    assert bad["first_failure"]["perturbation"] == samples[0]
    assert bad["first_failure"]["reason"] == bad["runs"][0]["reason"]


def test_every_sample_passing_exits_0_and_a_candidate_checking_nothing_exits_3(tmp_path, robots):
    robot, _ = robots
    path = campaign(tmp_path, "samples = 2\n[bounds]\ngains = [0.95, 1.05]\n")
    code, out, _ = simulate(robot, "--campaign", path, "--serial", "--duration", "0.3")
    assert code == 0 and out.rstrip().endswith("PASS: all 2 samples pass")
    write(tmp_path, "bare.urdf", PENDULUM.split("<transmission")[0] + "</robot>")
    path = campaign(tmp_path, 'samples = 2\ncandidates = ["bare.urdf"]\n')
    code, out, _ = simulate(robot, "--campaign", path, "--serial", "--duration", "0.3")
    assert code == 3 and "INCONCLUSIVE" in out
    assert "│       2 │    0 │    0 │        2 │" in out


def test_a_candidate_named_twice_is_summarised_twice(tmp_path, robots):
    path = campaign(tmp_path, 'samples = 2\ncandidates = ["p.urdf", "p.urdf"]\n')
    code, out, _ = simulate(robots[0], "--campaign", path, "--serial", "--duration", "0.3",
                            "--format", "json")
    first, second = json.loads(out)["candidates"]
    assert code == 0 and first == second and first["samples"] == 2


def test_the_command_s_configs_are_the_candidates_when_the_file_names_none(tmp_path, robots):
    robot, flipped = robots
    path = campaign(tmp_path, "samples = 1\n")
    code, out, _ = simulate(robot, "--candidate", flipped, "--campaign", path, "--serial",
                            "--duration", "0.3", "--format", "json")
    assert code == 1
    assert [c["config"] for c in json.loads(out)["candidates"]] == [flipped]


def test_samples_depend_on_the_seed_alone_and_corners_come_first(tmp_path):
    text = """seed = 3
samples = 2
corners = true
[bounds]
damping = [0.0, 0.2]
gains = 1.2
sensor_noise = [0.0, 1e-4]
"""
    first = draw(read_campaign(write(tmp_path, "c.toml", text)))
    assert first == draw(read_campaign(write(tmp_path, "c.toml", text)))
    assert first[:4] == [{"damping": d, "gains": 1.2, "sensor_noise": n}
                         for d in (0.0, 0.2) for n in (0.0, 1e-4)]
    drawn = first[4:]
    assert len(drawn) == 2 and drawn[0] != drawn[1]
    assert all(0 <= s["damping"] <= 0.2 and s["gains"] == 1.2 for s in drawn)
    other = draw(read_campaign(write(tmp_path, "c.toml", text.replace("seed = 3", "seed = 4"))))
    assert other[:4] == first[:4] and other[4:] != drawn


@pytest.mark.parametrize(("text", "message"), [
    ("samples = 2\nseeds = 1\n", "campaign.toml:2: unknown key 'seeds' (expected seed, "),
    ("samples = 0\n", "campaign.toml:1: no samples: give samples = N (N > 0) or corners = true"),
    ("samples = -1\n", "campaign.toml:1: samples: expected a whole number of at least 0, got -1"),
    ("samples = 1\ncorners = 1\n", "campaign.toml:2: corners: expected true or false, got 1"),
    ("samples = 1\ncandidates = [1]\n", "campaign.toml:2: candidates: expected a list of file "),
    ("samples = 1\n[bounds]\ngains = [1.2, 0.8]\n",
     "campaign.toml:3: bounds.gains: low 1.2 is above high 0.8"),
    ("samples = 1\n[bounds]\ngains = [0, 2]\n", "campaign.toml:3: bounds.gains: must be positive"),
    ("samples = 1\n[bounds]\nfriction = -1\n",
     "campaign.toml:3: bounds.friction: must be zero or positive, got -1"),
    ("samples = 1\n[bounds]\ndamping = [0, 1, 2]\n",
     "campaign.toml:3: bounds.damping: expected [low, high] or one number"),
    ("samples = 1\n[bounds]\nstiffness = 1\n", "campaign.toml:3: bounds.stiffness: unknown"),
    ("samples = 1\nbounds = 3\n", "campaign.toml:2: bounds: expected a table"),
    ("samples = 1\n[bounds.payload]\nmass = 1\n",
     "campaign.toml:2: bounds.payload.link: expected the name of a link"),
    ("samples = 1\n[bounds.payload]\nlink = \"rod\"\n",
     "campaign.toml:2: bounds.payload.mass: missing"),
    ("samples = 1\n[bounds.payload]\nlink = \"rod\"\nmass = 1\nxyz = [0, 0]\n",
     "campaign.toml:5: bounds.payload.xyz: expected three numbers (m) within ±1000, got [0, 0]"),
    ("samples = 1\n[bounds.payload]\nlink = \"rod\"\nmass = 1\ncolour = 1\n",
     "campaign.toml:5: bounds.payload.colour: unknown"),
    ("samples = 1\n[bounds]\npayload = 2\n",
     "campaign.toml:3: bounds.payload: expected a table with link and mass"),
    ("samples = 200000\n", "campaign.toml:1: 200000 samples; a campaign takes at most 100000"),
    ("samples = [\n", "campaign.toml: invalid TOML"),
    ("samples = 1\n[bounds.payload]\nlink = \"nowhere\"\nmass = 1\n",
     "campaign.toml:3: bounds.payload.link: no link 'nowhere' in the robot"),
    ("samples = 1\n[bounds.payload]\nlink = \"base\"\nmass = 1\n",
     "campaign.toml:3: bounds.payload.link: link 'base' is fixed to the base"),
    ("samples = 1\n[bounds.payload]\nlink = \"nowhere\"\nmass = 0\n",
     "campaign.toml:3: bounds.payload.link: no link 'nowhere' in the robot"),
    ("samples = 1\ncandidates = [\"missing.urdf\"]\n", "missing.urdf"),
])
def test_a_bad_campaign_is_one_line_and_exit_2(tmp_path, robots, text, message):
    robot, _ = robots
    path = campaign(tmp_path, text)
    code, out, err = simulate(robot, "--campaign", path, "--serial", "--duration", "0.3")
    assert (code, out) == (2, "")
    assert len(err.splitlines()) == 1 and message in err, err
    assert err.startswith(f"txtool: {path}") or message == "missing.urdf"


def test_a_xacro_candidate_is_refused_under_no_xacro(tmp_path, robots):
    robot, _ = robots
    write(tmp_path, "c.urdf.xacro", PENDULUM)
    path = campaign(tmp_path, 'samples = 1\ncandidates = ["c.urdf.xacro"]\n')
    code, out, err = simulate(robot, "--campaign", path, "--serial", "--no-xacro")
    assert (code, out) == (2, "")
    assert err.startswith("txtool: c.urdf.xacro: simulate needs the xacro expansion")


@pytest.mark.parametrize(("args", "message"), [
    (["--csv", "out.csv"], "--csv: not with --campaign"),
    (["--plot", "out.png"], "--plot: not with --campaign"),
    (["--serial", "--workers", "2"], "--serial: not with --scheduler or --workers"),
    (["--scheduler", "tcp://127.0.0.1:1", "--workers", "2"], "--workers: sizes the local"),
])
def test_options_that_do_not_go_with_a_campaign_are_refused(tmp_path, robots, args, message):
    robot, _ = robots
    path = campaign(tmp_path, "samples = 1\n")
    code, out, err = simulate(robot, "--campaign", path, *args)
    assert (code, out) == (2, "") and message in err


@pytest.mark.parametrize("option", [["--serial"], ["--workers", "2"],
                                    ["--scheduler", "tcp://127.0.0.1:1"]])
def test_cluster_options_need_a_campaign(robots, option):
    code, out, err = simulate(robots[0], *option)
    assert (code, out) == (2, "") and "only with --campaign FILE" in err


def options(robot: str) -> Options:
    return Options(robot=robot, duration=0.3, keep_series=False)


def task(robot: str, payload: Payload | None = None, **perturbation: float) -> Task:
    return Task(options(robot), None, robot, 0, perturbation, 1, payload, "here")


def test_the_payload_loads_the_plant_only(tmp_path, robots):
    """A point mass m at the end of the rod adds m g L to the gravity torque at horizontal."""
    robot, _ = robots
    p = prepare(options(robot), None)
    rod = Payload("rod", (0.5, 0.0, 0.0))
    heavier = plant_robot(p.robot, {"payload_mass": 1.5}, task(robot, rod, payload_mass=1.5))
    zero = np.zeros(1)
    before = pin.computeGeneralizedGravity(p.robot.model, p.robot.model.createData(), zero)
    after = pin.computeGeneralizedGravity(heavier.model, heavier.model.createData(), zero)
    assert after[0] - before[0] == pytest.approx(1.5 * 9.81 * 0.5, rel=1e-12)
    empty = plant_robot(p.robot, {"payload_mass": 0.0}, task(robot, rod, payload_mass=0.0))
    assert empty.model.inertias[1] == p.robot.model.inertias[1]
    plan = perturbed_plan(p, task(robot, rod, payload_mass=1.5))
    assert plan.ctrl is p.plan.ctrl  # the controller keeps the URDF's model
    assert plan.plant.inertias[1].mass == pytest.approx(p.robot.model.inertias[1].mass + 1.5)


def test_damping_friction_rotor_inertia_and_gains_reach_the_loop(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    params = write(tmp_path, "p.toml", "[actuators.m_shoulder]\nrotor_inertia = 1e-4\n")
    p = prepare(Options(robot=robot, params=params, duration=0.3), None)
    t = Task(p.options, None, robot, 0,
             {"damping": 0.3, "friction": 0.2, "rotor_inertia": 2.0, "gains": 0.5}, 1)
    plan = perturbed_plan(p, t)
    assert np.array_equal(plan.dynamics.damping, p.robot.damping + 0.3)
    assert np.array_equal(plan.dynamics.friction, p.robot.friction + 0.2)
    shoulder = p.robot.joints.index("shoulder")
    h = plan.dt / plan.dynamics.substeps
    rotor = plan.dynamics.model.armature[shoulder] - h * plan.dynamics.damping[shoulder]
    assert rotor == pytest.approx(2.0 * 1e-4 * 50**2)  # twice the rotor, through n = 50
    assert p.controller is not None
    ff, first = plan.slots["ff"], p.ref
    assert np.allclose(plan.start_rows[:, ff], first.qdd + 0.5 * p.controller.kp * first.q
                       + 0.5 * p.controller.kd * first.qd)
    assert np.array_equal(plan.ctrl.armature, p.plan.ctrl.armature)


def test_sensor_noise_is_on_the_position_readings_and_the_same_for_the_same_seed(tmp_path,
                                                                                robots):
    robot, _ = robots
    p = prepare(options(robot), None)
    state = loop.run(perturbed_plan(p, task(robot, sensor_noise=1e-3)))
    rows, s = state.rows[:-1], state.slots
    true = rows[:, s["x"]] @ p.plant.pos_j2a.T + p.plant.pos_j2a_c
    noise = (rows[:, s["enc"]] - true)[:, 0]
    assert 0.8e-3 < noise.std() < 1.2e-3 and abs(noise.mean()) < 3e-4
    speeds = rows[:, s["v"]] @ p.plant.vel_j2a.T
    assert np.array_equal(rows[:, s["encv"]], speeds)  # exact speeds, as the run reads them
    again = run_sample(task(robot, sensor_noise=1e-3))
    assert again == run_sample(task(robot, sensor_noise=1e-3))
    assert again != run_sample(Task(options(robot), None, robot, 1, {"sensor_noise": 1e-3}, 1))
    still = run_sample(task(robot, sensor_noise=0.0))
    assert still["margin"] == pytest.approx(run_sample(task(robot))["margin"], abs=1e-9)


def test_sensor_noise_with_encoders_is_quantised(tmp_path, robots):
    robot, _ = robots
    p = prepare(Options(robot=robot, duration=0.3, encoder_counts=4096), None)
    state = loop.run(perturbed_plan(p, Task(p.options, None, robot, 0, {"sensor_noise": 1e-3},
                                            1)))
    counts = state.rows[:-1, state.slots["enc"]] / (2 * math.pi / 4096)
    assert np.allclose(counts, np.rint(counts), rtol=0, atol=1e-6)


def test_a_diverging_sample_has_no_margin(tmp_path):
    """Gains scaled beyond what the sampled loop can take (kd dt = 16), with no effort limit
    to hold them: the run diverges, a failure without a margin."""
    robot = write(tmp_path, "p.urdf", PENDULUM.replace('effort="100"', 'effort="0"'))
    record = run_sample(Task(Options(robot=robot, duration=2.0), None, robot, 0,
                             {"gains": 400.0}, 1))
    assert record["verdict"] == "fail" and record["margin"] is None
    assert record["max_error"] is None and record["joint"] == "swing"
    assert record["reason"].startswith("the simulation diverged at t=")


@pytest.mark.parametrize("command", [["simulate", "--duration", "0.2"], ["show"],
                                     ["convert", "--to", "ros2-p2"]])
def test_only_a_campaign_on_a_cluster_imports_dask(tmp_path, robots, command):
    result = subprocess.run([sys.executable, "-c", PROBE, command[0], robots[0], *command[1:]],
                            capture_output=True, text=True, timeout=120, cwd=tmp_path)
    probe = json.loads(result.stderr.strip().splitlines()[-1])
    assert probe["code"] == 0
    assert "dask" not in probe["loaded"] and "distributed" not in probe["loaded"]


ROOT = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((ROOT / "schemas" / "campaign.schema.json").read_text(encoding="utf-8"))


def docs_example() -> str:
    section = (ROOT / "docs" / "simulate.md").read_text(encoding="utf-8").split("## Campaigns")[1]
    return section.split("```toml\n")[1].split("```")[0]


@pytest.mark.parametrize("text", [
    docs_example(),
    "samples = 3\n",
    "corners = true\n[bounds]\ngains = [0.5, 2]\n[bounds.payload]\nlink = \"a\"\nmass = 1\n",
])
def test_the_schema_and_the_reader_accept_the_same_files(tmp_path, text):
    jsonschema.validate(parse_toml(text, "c.toml"), SCHEMA)
    assert draw(read_campaign(write(tmp_path, "c.toml", text)))


@pytest.mark.parametrize("text", [
    "samples = 1\nseeds = 1\n", "samples = -1\n", "samples = 1\ncorners = 1\n",
    "samples = 1\ncandidates = [1]\n", "samples = 1\n[bounds]\ngains = 0\n",
    "samples = 1\n[bounds]\nfriction = -1\n", "samples = 1\n[bounds]\ndamping = [0, 1, 2]\n",
    "samples = 1\n[bounds]\nstiffness = 1\n", "samples = 1\n[bounds.payload]\nmass = 1\n",
    "samples = 1\n[bounds.payload]\nlink = \"a\"\nmass = 1\nxyz = [0, 0]\n",
])
def test_the_schema_and_the_reader_refuse_the_same_files(tmp_path, text):
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(parse_toml(text, "c.toml"), SCHEMA)
    with pytest.raises(InputError):
        read_campaign(write(tmp_path, "c.toml", text))
