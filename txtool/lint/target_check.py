"""What a conversion or a fix writes, judged by the programs that will read it.

convert, migrate (its fixes and ``--to``), ``validate --fix`` and the language server's fixes
hand what they wrote to :func:`judge`, which runs every rule of ``validate`` on it with the
readers forced to the target's (:func:`runs_for`):

* ``ros2-p2``: ros2_control of every ROS 2 distribution txtool models (Humble reads numbers
  as its C++17 build does and accepts a mimic joint's command interface; Jazzy and later do
  not), or only the one ``--ros-distro`` names: one lint for all of them, and one per
  distribution where that lint has a warning (a verdict some of them only refuse);
* ``ros2-p1``: the same, since ros2_control is the only ROS 2 program that reads
  transmissions; it never adopted Proposal 1 and throws "no attribute 'role' in 'joint' tag"
  on its ``<role>`` elements (TX303). That finding is the form the user asked for: it is
  said once as a warning, not as a loss, and everything else is held to ros2_control;
* ``ros1``: ros_control (Noetic); and, where the written document still has ``<ros2_control>``
  blocks, ros2_control as for ``ros2-p2``, which still reads them (a transmission left in one
  in ROS 1 form makes it throw "Missing <plugin> tag");
* no target (fixes only): the readers ``validate`` assumes for the file.

A finding of severity ``error`` for one of these readers (the reader refuses the document or
silently reads something else) is a loss, unless the input had it already for the same
reader (a conversion then says it as a warning, unless the finding is one for which the
reader refuses the whole document, ``Problem.refuses_whole``: the written file would not load,
so it stays a loss that says the input had it): findings are compared by rule code and
message (which names the element: the transmission, joint or actuator and what is wrong with
it) as a multiset, so a problem the conversion carried over unchanged is not blamed on it, and
one it made (a mimic joint given a command interface, a transmission put on a fixed joint) is.
A fix is not blamed either for an error on a transmission the input already had an error or a
warning for (see :func:`_flagged`). The input is linted only when the output has an error, and
for a conversion only with the rules that found one (and those they defer to:
``Rule.defers_to``): the other rules' findings would be compared with nothing.

A robot that a conversion to ROS 2 leaves without any ``<ros2_control>`` is refused whole
(:func:`_whole`: no rule says so, since a ROS 1 robot is not refused for it).

A xacro file migrated as written is judged on the expansion of the written source, as
``validate`` expands it (its includes and ``$(find)`` found from where the file is); where
the expansion fails, on the source as written, as ``validate`` does. A written file that
other files of the run include is judged in their expansions too (:func:`judge_includers`).
"""

from __future__ import annotations

import dataclasses
import os
import re
from collections import Counter
from collections.abc import Callable, Sequence
from typing import NamedTuple

from lxml import etree

from txtool.io.encodings import text_lines
from txtool.io.load import needs_expansion
from txtool.io.xmlio import InputError, Source, XacroOptions, local, parse_bytes
from txtool.lint.config import Settings, resolve
from txtool.lint.engine import lint_source
from txtool.lint.problem import Problem
from txtool.model.core import Dialect
from txtool.model.distro import ROS2, Distro
from txtool.model.readers import ROS2_CONTROL, ROS_CONTROL, Stated

__all__ = ["Judged", "Run", "Written", "judge", "judge_converted", "judge_includers", "prepared",
           "runs_for", "target_distro"]

# The finding ros2_control gives every <role> element of Proposal 1 (see the module doc).
_P1_FORM = "TX303"


class Run(NamedTuple):
    """One lint of the written document: the reader and its distributions, as messages name
    them, and what the lint is told."""

    reader: str
    distros: tuple[str, ...]
    stated: Stated

    def split(self) -> list[Run]:
        """One run per distribution (see :func:`judge`)."""
        reader = self.stated.readers[0]
        return [Run(self.reader, (name,), Stated((reader,), Distro(name), origin="target"))
                for name in self.distros]


@dataclasses.dataclass
class Judged:
    """What the check found: ``losses`` (the command exits 1 on them unless losses are
    allowed) and ``warnings`` (said, nothing lost)."""

    losses: list[str] = dataclasses.field(default_factory=list)
    warnings: list[str] = dataclasses.field(default_factory=list)


