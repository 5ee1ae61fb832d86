"""``convert --to bb --bb-topology``: a whole ``topology do ... end`` for the robot, joints
written as BB's URDF importer writes them (lib/bb/urdf/importer.ex @64ab268: render_joint
:351-364, origin :444-462, axis :385-404 and :464-478, limit :406-430)."""

from __future__ import annotations

from pathlib import Path

from tests.mechanics.test_bb_export import convert, ros1

ROBOT = """<robot name="r">
  <link name="world"/><link name="base"/><link name="arm"/><link name="slider"/>
  <link name="rim"/><link name="tilted"/>
  <joint name="anchor" type="fixed"><parent link="nowhere"/><child link="world"/></joint>
  <joint name="base" type="fixed"><parent link="world"/><child link="base"/>
    <origin xyz="0 0 0.5" rpy="0 0 0"/></joint>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0.1 0 0" rpy="0 0 1.5"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="30" velocity="2"/></joint>
  <joint name="slide" type="prismatic"><parent link="arm"/><child link="slider"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.2" effort="5" velocity="0.1"/></joint>
  <joint name="wheel" type="continuous"><parent link="arm"/><child link="rim"/>
    <axis xyz="0 0 1"/><limit effort="2" velocity="9"/></joint>
  <joint name="tilt" type="revolute"><parent link="rim"/><child link="tilted"/>
    <axis xyz="0 0.6 0.8"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  {body}
</robot>
"""


def test_topology_nests_links_joints_and_actuators(tmp_path: Path) -> None:
    body = ros1("s", "shoulder", "shoulder_motor", "-100", "0.25") + ros1(
        "p", "slide", "slide_motor", "2000")
    code, out, err = convert(tmp_path, ROBOT.format(body=body), "--bb-topology")
    assert (code, "error" in err) == (0, False)
    assert out == """\
# BB topology: links, joints and actuators (visuals, collisions, inertia, dynamics and mimic sensors: mix bb.from_urdf)
topology do
  link :world do
    joint :base_joint do
      type :fixed
      origin do
        z ~u(0.5 meter)
      end
      link :base do
        joint :shoulder do
          type :revolute
          origin do
            x ~u(0.1 meter)
            yaw ~u(1.5 radian)
          end
          axis do
            roll ~u(-90 degree)
          end
          limit do
            lower ~u(-1 radian)
            upper ~u(1 radian)
            effort ~u(30 newton_meter)
            velocity ~u(2 radian_per_second)
          end
          # transmission 's'
          actuator :shoulder_motor, Driver do
            transmission do
              reduction 100.0
              offset ~u(0.25 radian)
              reversed? true
            end
          end
          link :arm do
            joint :slide do
              type :prismatic
              axis do
                pitch ~u(90 degree)
              end
              limit do
                lower ~u(0 meter)
                upper ~u(0.2 meter)
                effort ~u(5 newton)
                velocity ~u(0.1 meter_per_second)
              end
              # transmission 'p'
              actuator :slide_motor, Driver do
                transmission do
                  reduction 2000.0
                end
              end
              link :slider
            end
            joint :wheel do
              type :continuous
              axis do
              end
              limit do
                effort ~u(2 newton_meter)
                velocity ~u(9 radian_per_second)
              end
              link :rim do
                joint :tilt do
                  type :revolute
                  axis do
                    roll ~u(-36.86989764584402 degree)
                    pitch ~u(0 degree)
                  end
                  limit do
                    lower ~u(0 radian)
                    upper ~u(1 radian)
                    effort ~u(1 newton_meter)
                    velocity ~u(1 radian_per_second)
                  end
                  link :tilted
                end
              end
            end
          end
        end
      end
    end
  end
end
"""


def test_a_fragment_has_no_topology(tmp_path: Path) -> None:
    xml = f"<robot name='r'>{ros1('t', 'j', 'm', '2')}</robot>"
    code, out, err = convert(tmp_path, xml, "--bb-topology")
    assert (code, out) == (1, "")
    assert "no <robot> with <link> elements, so no topology; give the robot's URDF" in err


def test_two_root_links_are_reported(tmp_path: Path) -> None:
    xml = (f"<robot name='r'><link name='a'/><link name='b'/>"
           f"{ros1('t', 'j', 'm', '2')}</robot>")
    code, _, err = convert(tmp_path, xml, "--bb-topology")
    assert code == 1
    assert "BB's topology has one root link, this robot has 2 (a, b)" in err
