"""txtool: lint, convert and verify robot transmission configurations.

The command line is ``txtool``; this module is the small API for scripts. Importing it is
cheap: each function imports what it needs when called (``simulate`` alone loads Pinocchio).

In a clone of the repository (the tests run these examples from its root):

>>> import txtool
>>> [(p.line, p.code) for p in txtool.validate("fixtures/broken_robot.urdf")][:2]
[(37, 'TX303'), (45, 'TX105')]
>>> [(t.name, t.kind) for t in txtool.read("fixtures/demo_robot.urdf")]
[('shoulder_trans', 'simple'), ('wrist_trans', 'differential')]
>>> done = txtool.convert("fixtures/demo_robot.urdf", to="ros2-p2")
>>> (done.converted, done.losses)
(2, [])
>>> txtool.convert("fixtures/demo_robot.urdf", to="bb").losses  # doctest: +ELLIPSIS
["transmission 'wrist_trans': differential type ... (BB has simple transmissions only)"]

Bad input raises :class:`InputError` with the one-line message the CLI prints; ``simulate``
without the ``sim`` extra raises :class:`MissingExtra` (a ``ModuleNotFoundError``) whose one
line names the extra to install.
"""

from __future__ import annotations

# First, before anything slow loads: Ctrl-C while the `txtool` command starts is one line and
# exit 130, not a traceback (see txtool.io.signals). Importing txtool as a library changes nothing.
from txtool.io import signals as _signals

if _signals.started_as_command():
    _signals.exit_on_signals()

import os  # noqa: E402
from collections.abc import Iterable, Mapping, Sequence  # noqa: E402
from typing import TYPE_CHECKING, Any, Literal, Union

PathLike = Union[str, "os.PathLike[str]"]
DIALECT_CHOICES = ("ros1", "ros2-p1", "ros2-p2")
TARGET_CHOICES = (*DIALECT_CHOICES, "bb")

__version__ = "0.1.0"

if TYPE_CHECKING:
    from txtool.io.resources import MissingExtra
    from txtool.io.xmlio import InputError, Source, XacroOptions
    from txtool.lint.problem import Problem
    from txtool.model.core import Dialect, Transmission
    from txtool.simulation.result import ActuatorStats, Coverage, JointStats, RunResult
    from txtool.transform.api import Conversion

__all__ = [
    "ActuatorStats",
    "Conversion",
    "Coverage",
    "InputError",
    "JointStats",
    "MissingExtra",
    "Problem",
    "RunResult",
    "Transmission",
    "__version__",
    "convert",
    "read",
    "simulate",
    "validate",
]

_LAZY = {
    "ActuatorStats": "txtool.simulation.result",
    "Conversion": "txtool.transform.api",
    "Coverage": "txtool.simulation.result",
    "InputError": "txtool.io.xmlio",
    "JointStats": "txtool.simulation.result",
    "MissingExtra": "txtool.io.resources",
    "Problem": "txtool.lint.problem",
    "RunResult": "txtool.simulation.result",
    "Transmission": "txtool.model.core",
}


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'txtool' has no attribute {name!r}")
    import importlib

    return getattr(importlib.import_module(module), name)


def validate(
    paths: PathLike | Iterable[PathLike],
    *,
    select: Sequence[str] | None = None,
    ignore: Sequence[str] = (),
    config: PathLike | None = None,
    no_xacro: bool = False,
    xacro_args: Mapping[str, str] | None = None,
    pkg_dirs: Sequence[PathLike] = (),
    pkg_paths: Mapping[str, PathLike] | None = None,
    jobs: int = 1,
    controllers: Sequence[PathLike] = (),
) -> list[Problem]:
    """Lint files and folders as ``txtool validate`` does; the findings in report order.

    ``select``/``ignore`` take rule codes or prefixes; the configuration file that applies to
    each file is found as on the command line unless ``config`` names one. ``controllers``
    are controller configurations (YAML) checked against the robot files (``--controllers``).
    A file that cannot be read raises :class:`InputError` (the CLI's exit 2).
    """
    from txtool.lint.api import LintOptions, lint_paths

    if isinstance(paths, str | os.PathLike):
        given = [os.fspath(paths)]
    else:
        given = [os.fspath(p) for p in paths]
    options = LintOptions(
        select=tuple(select) if select is not None else None,
        ignore=tuple(ignore),
        config=os.fspath(config) if config is not None else None,
        xacro=_xacro_options(xacro_args, pkg_dirs, pkg_paths),
        no_xacro=no_xacro,
        jobs=jobs,
        controllers=tuple(os.fspath(c) for c in controllers),
    )
    result = lint_paths(given or ["."], options)
    if result.errors:
        from txtool.io.xmlio import InputError

        raise InputError(result.errors[0].message)
    return result.problems