def target_distro(target: Dialect | None, distro: str | None) -> Distro | None:
    """``--ros-distro`` for a conversion to ``target``: ``ValueError`` when it names the other
    ROS generation (ros_control reads ROS 1, ros2_control ROS 2)."""
    if distro is None:
        return None
    from txtool.model.distro import parse_distro

    parsed = parse_distro(distro)
    if target is not None and (target == "ros1") == parsed.ros2:
        reader = "ros_control (noetic)" if target == "ros1" else "ros2_control"
        raise ValueError(f"--ros-distro {parsed.value} does not read --to {target}: "
                         f"{reader} does")
    return parsed


def runs_for(target: Dialect | None, distro: Distro | None, written: Source,
             own: Stated | None = None) -> list[Run]:
    """The readers ``written`` (a document in ``target``) is checked for (see the module
    documentation); ``own``: what the user said of the file's readers, for fixes alone."""
    if target is None:
        stated = own or Stated()
        if distro is not None:
            stated = dataclasses.replace(stated, distro=distro,
                                         distro_said=f"--ros-distro {distro.value}")
        return [Run("the readers validate assumes for it", (), stated)]
    runs = []
    if target == "ros1":
        runs.append(Run(ROS_CONTROL.key, (Distro.NOETIC.value,),
                        Stated((ROS_CONTROL,), origin="target")))
        if not _has_components(written):
            return runs
    if distro is not None and distro.ros2:
        runs.append(Run(ROS2_CONTROL.key, (distro.value,),
                        Stated((ROS2_CONTROL,), distro, origin="target")))
    else:  # every distribution at once (split where their verdicts differ: see judge)
        runs.append(Run(ROS2_CONTROL.key, tuple(d.value for d in ROS2),
                        Stated((ROS2_CONTROL,), origin="target")))
    return runs


def _has_components(source: Source) -> bool:
    root = source.root
    return next(root.iter("{*}ros2_control", "ros2_control"), None) is not None


def judge_converted(data: bytes, source: Source, target: Dialect, *,
                    distro: Distro | None = None,
                    reload: Callable[[], Source | None] | None = None) -> Judged:
    """:func:`judge` for ``convert``: ``data`` is what the conversion of ``source`` wrote (of a
    xacro input, its expansion converted); ``reload`` reads a xacro input again when its
    expansion is needed to compare with (the conversion consumed it)."""
    # The expansion of a xacro input is judged as the plain document it is (its lines, not
    # traced back to the source), and the input's expansion likewise.
    name = f"{source.path}.expanded" if source.expanded else source.path
    if data == source.data:  # nothing converted: only what the document misses as a whole
        return Judged(losses=_whole(prepared(source.path, name, data, expand=False), target))

    def before() -> Source | None:
        if not source.expanded:
            return prepared(source.path, name, source.data, expand=False)
        again = reload() if reload is not None else None
        if again is None:
            return None
        text = etree.tostring(again.tree, encoding="utf-8", xml_declaration=True)
        return Source(name, text, again.tree)

    # Given to judge alone, which lets the tree go before it reads the input.
    return judge(prepared(source.path, name, data, expand=False), before, target, distro=distro)


def prepared(path: str, display: str, data: bytes, settings: Settings | None = None,
             expand: bool = True) -> Source:
    """``data``, the text written for the file at ``path``, read as ``validate`` reads it: a
    xacro document expanded (unless ``expand`` is False or ``settings`` turn xacro off),
    else, or where the expansion fails, as written."""
    tree = parse_bytes(data, display, limit=None)
    source = Source(display, data, tree)
    xacro_off = settings is not None and settings.no_xacro
    if not expand or xacro_off or path == "-" or not needs_expansion(display, data, tree):
        return source
    from txtool.io.xacro import XacroError, expand_xacro
    from txtool.io.xmlio import XacroOptions

    options = settings.xacro if settings is not None else XacroOptions()
    try:
        expanded = expand_xacro(path, display, options, data=data)
    except XacroError:
        return source
    return Source(display, data, expanded, expanded=True, source_tree=tree)


