"""The scripting API: ``import txtool`` and call validate, read, convert and simulate."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import txtool

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"
BROKEN = str(FIXTURES / "broken_robot.urdf")
DEMO = str(FIXTURES / "demo_robot.urdf")
SNIPPET = """<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>-50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_importing_txtool_loads_nothing_heavy():
    code = ("import sys, txtool; heavy = [m for m in ('lxml', 'pydantic', 'numpy', 'rich', "
            "'click', 'pinocchio') if m in sys.modules]; print(heavy)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


def test_validate_returns_the_findings_the_cli_prints():
    from click.testing import CliRunner

    from txtool.cli import cli

    problems = txtool.validate([BROKEN])
    assert problems and all(isinstance(p, txtool.Problem) for p in problems)
    printed = CliRunner().invoke(cli, ["validate", "-q", BROKEN]).stdout.splitlines()
    assert [f"{p.path}:{p.line}:{p.column}: {p.severity} {p.code}" for p in problems] == [
        " ".join(line.split()[:3]) for line in printed]
    assert txtool.validate(BROKEN, select=["TX106"]) == [p for p in problems if p.code == "TX106"]


def test_validate_raises_input_error_for_an_unreadable_file(tmp_path):
    with pytest.raises(txtool.InputError, match="missing.urdf"):
        txtool.validate([str(tmp_path / "missing.urdf")])


def test_read_a_file_and_text():
    names = [t.name for t in txtool.read(DEMO)]
    assert names and all(isinstance(t, txtool.Transmission) for t in txtool.read(DEMO))
    (t,) = txtool.read(SNIPPET)
    assert (t.name, t.kind, t.dialect) == ("t", "simple", "ros1")
    assert [a.name for a in t.actuators] == ["m"]


def test_convert_returns_text_and_losses():
    done = txtool.convert(SNIPPET, to="ros2-p2")
    assert isinstance(done, txtool.Conversion) and done.lossless and done.converted == 1
    assert "<ros2_control" in done.text and done.data == done.text.encode("utf-8")
    (back,) = txtool.read(done.text)
    assert back.dialect == "ros2-p2"
    assert txtool.convert(txtool.convert(DEMO, to="ros2-p1").text, to="ros1").converted >= 1


def test_convert_of_bad_input_raises_input_error():
    with pytest.raises(txtool.InputError):
        txtool.convert("<robot><transmission></robot>", to="ros2-p2")


def test_paths_may_be_path_objects(tmp_path):
    assert txtool.validate(Path(BROKEN)) == txtool.validate(BROKEN)
    assert txtool.validate([Path(BROKEN)], config=None) == txtool.validate([BROKEN])
    assert txtool.read(Path(DEMO)) == txtool.read(DEMO)
    assert txtool.convert(Path(DEMO), to="ros2-p2").data == txtool.convert(DEMO,
                                                                          to="ros2-p2").data
    assert txtool.read(DEMO, pkg_dirs=[Path(tmp_path)]) == txtool.read(DEMO)


@pytest.mark.parametrize("to", ["ros2", "ROS1", "ros2-p3", ""])
def test_an_unknown_target_dialect_raises_value_error_naming_the_choices(to):
    with pytest.raises(ValueError, match=r"unknown target dialect .*: choose one of 'ros1', "
                                         r"'ros2-p1', 'ros2-p2'"):
        txtool.convert(SNIPPET, to=to)  # type: ignore[arg-type]


def test_simulate_returns_one_result_per_config(tmp_path):
    pytest.importorskip("pinocchio")
    (own,) = txtool.simulate(DEMO, duration=0.5)
    assert own.passed and own.reasons == []
    flipped = tmp_path / "flipped.urdf"
    from txtool.simulation.demo import flipped_copy

    flipped, _ = flipped_copy(DEMO, tmp_path)
    (bad,) = txtool.simulate(DEMO, [str(flipped)], duration=0.5)
    assert not bad.passed and bad.reasons
    (alone,) = txtool.simulate(Path(DEMO), Path(flipped), duration=0.5)  # one config, a Path
    assert (alone.verdict, alone.reasons) == ("fail", bad.reasons)
    assert isinstance(alone, txtool.RunResult) and isinstance(alone.coverage, txtool.Coverage)
    assert all(isinstance(j, txtool.JointStats) for j in alone.joints.values())
    assert alone.series is None
    (kept,) = txtool.simulate(DEMO, duration=0.2, keep_series=True, skip=["wrist_trans"])
    assert kept.series is not None and kept.coverage.skipped[0][0] == "wrist_trans"


def test_the_examples_of_help_txtool_give_what_they_show(monkeypatch):
    import doctest

    monkeypatch.chdir(FIXTURES.parent)
    failed, tried = doctest.testmod(txtool, report=True)
    assert (failed, tried >= 5) == (0, True)


def test_convert_to_bb_gives_what_the_cli_prints(tmp_path):
    from click.testing import CliRunner

    from txtool.cli import cli

    robot = SNIPPET.replace('<robot name="r">', """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>""")
    done = txtool.convert(robot, to="bb")
    assert (done.converted, done.losses) == (1, [])
    assert "actuator :m, Driver do" in done.text and done.data == done.text.encode("utf-8")
    (tmp_path / "r.urdf").write_text(robot)
    printed = CliRunner().invoke(cli, ["convert", str(tmp_path / "r.urdf"), "--to", "bb"])
    assert (printed.exit_code, printed.stdout) == (0, done.text)
    topology = txtool.convert(DEMO, to="bb", bb_topology=True, bb_direction="negative-reduction")
    assert "topology do" in topology.text
    assert "reduction -" in topology.text and topology.losses


def test_simulate_refuses_a_misspelt_option():
    with pytest.raises(TypeError, match="duraton"):
        txtool.simulate(DEMO, duraton=0.5)  # type: ignore[call-arg]


def test_simulate_without_the_sim_extra_says_which_extra_in_one_line(monkeypatch):
    monkeypatch.setitem(sys.modules, "pinocchio", None)  # as if it were not installed
    with pytest.raises(txtool.MissingExtra) as raised:
        txtool.simulate(DEMO, duration=0.5)
    message = str(raised.value)
    assert isinstance(raised.value, ModuleNotFoundError) and "\n" not in message
    assert message.startswith("txtool.simulate needs the 'sim' extra: pip install 'txtool[sim]")


def test_the_api_is_what_all_says():
    assert sorted(txtool.__all__) == sorted(
        ["ActuatorStats", "Conversion", "Coverage", "InputError", "JointStats", "MissingExtra",
         "Problem", "RunResult", "Transmission", "__version__", "convert", "read", "simulate",
         "validate"])
    for name in txtool.__all__:
        assert getattr(txtool, name) is not None
    with pytest.raises(AttributeError):
        txtool.nothing  # noqa: B018


def test_model_replace_is_dataclasses_replace() -> None:
    """Conversions copy models with :func:`txtool.model.core.replace`, which sets slots
    directly: the copy equals what :func:`dataclasses.replace` builds, stays frozen, and an
    unknown field is refused as there."""
    import dataclasses

    from txtool.model.core import Location, Member, Number, Transmission, replace

    member = Member(name="j", role="joint1", mechanical_reduction=Number(value=2.0, text="2"),
                    interfaces=("effort",), location=Location(path="r.urdf", line=3, column=5))
    t = Transmission(name="t", type="x", kind="simple", joints=(member,), dialect="ros1")
    for value, changes in ((member, {"role": None, "offset": Number(value=None, text="")}),
                           (t, {"dialect": "ros2-p2", "actuators": (member,)}), (t, {})):
        copy = replace(value, **changes)
        assert copy == dataclasses.replace(value, **changes)
        assert copy is not value and hash(copy) == hash(dataclasses.replace(value, **changes))
        with pytest.raises(dataclasses.FrozenInstanceError):
            copy.name = "other"  # type: ignore[misc]
    with pytest.raises(TypeError, match="no field colour"):
        replace(member, colour="red")


def test_model_builder_is_the_class_constructor() -> None:
    """The readers build models with :func:`txtool.model.core.builder`, which sets slots
    directly: a value equals (and hashes as) the one the class builds, with the same defaults,
    stays frozen, and a missing or unknown field is refused as there."""
    import dataclasses

    from txtool.model.core import Location, Member, Number, Transmission, builder

    number = Number(value=2.0, text="2")
    cases = [
        (Number, {"value": None}),
        (Number, {"value": -0.0, "text": "-0"}),
        (Location, {"path": "r.urdf", "line": 3}),
        (Member, {"name": "j", "mechanical_reduction": number, "read_only": True}),
        (Transmission, {"name": "t", "type": "x", "kind": "simple", "dialect": "ros1",
                        "joints": (Member(name="j"),), "xml": "<transmission/>"}),
    ]
    for model, fields in cases:
        value = builder(model)(**fields)
        assert type(value) is model
        assert value == model(**fields) and hash(value) == hash(model(**fields))
        assert dataclasses.asdict(value) == dataclasses.asdict(model(**fields))
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(value, next(iter(fields)), "other")
    with pytest.raises(TypeError, match="name"):
        builder(Member)(role="joint1")
    with pytest.raises(TypeError, match="colour"):
        builder(Member)(name="j", colour="red")

    @dataclasses.dataclass(frozen=True, slots=True)
    class Listed:  # a default factory would be shared by every value: refused
        items: list[str] = dataclasses.field(default_factory=list)

    with pytest.raises(TypeError, match="Listed.items: a default factory is not supported"):
        builder(Listed)


def test_standard_type_names_each_standard_kind_and_refuses_others() -> None:
    from txtool.model.core import kind_of, standard_type

    for kind in ("simple", "differential", "four_bar"):
        assert kind_of(standard_type(kind)) == kind
    with pytest.raises(ValueError, match="kind 'other' has no standard type"):
        standard_type("other")  # type: ignore[arg-type]


def test_a_custom_type_is_not_translated_across_families() -> None:
    from txtool.dialects.translate import translate
    from txtool.model.core import Member, Transmission

    custom = Transmission(name="t", type="franka_hw/FrankaStateInterface", kind="other",
                          dialect="ros1", joints=(Member(name="j"),))
    across = translate(custom, "ros2-p2")
    assert across.transmission is custom
    assert across.losses == ["transmission 't': custom type 'franka_hw/FrankaStateInterface' "
                             "cannot be carried to ros2-p2; left as written"]
    assert translate(custom, "ros1").losses == []


def test_ros2_writer_writes_read_only_parameters_and_both_role_forms() -> None:
    from lxml import etree

    from txtool.dialects.ros2 import write
    from txtool.model.core import Member, Transmission

    t = Transmission(name="t", type="transmission_interface/SimpleTransmission", kind="simple",
                     dialect="ros2-p2", joints=(Member(name="j", role="joint1", read_only=True),),
                     actuators=(Member(name="m", role="actuator1"),),
                     parameters=(("mode", "fast"),))
    assert etree.tostring(write(t, "ros2-p2")).decode() == (
        '<transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
        '<actuator name="m" role="actuator1"/><joint name="j" role="joint1" read_only="true"/>'
        '<param name="mode">fast</param></transmission>')
    assert etree.tostring(write(t, "ros2-p1")).decode() == (
        '<transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
        '<actuator name="m"><role>actuator1</role></actuator>'
        '<joint name="j" read_only="true"><role>joint1</role></joint>'
        '<param name="mode">fast</param></transmission>')


def test_validate_reads_a_configuration_changed_between_calls(tmp_path, monkeypatch):
    (tmp_path / ".git").mkdir()
    monkeypatch.chdir(tmp_path)
    robot = tmp_path / "robot.urdf"
    robot.write_text(SNIPPET.replace("-50", "0"))
    assert [p.code for p in txtool.validate(robot)] == ["TX106"]
    (tmp_path / ".txtool.toml").write_text('ignore = ["TX106"]\n')
    assert txtool.validate(robot) == []
