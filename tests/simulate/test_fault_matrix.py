"""The fault matrix over many robots: every fault of :mod:`tests.simulate.faults` injected into
each robot's own config fails (exit code 1) with the right kind of cause named, and the robot's
own config passes.

Robots: the generated ones of :mod:`tests.simulate.generated_robots` (several reductions, a
differential and a four-bar in both dialects, a counterbalanced heavy joint), complete robots of
the corpus and robots derived from the corpus UR5e. The default run keeps to the small ones
(about 10 s of CPU); ``TXTOOL_FAULT_MATRIX=full`` adds every form of the generated robots and
every complete corpus robot that simulates (several minutes: TIAGo and NAO take most).

One baseline per robot: its own config on the default motion of 1 s (which must pass); every
candidate then follows that same motion, given as a trajectory, so the motion is planned once.
Causes are read from ``RunResult.causes`` (their kinds), not from the text.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from tests.corpus import corpus_file
from tests.simulate.faults import FAULTS, inject
from tests.simulate.generated_robots import (
    CHAIN,
    COUNTERBALANCED,
    DIFFERENTIAL,
    FOUR_BAR,
    Generated,
    derived,
)
from txtool.simulation.result import KINDS, Cause, RunResult
from txtool.simulation.run import Options, exit_code, simulate_one

FULL = os.environ.get("TXTOOL_FAULT_MATRIX") == "full"
BASELINE_S = 1.0
# Reasons that are not a symptom of the run itself: the diagnosis, the exact comparison of the
# maps, the comparison of the interfaces.
NOT_SYMPTOMS = ("likely cause: ", "the config's maps differ from the robot's")
# Faults whose size does not depend on the motion's amplitude: these must show in the run
# itself (tracking, limits, effort path, divergence), not only in the comparison of the maps.
SEEN_IN_MOTION = ("sign reversed", "offset +0.3")
EVERY = frozenset(FAULTS)
SIMPLE_ONLY = EVERY - {"actuator roles swapped", "effort convention"}


@dataclass(frozen=True)
class Case:
    name: str
    robot: Callable[[Path], Path]  # writes (or finds) the robot file
    applicable: frozenset[str]  # the faults that apply to it
    joint: str | None = None  # the transmission edited: this joint's (None: the first)
    ros1_twin: Callable[[], str] | None = None


def generated(robot: Generated, form: str) -> Callable[[Path], Path]:
    def write(folder: Path) -> Path:
        path = folder / f"{robot.name}.{form}.urdf"
        path.write_text(getattr(robot, form)(), encoding="utf-8")
        return path
    return write


def corpus(name: str) -> Callable[[Path], Path]:
    return lambda folder: corpus_file(name)


def from_corpus(name: str, **changes) -> Callable[[Path], Path]:
    """A corpus robot with its transmissions or limits changed (:func:`derived`)."""
    def write(folder: Path) -> Path:
        path = folder / f"derived.{name}"
        path.write_bytes(derived(corpus_file(name).read_bytes(), **changes))
        return path
    return write


UR5E = "universal_robot__ur5e.urdf"


COUPLED = EVERY - {"joints swapped", "effort convention"}
DEFAULT = [
    Case("chain (ROS 1)", generated(CHAIN, "ros1"), SIMPLE_ONLY),
    Case("counterbalanced shoulder (ROS 2)", generated(COUNTERBALANCED, "ros2"), SIMPLE_ONLY,
         joint="shoulder"),
    Case("differential (ROS 1)", generated(DIFFERENTIAL, "ros1"), COUPLED, joint="elbow"),
    Case("differential (ROS 2)", generated(DIFFERENTIAL, "ros2"), COUPLED, joint="elbow"),
    Case("four-bar (ROS 2)", generated(FOUR_BAR, "ros2"), COUPLED | {"effort convention"},
         joint="elbow", ros1_twin=FOUR_BAR.ros1),
    Case("ur5e", corpus(UR5E), SIMPLE_ONLY),
    Case("husky", corpus("husky__husky.urdf"), SIMPLE_ONLY),
    # the UR5e with reductions from -160 to 120 and its last two joints on a differential
    Case("ur5e, reductions and a differential wrist", from_corpus(
        UR5E, reductions=(50, 100, -160, 80, 120, 30), pair=("wrist_2_joint", "wrist_3_joint")),
         COUPLED, joint="wrist_2_joint"),
    # gravity needs up to 52 N·m at its shoulder_lift_joint: 1.5 times a limit of 35 N·m
    Case("ur5e, counterbalanced shoulder", from_corpus(
        UR5E, effort={"shoulder_lift_joint": 35.0}), SIMPLE_ONLY, joint="shoulder_lift_joint"),
]
MORE = [
    Case("chain (ROS 2)", generated(CHAIN, "ros2"), SIMPLE_ONLY),
    Case("counterbalanced shoulder (ROS 1)", generated(COUNTERBALANCED, "ros1"), SIMPLE_ONLY,
         joint="shoulder"),
    Case("counterbalanced robot, its elbow (ROS 1)", generated(COUNTERBALANCED, "ros1"),
         SIMPLE_ONLY, joint="elbow"),
    # the simple shoulder comes first; the roles are swapped in the coupled transmission
    Case("differential's shoulder (ROS 1)", generated(DIFFERENTIAL, "ros1"), COUPLED),
    Case("four-bar's shoulder (ROS 2)", generated(FOUR_BAR, "ros2"), COUPLED),
    Case("baxter", corpus("baxter__baxter.urdf"), SIMPLE_ONLY),
    Case("iiwa14", corpus("iiwa_stack__iiwa14.urdf"), SIMPLE_ONLY),
    Case("j2s7s300", corpus("kinova_ros__j2s7s300.urdf"), SIMPLE_ONLY),
    Case("nao", corpus("nao_robot__naoV50.urdf"), SIMPLE_ONLY),
    Case("omy_f3m", corpus("open_manipulator__omy_f3m.urdf"), SIMPLE_ONLY),
    Case("gen3", corpus("ros_kortex__gen3_robotiq_2f_85.urdf"), SIMPLE_ONLY),
    Case("sawyer", corpus("sawyer_robot__sawyer.urdf"), SIMPLE_ONLY),
    # its wrist is a ROS 2 differential with reductions -1 and 1
    Case("tiago", corpus("tiago_robot__tiago_pal-hey5.urdf"), EVERY - {"effort convention"}),
    Case("yumi", corpus("yumi__yumi.urdf"), SIMPLE_ONLY),
]
CASES = DEFAULT + (MORE if FULL else [])


def symptoms(run: RunResult) -> list[str]:
    interfaces = {c.text for c in run.causes if c.kind == "interface"}
    return [r for r in run.reasons if not r.startswith(NOT_SYMPTOMS) and r not in interfaces]


def baseline_motion(robot: Path, folder: Path) -> tuple[RunResult, Path]:
    """The robot's own config on the default motion, and that motion as a trajectory file."""
    own = simulate_one(Options(robot=str(robot), duration=BASELINE_S), None)
    assert own.series is not None
    rows = np.column_stack([own.series.time, own.series.q_ref])[::5]
    path = folder / "motion.csv"
    np.savetxt(path, rows, delimiter=",", header="time," + ",".join(own.series.joints),
               comments="", fmt="%.10g")
    return own, path


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_every_fault_fails_with_its_cause_named(tmp_path, case):
    robot = case.robot(tmp_path)
    own, motion = baseline_motion(robot, tmp_path)
    assert own.passed and exit_code([own]) == 0, own.reasons[:3]
    options = Options(robot=str(robot), trajectory=str(motion), keep_series=False)
    again = simulate_one(options, str(robot))
    assert again.passed and not again.causes, again.reasons[:3]

    text = robot.read_bytes()
    twin = case.ros1_twin().encode() if case.ros1_twin else None
    wrong, applied = [], set()
    for fault_name in FAULTS:
        fault = inject(text, own.coverage.simulated, fault_name, case.joint, twin)
        if fault is None:
            continue
        applied.add(fault_name)
        candidate = tmp_path / "candidate.urdf"
        candidate.write_bytes(fault.config)
        run = simulate_one(options, str(candidate))
        kinds = {c.kind for c in run.causes}
        problems = []
        if exit_code([run]) != 1 or run.verdict != "fail":
            problems.append(f"verdict {run.verdict}")
        if not kinds & fault.named:
            problems.append(f"none of {sorted(fault.named)} named")
        if not kinds <= fault.allowed:
            problems.append(f"also named {sorted(kinds - fault.allowed)}")
        if fault_name in SEEN_IN_MOTION and not symptoms(run):
            problems.append("not seen in the motion, only in the maps")
        if case.joint in own.counterbalance and case.joint not in run.counterbalance:
            problems.append("the counterbalance was not assumed in the faulty run")
        if problems:
            wrong.append(f"{fault_name} on {fault.transmission}: {'; '.join(problems)}: "
                         f"{run.reasons[-3:]}")
    assert wrong == []
    assert applied == case.applicable


