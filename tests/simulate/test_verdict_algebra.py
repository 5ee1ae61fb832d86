"""The verdict algebra of simulate and campaigns, exhaustively: a run's verdict from its reasons
and coverage, every pair and triple of verdicts combined (a failure outranks an inconclusive
run, which outranks a pass, in any order), every interface mismatch (subsets included), the
worst sample of a campaign (a diverged one is the worst of all), and the seeds that reach each
random source. The deciding functions are pure; the one run below is a pendulum's 0.3 s."""

from __future__ import annotations

import itertools
import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from tests.simulate.robots import pendulum, write
from txtool.cli import cli
from txtool.simulation import campaign as campaigns
from txtool.simulation.campaign_file import read_campaign
from txtool.simulation.campaign_task import NoisyEncoder, Task, perturbed_plan
from txtool.simulation.checks import interface_mismatch
from txtool.simulation.drive import COMMANDS, Drive
from txtool.simulation.report import overall_verdict
from txtool.simulation.result import Coverage, RunResult
from txtool.simulation.run import EXIT_INCONCLUSIVE, Options, exit_code, prepare

VERDICTS = ("pass", "fail", "inconclusive")
RANK = {"fail": 0, "inconclusive": 1, "pass": 2}  # the first outranks the others
EXIT = {"pass": 0, "fail": 1, "inconclusive": EXIT_INCONCLUSIVE}
NOTHING = Coverage(transmissions=2)
PARTIAL = Coverage(transmissions=2, simulated=("t1",), joints=2, joints_checked=1)
FULL = Coverage(transmissions=2, simulated=("t1", "t2"), joints=2, joints_checked=2)


def run_with(reasons: list[str], coverage: Coverage) -> RunResult:
    return RunResult("robot.urdf", "config.urdf", 0.001, 0, 0.0, "", {}, {}, reasons, [],
                     coverage=coverage)


def run_of(verdict: str) -> RunResult:
    return {"pass": run_with([], FULL), "fail": run_with(["joint 'j': off"], FULL),
            "inconclusive": run_with([], NOTHING)}[verdict]


@pytest.mark.parametrize(("reasons", "coverage", "verdict"), [
    ([], FULL, "pass"),
    ([], PARTIAL, "pass"),
    ([], NOTHING, "inconclusive"),
    ([], Coverage(), "inconclusive"),
    (["joint 'j': off"], FULL, "fail"),
    (["joint 'j': off"], PARTIAL, "fail"),
    (["joint 'j': off"], NOTHING, "fail"),  # a failure is one even where nothing was simulated
    (["a", "b"], Coverage(), "fail"),
])
def test_a_run_s_verdict_from_its_reasons_and_coverage(reasons, coverage, verdict):
    run = run_with(reasons, coverage)
    assert run.verdict == verdict
    assert (run.passed, run.failed) == (verdict == "pass", verdict == "fail")
    assert exit_code([run]) == EXIT[verdict]


def combinations() -> list[tuple[str, ...]]:
    return [pair for size in (1, 2, 3) for pair in itertools.product(VERDICTS, repeat=size)]


@pytest.mark.parametrize("verdicts", combinations(), ids="-".join)
def test_several_runs_take_the_highest_ranked_verdict_in_any_order(verdicts):
    expected = min(verdicts, key=RANK.__getitem__)
    runs = [run_of(v) for v in verdicts]
    assert overall_verdict(runs) == expected
    assert exit_code(runs) == EXIT[expected]


def record(sample: int, verdict: str, margin: float | None = 0.5) -> dict:
    """A campaign's record of one sample (campaign_task.run_sample's shape)."""
    if verdict == "inconclusive":
        return {"sample": sample, "perturbation": {}, "verdict": verdict, "margin": None,
                "joint": None, "max_error": None, "units": None, "reason": None}
    return {"sample": sample, "perturbation": {"gains": 1.0 + sample}, "verdict": verdict,
            "margin": margin, "joint": f"j{sample}",
            "max_error": None if margin is None else 1 - margin, "units": "rad",
            "reason": None if verdict == "pass" else f"reason {sample}"}


@pytest.mark.parametrize("verdicts", combinations(), ids="-".join)
def test_a_candidate_s_verdict_counts_and_first_failure_from_its_samples(verdicts):
    runs = [record(i, v, margin=0.5 if v == "pass" else -0.5) for i, v in enumerate(verdicts)]
    summary = campaigns.summary("c.urdf", runs)
    expected = min(verdicts, key=RANK.__getitem__)
    assert summary["verdict"] == expected
    assert campaigns.exit_code({"verdict": summary["verdict"]}) == EXIT[expected]
    assert (summary["samples"], summary["passed"], summary["failed"],
            summary["inconclusive"]) == (len(verdicts), verdicts.count("pass"),
                                         verdicts.count("fail"), verdicts.count("inconclusive"))
    failing = [i for i, v in enumerate(verdicts) if v == "fail"]
    first = summary["first_failure"]
    assert (first and first["sample"]) == (failing[0] if failing else None)
    if first is not None:
        assert first == {"sample": failing[0], "perturbation": {"gains": 1.0 + failing[0]},
                         "reason": f"reason {failing[0]}"}
    scored = [i for i, v in enumerate(verdicts) if v != "inconclusive"]
    worst = summary["worst"]
    assert (worst and worst["sample"]) == (min(scored, key=lambda i: runs[i]["margin"])
                                           if scored else None)


