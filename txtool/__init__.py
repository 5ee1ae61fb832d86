"""txtool: lint, convert and verify robot transmission configurations.

The command line is ``txtool``; this module is the small API for scripts. Importing it is
cheap: each function imports what it needs when called (``simulate`` alone loads Pinocchio).

>>> import txtool
>>> [p.code for p in txtool.validate(["fixtures/broken_robot.urdf"])][:2]  # doctest: +SKIP
['TX106', 'TX102']
>>> [t.name for t in txtool.read("fixtures/demo_robot.urdf")]  # doctest: +SKIP
['shoulder_trans', 'elbow_trans']
>>> txtool.convert("fixtures/demo_robot.urdf", to="ros2-p2").losses  # doctest: +SKIP
[]

Bad input raises :class:`InputError` with the one-line message the CLI prints.
"""

from __future__ import annotations

# First, before anything slow loads: Ctrl-C while the `txtool` command starts is one line and
# exit 130, not a traceback (see txtool.io.signals). Importing txtool as a library changes nothing.
from txtool.io import signals as _signals

if _signals.started_as_command():
    _signals.exit_on_signals()

import os  # noqa: E402
from collections.abc import Iterable, Mapping, Sequence  # noqa: E402
from typing import TYPE_CHECKING, Any, Union

PathLike = Union[str, "os.PathLike[str]"]
DIALECT_CHOICES = ("ros1", "ros2-p1", "ros2-p2")

__version__ = "0.1.0"

if TYPE_CHECKING:
    from txtool.io.xmlio import InputError, Source, XacroOptions
    from txtool.lint.problem import Problem
    from txtool.model.core import Dialect, Transmission
    from txtool.transform.api import Conversion

__all__ = [
    "Conversion",
    "InputError",
    "Problem",
    "Transmission",
    "__version__",
    "convert",
    "read",
    "simulate",
    "validate",
]

_LAZY = {
    "Conversion": "txtool.transform.api",
    "InputError": "txtool.io.xmlio",
    "Problem": "txtool.lint.problem",
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
) -> list[Problem]:
    """Lint files and folders as ``txtool validate`` does; the findings in report order.

    ``select``/``ignore`` take rule codes or prefixes; the configuration file that applies to
    each file is found as on the command line unless ``config`` names one. A file that cannot
    be read raises :class:`InputError` (the CLI's exit 2).
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
    to: Dialect,
    expand: bool = True,
    xacro_args: Mapping[str, str] | None = None,
    pkg_dirs: Sequence[PathLike] = (),
    pkg_paths: Mapping[str, PathLike] | None = None,
    ros_distro: str | None = None,
) -> Conversion:
    """Convert a file or XML text to ``to`` (``"ros1"``, ``"ros2-p1"`` or ``"ros2-p2"``) as
    ``txtool convert`` does, keeping every byte it need not change; nothing is written.
    What is written is checked with validate's rules for the target's loaders (every ROS 2
    distribution, or ``ros_distro``): an error there is in ``losses``.
    Another ``to`` raises ``ValueError`` naming the choices."""
    if to not in DIALECT_CHOICES:
        raise ValueError(f"unknown target dialect {to!r}: choose one of "
                         + ", ".join(map(repr, DIALECT_CHOICES)))
    from txtool.transform.api import converted

    loaded = _source(source, expand, _xacro_options(xacro_args, pkg_dirs, pkg_paths))
    return converted(loaded, to, ros_distro)


def simulate(robot: PathLike, configs: PathLike | Sequence[PathLike] = (),
             **options: Any) -> list[Any]:
    """Run ``txtool simulate ROBOT --config ...`` and return one result per config (the robot's
    own when ``configs`` is empty; one config may be given alone). Each result has ``verdict``
    (``pass``, ``fail`` or ``inconclusive``: nothing of the config could be simulated),
    ``passed``, ``reasons`` and ``coverage`` (what was checked). ``options`` are those of
    :class:`txtool.simulation.run.Options` (``duration``, ``dt``, ``tolerance``, ...). Needs
    the ``sim`` extra (Pinocchio)."""
    from txtool.simulation.run import Options, simulate_one

    given = [configs] if isinstance(configs, str | os.PathLike) else list(configs)
    paths = tuple(os.fspath(c) for c in given)
    settings = Options(robot=os.fspath(robot), configs=paths, keep_series=False, **options)
    return [simulate_one(settings, config) for config in (paths or (None,))]


def _xacro_options(
    args: Mapping[str, str] | None,
    pkg_dirs: Sequence[PathLike],
    pkg_paths: Mapping[str, PathLike] | None,
) -> XacroOptions:
    from txtool.io.xmlio import XacroOptions

    return XacroOptions(
        args=tuple((args or {}).items()),
        pkg_dirs=tuple(os.path.abspath(d) for d in pkg_dirs),
        pkg_paths=tuple((n, os.path.abspath(d)) for n, d in (pkg_paths or {}).items()),
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
