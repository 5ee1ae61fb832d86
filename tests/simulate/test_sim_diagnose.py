"""The diagnosis alone (maps, no simulation): one parameter changed, that change named."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.simulate.robots import arm_ros1, write
from txtool.io.load import load
from txtool.mechanics.maps import from_parameters
from txtool.simulation import diagnose
from txtool.simulation.drive import Drive, assemble
from txtool.simulation.model import RobotModel, build
from txtool.simulation.setup import bind

UNITS = ("rad", "rad", "rad")


@pytest.fixture(scope="module")
def arm(tmp_path_factory) -> RobotModel:
    return build(load(write(tmp_path_factory.mktemp("arm"), "arm.urdf", arm_ros1())))


def drive(robot: RobotModel, kind: str, n: float, ar: list[float], jr: list[float],
          offset: list[float]) -> Drive:
    shoulder = from_parameters("t_shoulder", "simple", (n,), (1.0,), (0.0,),
                               joints=("shoulder",), actuators=("m_shoulder",))
    wrist = from_parameters("t_wrist", kind, tuple(ar), tuple(jr), tuple(offset),
                            joints=("elbow", "wrist"), actuators=("m_left", "m_right"))
    return assemble("config.urdf", [shoulder, wrist], robot)


def causes(robot: RobotModel, plant: Drive, ctrl: Drive) -> list[str]:
    return diagnose.causes(plant, ctrl, bind(plant, ctrl).S, UNITS)


def factor(k: float) -> str:
    size = f"reduction off by a factor {abs(k):.4g}"
    return "direction reversed" if k == -1 else (f"direction reversed and {size}" if k < 0
                                                 else size)


reduction = st.builds(lambda m, s: m * s, st.integers(1, 400).map(lambda i: i / 4),
                      st.sampled_from([-1.0, 1.0]))
offsets = st.lists(st.sampled_from([0.0, 0.1, -0.25]), min_size=2, max_size=2)
factors = st.sampled_from([-1.0, 2.0, -2.0, 0.5, 3.0])


@settings(max_examples=150, deadline=None)
@given(kind=st.sampled_from(["differential", "four_bar"]), n=reduction,
       ar=st.lists(reduction, min_size=2, max_size=2),
       jr=st.lists(reduction, min_size=2, max_size=2), offset=offsets,
       fault=st.sampled_from(["shoulder", "joint", "actuator", "offset"]),
       index=st.integers(0, 1), k=factors)
def test_one_changed_parameter_is_named(arm, kind, n, ar, jr, offset, fault, index, k):
    plant = drive(arm, kind, n, ar, jr, offset)
    assert causes(arm, plant, plant) == []
    joint, actuator = ("elbow", "wrist")[index], ("m_left", "m_right")[index]
    changed = {"n": n, "ar": list(ar), "jr": list(jr), "offset": list(offset)}
    if fault == "shoulder":
        changed["n"] = n * k
    elif fault == "joint":
        changed["jr"][index] *= k
    elif fault == "actuator":
        changed["ar"][index] *= k
    else:
        changed["offset"][index] += 0.1
    found = causes(arm, plant, drive(arm, kind, **changed))
    assert len(found) == 1, found
    where = "in the config's transmission"
    if fault == "shoulder":
        assert found[0] == (f"joint 'shoulder': {factor(k)} {where} 't_shoulder' (reduction "
                            f"{n * k:.6g}, the robot's {n:.6g})")
    elif fault == "offset":
        assert found[0].startswith(f"joint '{joint}': offset off by +0.1 rad {where} 't_wrist'")
    elif fault == "joint" and (kind == "differential" or index == 1):
        assert found[0] == (f"joint '{joint}': {factor(k)} {where} 't_wrist' (reduction "
                            f"{jr[index] * k:.6g}, the robot's {jr[index]:.6g})")
    else:
        # The four-bar's first joint reduction acts only as the product ar1 jr1, on the first
        # actuator; reversing a differential's actuator may read as swapping its joints.
        named = actuator if fault == "actuator" else "m_left"
        assert (found[0].startswith(f"actuator '{named}': {factor(k)} {where} 't_wrist'")
                or found[0].endswith(f"the same as {factor(k)} on actuator '{named}'")), found


def test_a_joint_without_transmission_in_the_config_is_named(arm):
    plant = drive(arm, "differential", 50.0, [30.0, 20.0], [1.0, 1.0], [0.1, 0.0])
    wrist = next(m for m in plant.maps if m.name == "t_wrist")
    ctrl = assemble("config.urdf", [wrist], arm)
    assert causes(arm, plant, ctrl) == [
        "joint 'shoulder': the config has no transmission where the robot has a simple "
        "transmission 't_shoulder'"]