@pytest.mark.parametrize("position", [0, 1, 2])
def test_a_diverged_sample_is_the_worst_wherever_it_stands(position):
    margins: list[float | None] = [0.9, -0.4, 0.1]
    margins.insert(position, None)
    runs = [record(i, "pass" if m is not None and m > 0 else "fail", m)
            for i, m in enumerate(margins)]
    worst = campaigns.summary("c.urdf", runs)["worst"]
    assert worst == {"sample": position, "margin": None, "joint": f"j{position}",
                     "max_error": None, "units": "rad"}


def test_the_worst_margin_is_the_smallest_and_inconclusive_samples_have_none():
    runs = [record(0, "pass", 0.3), record(1, "inconclusive"), record(2, "pass", 0.2),
            record(3, "pass", 0.7)]
    assert campaigns.summary("c.urdf", runs)["worst"]["sample"] == 2
    assert campaigns.summary("c.urdf", [record(0, "inconclusive")])["worst"] is None


def drive(commands: dict[str, frozenset[str]]) -> Drive:
    empty = np.zeros((0, 0))
    return Drive("robot.urdf", (), (), (), empty, np.zeros(0), empty, np.zeros(0), empty,
                 empty, empty, empty, (), commands=commands)


KINDS = [frozenset(c) for size in (1, 2, 3) for c in itertools.combinations(COMMANDS, size)]


@pytest.mark.parametrize("robot", KINDS, ids=lambda k: "+".join(sorted(k)))
def test_every_other_set_of_command_interfaces_is_a_mismatch(robot):
    for config in KINDS:
        reasons = interface_mismatch(drive({"j": robot, "k": robot}), drive({"j": config}))
        if config == robot:
            assert reasons == []
        else:
            # a subset (position of position and velocity) or a superset is not the robot's
            assert reasons == [f"joint 'j': the config commands it through "
                               f"{' and '.join(sorted(config))}, the robot through "
                               f"{' and '.join(sorted(robot))}"], (robot, config)
    # a joint the config declares no interface for is not compared
    assert interface_mismatch(drive({"j": robot}), drive({})) == []


def test_campaign_seed_reaches_every_task(tmp_path):
    write(tmp_path, "p.urdf", PENDULUM)
    path = write(tmp_path, "c.toml", 'seed = 12345\nsamples = 3\ncandidates = ["a", "b"]\n'
                 "[bounds]\nsensor_noise = [0.001, 0.002]\n")
    tasks = campaigns.tasks_of(read_campaign(path), Options(robot=str(tmp_path / "p.urdf")))
    assert [(Path(t.label).name, t.sample, t.seed) for t in tasks] == [
        (label, sample, 12345) for label in ("a", "b") for sample in range(3)]


def test_the_sensor_noise_depends_on_the_campaign_seed_and_the_sample(tmp_path):
    robot = write(tmp_path, "p.urdf", PENDULUM)
    prepared = prepare(Options(robot=robot, duration=0.05, keep_series=False), None)

    def noise(seed: int, sample: int) -> np.ndarray:
        task = Task(prepared.options, None, robot, sample, {"sensor_noise": 1e-3}, seed)
        encoder = perturbed_plan(prepared, task).encoder
        assert isinstance(encoder, NoisyEncoder)
        return encoder.noise

    first = noise(1, 2)
    assert first.shape[0] == prepared.plan.steps + 1 and first.std() > 0
    assert np.array_equal(first, noise(1, 2))  # the same seed and sample: the same noise
    for other in (noise(7, 2), noise(1, 3), noise(2, 1), noise(0, 2)):
        assert not np.allclose(first, other)


PENDULUM = pendulum(2.0, 0.5, 40.0)


def simulate(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def test_a_failing_candidate_outranks_one_that_checks_nothing_in_the_campaign(tmp_path,
                                                                               monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, "p.urdf", PENDULUM)
    write(tmp_path, "flipped.urdf", pendulum(2.0, 0.5, -40.0))
    write(tmp_path, "bare.urdf", PENDULUM.split("<transmission")[0] + "</robot>")
    for order in (["bare.urdf", "flipped.urdf"], ["flipped.urdf", "bare.urdf"]):
        write(tmp_path, "c.toml", f"samples = 1\ncandidates = {json.dumps(order)}\n")
        code, out, _ = simulate("p.urdf", "--campaign", "c.toml", "--serial", "--duration",
                                "0.3", "--format", "json")
        document = json.loads(out)
        verdicts = {c["config"]: c["verdict"] for c in document["candidates"]}
        assert verdicts == {"bare.urdf": "inconclusive", "flipped.urdf": "fail"}
        assert (code, document["verdict"]) == (1, "fail")