def judge(written: Source, before: Callable[[], Source | None], target: Dialect | None, *,
          distro: Distro | None = None, own: Stated | None = None,
          settings: Settings | None = None) -> Judged:
    """The errors of ``written`` for its target's readers that ``before()`` (the input, read
    the same way; None: nothing to compare with) does not have for the same reader.

    ``settings`` give the rules' options and the file's suppressions are honoured; every rule
    runs at its registered severity, whatever a configuration selects.
    """
    base = _base(settings)
    judged = Judged(losses=_whole(written, target))
    runs = runs_for(target, distro, written, own)
    found = []
    for run in runs:
        # Read by every distribution at once, a verdict is an error where all of them refuse
        # and a warning where some do (txtool.model.distro): only a warning asks which.
        problems = _findings(written, base, run)
        if len(run.distros) > 1 and any(p.severity == "warning" for p in problems):
            found += [(each, _errors(written, base, each)) for each in run.split()]
        else:
            found.append((run, [p for p in problems if p.severity == "error"]))
    if not any(errors for _, errors in found):
        return judged
    text = written.data  # all that is read of it now: its tree goes before the input is read
    del written
    earlier: Source | None = None
    asked = False
    blamed: dict[tuple[int, int, str, str], list[Run]] = {}
    kept: dict[tuple[int, int, str, str], list[Run]] = {}  # the input's own, carried over
    still: dict[tuple[int, int, str, str], list[Run]] = {}  # ... for which it is refused whole
    form: list[Problem] = []
    for run, errors in found:
        if not errors:
            continue
        if not asked:
            earlier, asked = before(), True
        only = _compared(errors) if target is not None else None
        before_found = _findings(earlier, base, run, only) if earlier is not None else []
        had = Counter((p.code, p.message) for p in before_found if p.severity == "error")
        flagged = _flagged(before_found) if target is None else frozenset()
        for problem in errors:
            key = (problem.code, problem.message)
            where = (problem.line, problem.column, problem.code, problem.message)
            if had[key] > 0:
                had[key] -= 1
                if target is not None:
                    (still if problem.refuses_whole else kept).setdefault(where, []).append(run)
                continue
            if _transmission(problem) in flagged:
                continue
            if target == "ros2-p1" and _p1_form(problem, text):
                form.append(problem)
                continue
            blamed.setdefault(where, []).append(run)
    judged.losses.extend(_loss(*where, runs) for where, runs in sorted(blamed.items()))
    # The written file will not load, whoever is to blame: no hardware of the robot runs
    judged.losses.extend(f"{_loss(*where, runs)} (the input has it already: the target "
                         "refuses the written file whole all the same)"
                         for where, runs in sorted(still.items()))
    # The target refuses what was written all the same: said, not blamed on the conversion
    judged.warnings.extend(f"{_loss(*where, runs)} (the input has it already)"
                           for where, runs in sorted(kept.items()))
    if form:
        judged.warnings.append(_p1_warning(form[0]))
    return judged


def _whole(written: Source, target: Dialect | None) -> list[str]:
    """ros2_control's refusal of a robot without ``<ros2_control>`` (no rule says it: where
    nothing decides its readers, a ROS 1 robot is not refused for it): a conversion to ROS 2
    that leaves every transmission outside such a block writes a robot it refuses whole."""
    if target not in ("ros2-p1", "ros2-p2") or _has_components(written):
        return []
    root = written.root
    if not isinstance(root.tag, str) or local(root) != "robot":
        return []
    if next(root.iter("{*}transmission", "transmission"), None) is None:
        return []
    return ["ros2_control refuses this robot whole: it throws \"no "
            "'ros2_control' tag found in the URDF\" (component_parser.cpp "
            "parse_control_resources_from_urdf): no transmission of it stands in a "
            "<ros2_control> block"]


def _base(settings: Settings | None) -> Settings:
    defaults = _defaults()
    if settings is None:
        return defaults
    return dataclasses.replace(defaults, options=settings.options, xacro=settings.xacro,
                               no_xacro=settings.no_xacro)


_DEFAULTS: list[Settings] = []


def _defaults() -> Settings:
    if not _DEFAULTS:
        _DEFAULTS.append(resolve())
    return _DEFAULTS[0]


