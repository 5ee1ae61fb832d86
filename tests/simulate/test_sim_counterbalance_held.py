"""The counterbalance is worked out on the motion that runs, with the held joints held."""

from __future__ import annotations

import math

from tests.simulate.robots import EFFORT, link, write
from txtool.simulation.counterbalance import KEEP
from txtool.simulation.reference import default_shifts
from txtool.simulation.run import Options, simulate_one

G = 9.81


def transmission(joint: str) -> str:
    return (f'<transmission name="t_{joint}"><type>transmission_interface/SimpleTransmission'
            f'</type><joint name="{joint}">{EFFORT}</joint><actuator name="m_{joint}">'
            "<mechanicalReduction>10</mechanicalReduction></actuator></transmission>")


def folding_arm(elbow_limit: float) -> str:
    """Two links in the x-z plane. The shoulder (about -y) has Coulomb friction of 90% of its
    limit: it is held still, at the middle of its range (horizontal). The elbow turns about +y,
    so link 2 points at ``shoulder - elbow``: in the full motion both joints sweep the same
    span together and link 2 keeps one angle, 1 rad up, where gravity needs
    ``G * 0.5 * cos(1)`` (2.65 N·m); with the shoulder held, link 2 sweeps 1 -/+ 0.75 rad and
    gravity needs up to ``G * 0.5 * cos(0.25)`` (4.75 N·m)."""
    centre = -1.0 - 3.0 * default_shifts(2)[1]  # the elbow's own centre comes out at -1 rad
    lower, upper = centre - 1.5, centre + 1.5
    return f"""<robot name="folding">
  <link name="base"/>
  {link("a", 0.5, 0.25)}
  {link("b", 1.0, 0.5)}
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="a"/>
    <axis xyz="0 -1 0"/><limit lower="-1.5" upper="1.5" effort="100" velocity="5"/>
    <dynamics friction="90"/></joint>
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0.5 0 0"/><axis xyz="0 1 0"/>
    <limit lower="{lower}" upper="{upper}" effort="{elbow_limit}" velocity="5"/></joint>
  {transmission("shoulder")}{transmission("elbow")}
</robot>"""


def test_a_held_joint_is_held_when_the_counterbalance_is_worked_out(tmp_path):
    robot = write(tmp_path, "folding.urdf", folding_arm(elbow_limit=4.0))
    run = simulate_one(Options(robot=robot, keep_series=False), None)
    assert any(n.startswith("joint 'shoulder' is held still") for n in run.notes), run.notes
    assert run.passed, run.reasons
    assert set(run.counterbalance) == {"elbow"}
    entry = run.counterbalance["elbow"]
    static = G * 0.5 * math.cos(0.25)
    assert abs(entry["static_load"] - static) < 1e-3 * static
    assert abs(entry["carried"] - (static - KEEP * 4.0)) < 1e-3 * static


def test_without_a_counterbalance_the_held_pose_is_what_the_actuator_cannot_hold(tmp_path):
    robot = write(tmp_path, "folding.urdf", folding_arm(elbow_limit=4.0))
    run = simulate_one(Options(robot=robot, keep_series=False, counterbalance=False), None)
    assert run.verdict == "fail"
    assert run.reasons[0].startswith("actuator 'm_elbow': holding joint 'elbow' against gravity "
                                     "needs 0.475")