def test_the_counterbalanced_case_has_its_counterbalance(tmp_path):
    """The matrix's counterbalanced robot really is: its shoulder's static load exceeds its
    effort limit, so each of its faulty runs above carries the assumed counterbalance."""
    own = simulate_one(Options(robot=str(generated(COUNTERBALANCED, "ros2")(tmp_path)),
                               duration=BASELINE_S, keep_series=False), None)
    assert set(own.counterbalance) == {"shoulder"}
    load = own.counterbalance["shoulder"]
    assert 1.0 < float(load["static_load"]) / float(load["limit"]) < 4.0


def test_roles_swapped_in_a_ros2_block_change_nothing(tmp_path):
    """ros2_control reads no roles (ros2_control#3382): exchanging the role attributes of a
    differential's actuators is no fault there, and no cause is named."""
    text = DIFFERENTIAL.ros2()
    swapped = (text.replace('role="actuator1"><mechanical_reduction>30',
                            'role="actuator2"><mechanical_reduction>30')
               .replace('role="actuator2"><mechanical_reduction>20',
                        'role="actuator1"><mechanical_reduction>20'))
    assert swapped.count('role="actuator2"><mechanical_reduction>30') == 1
    robot = tmp_path / "robot.urdf"
    robot.write_text(text, encoding="utf-8")
    candidate = tmp_path / "candidate.urdf"
    candidate.write_text(swapped, encoding="utf-8")
    run = simulate_one(Options(robot=str(robot), duration=BASELINE_S, keep_series=False),
                       str(candidate))
    assert run.passed and run.causes == [], run.reasons