def _findings(source: Source, base: Settings, run: Run,
              only: frozenset[str] | None = None) -> list[Problem]:
    """What every rule finds in ``source`` for the run's readers; ``only``: these rules alone."""
    settings = dataclasses.replace(base, stated=run.stated)
    if only is not None:
        settings = dataclasses.replace(settings, enabled=settings.enabled & only)
    return lint_source(source, settings)


def _compared(errors: list[Problem]) -> frozenset[str]:
    """The rules that found ``errors`` (the input's findings of no other rule are compared
    with them), and those they defer to (which decide what they report)."""
    from txtool.rules import all_rules

    rules = all_rules()
    codes = {p.code for p in errors}
    return frozenset(codes.union(*(rules[code].defers_to for code in codes if code in rules)))


def _errors(source: Source, base: Settings, run: Run) -> list[Problem]:
    return [p for p in _findings(source, base, run) if p.severity == "error"]


_NAMED = re.compile(r"transmission '([^']*)'")


def _transmission(problem: Problem) -> str | None:
    """The transmission a finding is about, as its message names it."""
    found = _NAMED.search(problem.message)
    return found.group(1) if found else None


def _flagged(found: list[Problem]) -> frozenset[str | None]:
    """The transmissions with an error or a warning: a fix rewrites a transmission in its own
    dialect, so an error it brings to light on one of them (a legacy type attribute made an
    element: the loader now reads a transmission it skipped) was that transmission's."""
    return frozenset(_transmission(p) for p in found
                     if p.severity in ("error", "warning") and _transmission(p) is not None)


def _p1_form(problem: Problem, data: bytes) -> bool:
    """Whether ``problem`` is ros2_control's refusal of a Proposal 1 ``<role>`` element: TX303
    placed on a ``<role>`` start tag of ``data``, the text checked."""
    if problem.code != _P1_FORM:
        return False
    lines = text_lines(data)
    if not 1 <= problem.line <= len(lines):
        return False
    first, last = lines.span(problem.line - 1)
    start = first + problem.column - 1
    text = lines.text[start:min(start + 6, last)]
    return text.startswith("<role") and text[5:6] in (">", "/", " ", "\t", "")


def _loss(line: int, _column: int, code: str, message: str, runs: Sequence[Run]) -> str:
    from txtool.rules import all_rules

    name = all_rules()[code].name
    return f"line {line}: {code} {name} for {_readers(runs)}: {message}"


def _readers(runs: Sequence[Run]) -> str:
    """``ros2_control (jazzy, kilted, rolling)`` from one run per distribution."""
    names: dict[str, list[str]] = {}
    for run in runs:
        names.setdefault(run.reader, []).extend(run.distros)
    return "; ".join(f"{reader} ({', '.join(d for d in distros if d)})" if any(distros)
                     else reader for reader, distros in names.items())


def _p1_warning(problem: Problem) -> str:
    return (f"ros2-p1 is not what ros2_control reads: it throws \"no attribute 'role' in "
            f"'joint' tag\" on its <role> elements ({_P1_FORM}, first at line {problem.line}); "
            "the rest is checked as ros2_control reads it (--to ros2-p2 writes that)")


# -- the robots that include what migrate writes ------------------------------------------------


class Written(NamedTuple):
    """A file migrate would write: where it is, its bytes before and after."""

    path: str
    original: bytes
    data: bytes


def judge_includers(written: Sequence[Written], candidates: Sequence[str],
                    target: Dialect | None, settings_of: Callable[[str], Settings], *,
                    distro: Distro | None = None) -> dict[str, list[str]]:
    """The losses of each file of ``written`` as the robots that include it read it.

    A xacro fragment (``arm.transmission.xacro``) is no robot: its errors show only in the
    expansion of the file that includes it. Each of ``candidates`` (the other files of the
    run) that includes a written file is expanded twice, as it is and in a copy of its
    package (and of the written files' packages) holding what would be written, and
    :func:`judge` compares the two. The losses go to every written file that robot includes,
    each prefixed with the robot's path.
    """
    from txtool.io.xmlio import is_xacro
    from txtool.lint.fragments import fragments

    by_key = {os.path.realpath(w.path): w for w in written}
    found: dict[str, list[str]] = {}
    for robot in candidates:
        if not is_xacro(robot):
            continue
        settings = settings_of(robot)
        if settings.no_xacro:
            continue
        included = [by_key[os.path.realpath(p)] for p in fragments(
            [(robot, settings.xacro)], [w.path for w in written])]
        if not included:
            continue
        losses = _as_included(robot, [*included, *_itself(robot, by_key)], target, settings,
                              distro)
        for each in included:
            found.setdefault(each.path, []).extend(
                f"as {robot} includes it (lines of its expansion): {loss}" for loss in losses)
    return found


