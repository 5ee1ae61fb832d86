"""``txtool simulate``: argument parsing only; the work is in :mod:`txtool.simulation.app`."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import click

from txtool.commands.common import (
    FILE,
    FORMAT_OPTION,
    NO_XACRO_OPTION,
    Choice,
    RenamedOption,
    exit_on_input_error,
    refuse_unexpanded,
    require_extra,
    xacro_disabled,
    xacro_options,
)
from txtool.io.xmlio import InputError, XacroOptions
from txtool.model.distro import CHOICES

if TYPE_CHECKING:
    from txtool.simulation.run import Options


def campaign_options(function: Callable[..., Any]) -> Callable[..., Any]:
    """``--campaign`` and where it runs (docs/simulate.md, "Campaigns")."""
    options = [
        click.option("--campaign", "campaign_path", type=click.Path(dir_okay=False),
                     metavar="FILE.toml",
                     help="Run every candidate on perturbed robots drawn from FILE (payload, "
                          "friction, rotor inertia, gains, sensor noise) on Dask."),
        click.option("--scheduler", metavar="ADDRESS",
                     help="With --campaign: the Dask scheduler of a cluster, e.g. "
                          "tcp://host:8786 (default: a local cluster on this machine)."),
        click.option("--workers", type=click.IntRange(min=1), metavar="N",
                     help="With --campaign: processes of the local cluster  "
                          "[default: one per core]"),
        click.option("--serial", is_flag=True,
                     help="With --campaign: run the samples one after the other in this "
                          "process, without Dask."),
    ]
    for option in reversed(options):
        function = option(function)
    return function


def run_campaign(options: Options, *, campaign_path: str, scheduler: str | None,
                 workers: int | None, serial: bool, csv_path: str | None,
                 plot_path: str | None, output_format: str, no_xacro: bool) -> int:
    """``--campaign``: the checks of its options, then :func:`txtool.simulation.campaign.main`."""
    for given, name in ((csv_path, "--csv"), (plot_path, "--plot")):
        if given is not None:
            raise InputError(f"{name}: not with --campaign (a campaign writes its summary only)")
    if serial and (scheduler is not None or workers is not None):
        raise InputError("--serial: not with --scheduler or --workers (no cluster runs)")
    if scheduler is not None and workers is not None:
        raise InputError("--workers: sizes the local cluster, not the one of --scheduler")
    if not serial:
        require_extra("distributed", "campaign", "txtool simulate --campaign")
    from txtool.simulation.campaign import Where, main
    from txtool.simulation.campaign_file import read_campaign

    listed = read_campaign(campaign_path).candidates
    if xacro_disabled(no_xacro, options.robot, *listed):
        refuse_unexpanded("simulate", *listed)
    if options.xacro.args:
        warn_unused_args(options.robot, *listed)

    return main(campaign_path, options, Where(serial, scheduler, workers), output_format)


def warn_unused_args(*paths: str) -> None:
    """``--xacro-arg`` is for whichever of the files xacro expands: a warning only when it is
    none of them, naming each."""
    from txtool.io import load

    if not any(load.file_needs_expansion(path) is not False for path in paths):
        for path in dict.fromkeys(paths):
            load.warn_unused_args(path, load.PLAIN)


def refuse_campaign_options(campaign: dict[str, Any]) -> None:
    """--scheduler, --workers and --serial only mean something with --campaign."""
    for key, name in (("scheduler", "--scheduler"), ("workers", "--workers"),
                      ("serial", "--serial")):
        if campaign[key]:
            raise InputError(f"{name}: only with --campaign FILE")


@click.command("simulate")
@click.argument("robot", metavar="ROBOT", type=FILE)
@click.option("--candidate", "configs", cls=RenamedOption, old_names=("--config",),
              multiple=True, metavar="CANDIDATE", type=FILE,
              help="Config whose transmissions the controller uses (repeat to compare several; "
                   "default: ROBOT's own).")
@click.option("--params", "params", multiple=True, type=click.Path(dir_okay=False),
              metavar="FILE.toml|FILE.yaml",
              help="Actuator and gain parameters, or a ROS controllers YAML with PID gains "
                   "(repeat to combine; default: [tool.txtool.simulate] in the nearest "
                   "pyproject.toml above ROBOT).")
@click.option("--controllers", "controllers", multiple=True, type=click.Path(dir_okay=False),
              metavar="FILE",
              help="A controller configuration (YAML; repeatable): the joints its controllers "
                   "command are driven, the others held; the effort controllers' PID gains "
                   "are used. A controller its manager refuses (TX5xx error) fails the run.")
@click.option("--bandwidth", type=float, metavar="RAD/S",
              help="Closed-loop bandwidth w for default gains kp=w^2, kd=2w  [default: 20]")
@click.option("--duration", type=float, metavar="S",
              help="Run length. Default: at least 5 s, stretched (up to 240 s) until the "
                   "default motion is feasible for the robot's limits; given, the motion "
                   "shrinks to fit it instead. A --trajectory CSV: its last time.")
@click.option("--dt", type=float, metavar="S", help="Control and integration step  "
              "[default: 0.001]")
@click.option("--tolerance", type=float, metavar="RAD|M",
              help="Largest tracking error that passes  [default: 0.01]")
@click.option("--trajectory", type=click.Path(dir_okay=False), metavar="FILE.csv",
              help="Reference positions: header time,<joint>,... (default: minimum-jerk moves).")
@click.option("--interpolation", type=Choice(["cubic", "linear"]), default="cubic",
              show_default=True, help="How --trajectory samples are interpolated.")
@click.option("--allow-saturation", is_flag=True,
              help="Do not fail on actuator effort or speed limits (still reported).")
@click.option("--loader", type=Choice(["auto", "ros1", "ros2"]), default="auto",
              show_default=True, help="Which transmissions to use when a file has both kinds.")
@click.option("--ros-distro", type=click.Choice(CHOICES), default=None,
              help="The ROS distribution reading the files: its programs' readers and how they "
                   "read numbers, as validate takes it (over the configuration's ros-distro "
                   "and what package.xml and <gazebo> plugins say).")
@click.option("--effort-convention", "convention", type=Choice(["ros1", "ros2"]),
              default=None,
              help="Controller effort maps: ros_control's (ros1) or ros2_control's (ros2) for "
                   "every config  [default: each file's own loader]")
@click.option("--delay/--no-delay", default=True, show_default=True,
              help="One control period between reading the state and applying the effort "
                   "(read -> update -> write, as in ros2_control).")
@click.option("--encoder-counts", type=click.IntRange(min=1), metavar="N",
              help="Quantise actuator positions to N counts per revolution; velocity by finite "
                   "differences (default: exact readings).")
@click.option("--counterbalance/--no-counterbalance", default=True, show_default=True,
              help="Take a static gravity load beyond a joint's effort limit as carried by a "
                   "counterbalance or spring the URDF does not describe (a note per joint).")
@FORMAT_OPTION
@click.option("--csv", "csv_path", type=click.Path(dir_okay=False), metavar="PATH",
              help="Write the time series (PATH.N.csv per config when several).")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False),
              metavar="PATH.png|.svg|.pdf",
              help="Plot reference and actual positions, errors, actuator efforts and speeds "
                   "against their limits, all configs overlaid (needs the 'plot' extra).")
@click.option("--joints", "plot_joints", multiple=True, metavar="NAMES",
              help="With --plot: draw these joints (comma-separated names or shell patterns "
                   "such as 'arm_*'; repeatable) and their actuators (default: the joints a "
                   "transmission drives).")
@click.option("--skip", "skip", multiple=True, metavar="TRANSMISSION",
              help="Leave this transmission out (its joints are driven directly); repeatable.")
@click.option("--jobs", "-j", type=click.IntRange(min=1), default=1, show_default=True,
              help="Processes for several configs (at most one per config and per idle CPU; "
                   "short runs stay in one).")
@NO_XACRO_OPTION
@xacro_options
@campaign_options
@exit_on_input_error
def command(robot: str, configs: tuple[str, ...], params: tuple[str, ...],
            controllers: tuple[str, ...], bandwidth: float | None,
            duration: float | None, dt: float | None, tolerance: float | None,
            trajectory: str | None, interpolation: str, allow_saturation: bool, loader: str,
            ros_distro: str | None, convention: str | None, delay: bool, encoder_counts: int | None,
            counterbalance: bool, output_format: str, csv_path: str | None,
            plot_path: str | None, plot_joints: tuple[str, ...], skip: tuple[str, ...],
            jobs: int, no_xacro: bool,
            xacro: XacroOptions, **campaign: Any) -> int:
    """Check a transmission config in closed loop against the robot's own.

    The plant uses ROBOT's transmissions; a computed-torque controller encodes its commands and
    decodes its measurements with each CANDIDATE's. Exit 0 when the tracking error stays within
    --tolerance and no limit is exceeded, 1 when not, 3 when nothing of a config could be
    simulated (inconclusive), 2 on bad input. Under --no-xacro a
    .xacro ROBOT or CANDIDATE is refused: the model needs the expanded robot.
    """
    require_extra("pinocchio", "sim", "txtool simulate")
    if plot_joints and plot_path is None:
        raise InputError("--joints: only with --plot (it chooses the joints drawn)")
    joints = tuple(name.strip() for given in plot_joints for name in given.split(",")
                   if name.strip())
    if xacro_disabled(no_xacro, robot, *configs):
        refuse_unexpanded("simulate", robot, *configs)
    from txtool.simulation.app import main
    from txtool.simulation.run import Options

    options = Options(
        robot=robot, configs=configs, params=params or None, bandwidth=bandwidth, duration=duration,
        dt=dt, tolerance=tolerance, trajectory=trajectory, interpolation=interpolation,
        allow_saturation=allow_saturation, loader=loader, convention=convention, xacro=xacro,
        jobs=jobs, skip=skip, delay=delay, encoder_counts=encoder_counts,
        counterbalance=counterbalance, ros_distro=ros_distro, controllers=controllers,
    )
    if campaign["campaign_path"] is not None:
        return run_campaign(options, csv_path=csv_path, plot_path=plot_path,
                            output_format=output_format, no_xacro=no_xacro, **campaign)
    refuse_campaign_options(campaign)
    if xacro.args:
        warn_unused_args(robot, *configs)
    _, code = main(options, output=output_format, csv_path=csv_path, plot_path=plot_path,
                   plot_joints=joints)
    return code