def read(
    path_or_text: PathLike,
    *,
    expand: bool = True,
    xacro_args: Mapping[str, str] | None = None,
    pkg_dirs: Sequence[PathLike] = (),
    pkg_paths: Mapping[str, PathLike] | None = None,
) -> list[Transmission]:
    """The transmissions of a file (xacro expanded unless ``expand`` is False) or of XML text
    (a string starting with ``<``), in document order, in txtool's canonical model."""
    from txtool.dialects.read import read_source

    source = _source(path_or_text, expand, _xacro_options(xacro_args, pkg_dirs, pkg_paths))
    return [found.transmission for found in read_source(source)]


def convert(
    source: PathLike,
    *,
    to: Dialect | Literal["bb"],
    expand: bool = True,
    xacro_args: Mapping[str, str] | None = None,
    pkg_dirs: Sequence[PathLike] = (),
    pkg_paths: Mapping[str, PathLike] | None = None,
    bb_direction: Literal["reversed", "negative-reduction"] = "reversed",
    bb_topology: bool = False,
    ros_distro: str | None = None,
) -> Conversion:
    """Convert a file or XML text to ``to`` (``"ros1"``, ``"ros2-p1"`` or ``"ros2-p2"``) as
    ``txtool convert`` does, keeping every byte it need not change; nothing is written.
    What is written is checked with validate's rules for the target's loaders (every ROS 2
    distribution, or ``ros_distro``): an error there is in ``losses``.
    ``"bb"`` gives the Beam Bots DSL blocks of ``--to bb`` as ``text`` (``bb_direction`` and
    ``bb_topology`` are ``--bb-direction`` and ``--bb-topology``). Another ``to`` raises
    ``ValueError`` naming the choices."""
    if to not in TARGET_CHOICES:
        raise ValueError(f"unknown target dialect {to!r}: choose one of "
                         + ", ".join(map(repr, TARGET_CHOICES)))
    from txtool.transform.api import Conversion, converted

    loaded = _source(source, expand, _xacro_options(xacro_args, pkg_dirs, pkg_paths))
    if to == "bb":
        from txtool.transform.bb.export import export_bb

        exported = export_bb(loaded, direction=bb_direction, topology=bb_topology)
        # One "# transmission 'NAME'" comment heads each exported actuator.
        carried = sum(1 for line in exported.text.splitlines()
                      if line.lstrip().startswith("# transmission '"))
        return Conversion(text=exported.text, data=exported.text.encode("utf-8"),
                          losses=list(exported.losses), notes=list(exported.notes),
                          converted=carried)
    return converted(loaded, to, ros_distro)