def _itself(robot: str, by_key: dict[str, Written]) -> list[Written]:
    own = by_key.get(os.path.realpath(robot))
    return [own] if own is not None else []


def _as_included(robot: str, written: Sequence[Written], target: Dialect | None,
                 settings: Settings, distro: Distro | None) -> list[str]:
    """:func:`judge` of ``robot``'s expansion with ``written`` in place of those files."""
    import shutil
    import tempfile

    from txtool.io.package_xml import package_of
    from txtool.io.xacro import XacroError, expand_xacro

    before = expand_or_none(robot, settings.xacro)
    if before is None:
        return []
    with tempfile.TemporaryDirectory(prefix="txtool-check-") as scratch:
        copies: dict[str, str] = {}  # package folder -> its copy
        names: list[tuple[str, str]] = []
        for path in (robot, *(w.path for w in written)):
            info = package_of(path)
            folder = os.path.dirname(info.manifest) if info is not None else os.path.dirname(
                os.path.abspath(path))
            if folder not in copies:
                copies[folder] = os.path.join(scratch, str(len(copies)))
                shutil.copytree(folder, copies[folder], ignore=_not_read_by_xacro,
                                symlinks=True)
                if info is not None:
                    names.append((info.name, copies[folder]))
        for w in written:
            _put(w, copies)
        moved = _moved(robot, copies)
        # The copies first; the other packages found where the originals are
        options = settings.xacro._replace(
            pkg_paths=(*names, *settings.xacro.pkg_paths),
            pkg_dirs=(*settings.xacro.pkg_dirs, *_around(robot, copies)))
        try:
            tree = expand_xacro(moved, robot, options)
        except XacroError as exc:
            if exc.missing:  # what the copy lacks, not what is written
                return []
            return [f"xacro cannot expand it with what would be written: {exc.reason}"]
    data = etree.tostring(tree, encoding="utf-8", xml_declaration=True)
    after = Source(f"{robot}.expanded", data, tree)
    earlier = Source(f"{robot}.expanded",
                     etree.tostring(before, encoding="utf-8", xml_declaration=True), before)
    return judge(after, lambda: earlier, target, distro=distro, settings=settings,
                 own=settings.stated).losses


def expand_or_none(path: str, options: XacroOptions) -> etree._ElementTree | None:
    from txtool.io.xacro import XacroError, expand_xacro

    try:
        return expand_xacro(path, path, options)
    except (XacroError, InputError):
        return None


def _not_read_by_xacro(folder: str, names: list[str]) -> list[str]:
    """Meshes, images and the like: large, and never read by xacro."""
    kept = (".xacro", ".urdf", ".xml", ".yaml", ".yml", ".gazebo", ".trans", ".sdf", ".launch")
    return [name for name in names if not os.path.isdir(os.path.join(folder, name))
            and not name.endswith(kept)]


def _around(robot: str, copies: dict[str, str]) -> list[str]:
    """Where the packages beside the copied ones are: the workspace of ``robot``, or the
    folder holding each copied package."""
    from txtool.io.packages import workspace_roots

    return list(dict.fromkeys(workspace_roots(robot) or [
        os.path.dirname(folder) for folder in copies if len(folder.split(os.sep)) > 2]))


def _moved(path: str, copies: dict[str, str]) -> str:
    real = os.path.abspath(path)
    for folder, copy in copies.items():
        if real.startswith(folder + os.sep):
            return copy + real[len(folder):]
    return path


def _put(w: Written, copies: dict[str, str]) -> None:
    target = _moved(w.path, copies)
    with open(target, "wb") as handle:
        handle.write(w.data)