def _roles_swapped(text: str, first: str, second: str) -> str:
    """``<role>first</role>`` and ``<role>second</role>`` exchanged, each member in place."""
    assert f"<role>{first}</role>" in text and f"<role>{second}</role>" in text
    return (text.replace(f"<role>{first}</role>", "<role>@</role>")
            .replace(f"<role>{second}</role>", f"<role>{first}</role>")
            .replace("<role>@</role>", f"<role>{second}</role>"))


def _pair(tmp_path: Path, robot: str, candidate: str) -> RunResult:
    paths = []
    for name, text in (("robot.urdf", robot), ("candidate.urdf", candidate)):
        paths.append(tmp_path / name)
        paths[-1].write_text(text, encoding="utf-8")
    return simulate_one(Options(robot=str(paths[0]), duration=BASELINE_S, keep_series=False),
                        str(paths[1]))


def test_a_ros1_differential_with_its_actuator_roles_swapped_is_named_so(tmp_path):
    """ros_control takes the reductions by role and binds the actuators in XML order: the
    swapped roles give 'm_left' the reduction 20, which reads as two reduction factors. The
    cause is the roles."""
    robot = DIFFERENTIAL.ros1()
    run = _pair(tmp_path, robot, _roles_swapped(robot, "actuator1", "actuator2"))
    assert run.verdict == "fail"
    assert [c.kind for c in run.causes] == ["roles_swapped"]
    assert run.reasons[-1] == (
        "likely cause: transmission 't_wrist': actuator roles swapped in the config ('m_left' "
        "has actuator2, the robot's actuator1; 'm_right' has actuator1, the robot's "
        "actuator2); the loader then reads: actuator 'm_left': reduction off by a factor "
        "0.6667 in the config's transmission 't_wrist' (reduction 20, the robot's 30); "
        "actuator 'm_right': reduction off by a factor 1.5 in the config's transmission "
        "'t_wrist' (reduction 30, the robot's 20)")


def test_joint_and_actuator_roles_swapped_together_are_both_named(tmp_path):
    robot = DIFFERENTIAL.ros1()
    both = _roles_swapped(_roles_swapped(robot, "joint1", "joint2"), "actuator1", "actuator2")
    run = _pair(tmp_path, robot, both)
    texts = [c.text for c in run.causes if c.kind == "roles_swapped"]
    assert [t.split(" in the config")[0] for t in texts] == [
        "transmission 't_wrist': joint roles swapped",
        "transmission 't_wrist': actuator roles swapped"]
    assert "the loader then reads: " in texts[0]


def test_roles_swapped_between_equal_members_change_nothing(tmp_path):
    """Equal reductions and no offsets: whichever role each actuator has, ros_control binds the
    same numbers, so the config is the robot's and passes."""
    robot = DIFFERENTIAL.ros1().replace("<mechanicalReduction>20<", "<mechanicalReduction>30<")
    run = _pair(tmp_path, robot, _roles_swapped(robot, "actuator1", "actuator2"))
    assert run.passed and run.causes == [], run.reasons


def test_an_interface_change_alone_is_its_own_cause(tmp_path):
    robot = CHAIN.ros1()
    changed = robot.replace("EffortJointInterface", "PositionJointInterface", 1)
    run = _pair(tmp_path, robot, changed)
    assert run.reasons == ["joint 'base_yaw': the config commands it through position, the "
                           "robot through effort"]
    assert [c.kind for c in run.causes] == ["interface"]


def test_a_cause_has_a_known_kind():
    with pytest.raises(ValueError, match="unknown cause kind 'typo'"):
        Cause("typo", "text")
    assert Cause("offset", "joint 'a': offset off by +0.1 rad").kind in KINDS


def test_the_command_line_fails_a_role_swap_naming_the_roles(tmp_path):
    from click.testing import CliRunner

    from txtool.cli import cli

    robot = tmp_path / "robot.urdf"
    robot.write_text(DIFFERENTIAL.ros1(), encoding="utf-8")
    candidate = tmp_path / "candidate.urdf"
    candidate.write_text(_roles_swapped(DIFFERENTIAL.ros1(), "actuator1", "actuator2"),
                         encoding="utf-8")
    result = CliRunner().invoke(cli, ["simulate", str(robot), "--candidate", str(candidate),
                                      "--duration", "1"], catch_exceptions=False)
    assert (result.exit_code, result.stderr) == (1, "")
    assert "FAIL: joint 'wrist': tracking error" in result.stdout
    assert "\n  - likely cause: transmission 't_wrist': actuator roles swapped in the config " \
           "('m_left' has actuator2, the robot's actuator1;" in result.stdout