def simulate(
    robot: PathLike,
    configs: PathLike | Sequence[PathLike] = (),
    *,
    params: PathLike | Sequence[PathLike] = (),
    controllers: PathLike | Sequence[PathLike] = (),
    duration: float | None = None,
    dt: float | None = None,
    tolerance: float | None = None,
    bandwidth: float | None = None,
    trajectory: PathLike | None = None,
    interpolation: Literal["cubic", "linear"] = "cubic",
    allow_saturation: bool = False,
    loader: Literal["auto", "ros1", "ros2"] = "auto",
    effort_convention: Literal["ros1", "ros2"] | None = None,
    ros_distro: str | None = None,
    delay: bool = True,
    encoder_counts: int | None = None,
    counterbalance: bool = True,
    skip: Sequence[str] = (),
    jobs: int = 1,
    keep_series: bool = False,
    xacro_args: Mapping[str, str] | None = None,
    pkg_dirs: Sequence[PathLike] = (),
    pkg_paths: Mapping[str, PathLike] | None = None,
) -> list[RunResult]:
    """Run ``txtool simulate ROBOT --candidate ...`` and return one :class:`RunResult` per
    config (the robot's own when ``configs`` is empty; one config may be given alone).

    Each result has ``verdict`` (``pass``, ``fail`` or ``inconclusive``: nothing of the config
    could be simulated), ``passed``, ``reasons``, ``notes``, ``coverage`` (a
    :class:`Coverage`), ``joints`` (:class:`JointStats` by joint), ``actuators``
    (:class:`ActuatorStats`) and ``controllers`` (with ``controllers``: the controller
    commanding each joint, None for a joint held); ``series`` holds the time series when
    ``keep_series``. The keywords are the command's options (``effort_convention`` is
    ``--effort-convention``); None takes the value of the parameter files, else the default.
    Needs the ``sim`` extra (Pinocchio): without it :class:`MissingExtra` names the extra to
    install."""
    _require("pinocchio", "sim", "txtool.simulate")
    from txtool.simulation.jobs import execute
    from txtool.simulation.run import Options

    options = Options(
        robot=os.fspath(robot), configs=_paths(configs), params=_paths(params) or None,
        duration=duration, dt=dt, tolerance=tolerance, bandwidth=bandwidth,
        trajectory=os.fspath(trajectory) if trajectory is not None else None,
        interpolation=interpolation, allow_saturation=allow_saturation, loader=loader,
        convention=effort_convention, ros_distro=ros_distro, delay=delay,
        encoder_counts=encoder_counts, counterbalance=counterbalance, skip=tuple(skip),
        jobs=jobs, keep_series=keep_series, controllers=_paths(controllers),
        xacro=_xacro_options(xacro_args, pkg_dirs, pkg_paths),
    )
    return execute(options)


def _paths(given: PathLike | Sequence[PathLike]) -> tuple[str, ...]:
    if isinstance(given, str | os.PathLike):
        return (os.fspath(given),)
    return tuple(os.fspath(p) for p in given)


def _require(module: str, extra: str, what: str) -> None:
    import importlib.util

    try:
        found = importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):  # a parent package missing, or a module set to None
        found = False
    if not found:
        from txtool.io.resources import MissingExtra, install_extra

        raise MissingExtra(f"{what} needs the '{extra}' extra: {install_extra(extra)}",
                           name=module)


def _xacro_options(
    args: Mapping[str, str] | None,
    pkg_dirs: Sequence[PathLike],
    pkg_paths: Mapping[str, PathLike] | None,
) -> XacroOptions:
    from txtool.io.xmlio import XacroOptions

    dirs = tuple(os.path.abspath(d) for d in pkg_dirs)
    paths = tuple((n, os.path.abspath(d)) for n, d in (pkg_paths or {}).items())
    return XacroOptions(  # the caller's folders, as the command line's: readable
        args=tuple((args or {}).items()), pkg_dirs=dirs, pkg_paths=paths,
        readable=dirs + tuple(folder for _, folder in paths),
    )


def _source(path_or_text: PathLike, expand: bool, xacro: XacroOptions) -> Source:
    if isinstance(path_or_text, os.PathLike):
        path_or_text = os.fspath(path_or_text)
    elif path_or_text.lstrip().startswith("<"):
        from txtool.io.xmlio import Source, parse_bytes

        data = path_or_text.encode("utf-8")
        return Source(path="<string>", data=data, tree=parse_bytes(data, "<string>"))
    from txtool.io.load import load

    return load(path_or_text, xacro=xacro, expand=expand)
