"""Every complete robot of the corpus against its own transmissions: no false alarms.

The complete robots are the corpus's expanded URDFs (MANIFEST notes "EXPANDED", "Expanded",
"COMMITTED ... URDF", "expanded"). Runs are 1 s (the default motion shrinks to fit) to keep the
suite short; default settings otherwise. Two robots cannot hold themselves with the effort
limits their URDF gives, because the URDF leaves out what carries the load on the real robot:
PR2's arm counterbalance springs (PR2's transmissions are custom types, so it is not simulated)
and TIAGo's base suspension springs. By default simulate
assumes such a counterbalance and says so per joint; with ``--no-counterbalance`` they fail,
naming the actuator that cannot hold its joint.
"""

from __future__ import annotations

import pytest

from tests.corpus import corpus_dir, corpus_file
from txtool.simulation.run import Options, simulate_one

COMPLETE = (
    "baxter__baxter.urdf",
    "franka_ros__panda-gazebo.urdf",
    "husky__husky.urdf",
    "iiwa_stack__iiwa14.urdf",
    "kinova_ros__j2s7s300.urdf",
    "moveit_resources__pr2_robot.urdf",
    "nao_robot__naoV50.urdf",
    "open_manipulator__omy_f3m.urdf",
    "ros_kortex__gen3_robotiq_2f_85.urdf",
    "sawyer_robot__sawyer.urdf",
    "shadow__shadowhand_motor.urdf",
    "tiago_robot__tiago_pal-hey5.urdf",
    "universal_robot__ur5e.urdf",
    "yumi__yumi.urdf",
)
COUNTERBALANCED = {
    "tiago_robot__tiago_pal-hey5.urdf": {"suspension_left_joint", "suspension_right_joint"},
}
CANNOT_HOLD = {
    "tiago_robot__tiago_pal-hey5.urdf": "actuator 'suspension_left_joint': holding joint "
                                        "'suspension_left_joint' against gravity needs 116",
}
# Robots none of whose transmissions the simulator can drive: custom types with no standard
# maths (pr2_mechanism_model, sr_mechanism_model), ros_control refusing every transmission
# (the Panda's have no reduction: franka_gazebo reads none, ros_control needs one), or none
# read at all (OMY's are top-level ROS 1 transmissions, its only readers gz_ros2_control and
# ros2_control, which read those inside <ros2_control>: validate's TX305). Their self-check
# checks nothing, so it is inconclusive, never a pass.
INCONCLUSIVE = {
    "open_manipulator__omy_f3m.urdf": "no reader of the config reads any of its 10 "
                                      "transmissions (read by no reader of the file: it stands "
                                      "outside every <ros2_control> block",
    "franka_ros__panda-gazebo.urdf": "none of the config's 9 transmissions can be simulated",
    "moveit_resources__pr2_robot.urdf": "none of the config's 30 transmissions can be simulated "
                                        "(custom type 'pr2_mechanism_model/",
    "shadow__shadowhand_motor.urdf": "none of the config's 24 transmissions can be simulated "
                                     "(custom type 'sr_mechanism_model/SimpleTransmission'",
}


def test_the_list_is_the_manifests_expanded_robots():
    manifest = (corpus_dir() / "MANIFEST.tsv").read_text(encoding="utf-8").splitlines()
    expanded = {line.split("\t")[0] for line in manifest[1:]
                if any(w in line.split("\t")[-1] for w in ("EXPANDED", "Expanded", "expanded",
                                                           "COMMITTED"))}
    assert expanded == set(COMPLETE)


@pytest.mark.parametrize("name", COMPLETE)
def test_complete_robot_passes_its_own_self_check(name):
    run = simulate_one(Options(robot=str(corpus_file(name)), duration=1.0, keep_series=False),
                       None)
    if name in INCONCLUSIVE:
        assert (run.verdict, run.reasons) == ("inconclusive", [])
        assert run.coverage.why_nothing().startswith(INCONCLUSIVE[name])
        return
    assert run.passed, (run.reasons[:3], run.notes)
    assert not any(r.startswith("the simulation diverged") for r in run.reasons)
    assert set(run.counterbalance) == COUNTERBALANCED.get(name, set())
    for joint in run.counterbalance:
        assert any(n.startswith(f"joint '{joint}': gravity needs up to") for n in run.notes)


@pytest.mark.parametrize("name", sorted(CANNOT_HOLD))
def test_without_a_counterbalance_the_robot_cannot_hold_itself(name):
    options = Options(robot=str(corpus_file(name)), duration=1.0, keep_series=False,
                      counterbalance=False)
    run = simulate_one(options, None)
    assert run.reasons[0].startswith(CANNOT_HOLD[name]), run.reasons[:2]
