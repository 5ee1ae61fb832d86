"""Migrate files in place: apply the fixable rules and, optionally, a dialect conversion.

Files are read as written, never expanded: in a xacro file the literal transmission XML is
rewritten and ``${...}`` expressions, macros and comments stay as they are. The migration is
said as edits of the original bytes (:mod:`.edits.core`: the fixes, the conversion and the fixes
after it each say their change as edits, composed into one set), so every byte outside an
edit keeps its value (quoting, spacing, line endings) and a diff shows the migration and
nothing else. A file that does not change is
never written. The result of a migration is a fixed point: migrating it again changes nothing.

:func:`migrate_paths` returns a :class:`Report` (diff text, messages and exit code); it writes
files only in ``write`` mode. Nothing here prints.
"""

from __future__ import annotations

import dataclasses
import os
from collections import Counter
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Literal

from lxml import etree

from txtool.dialects.read import transmission_elements
from txtool.io.encodings import document_text
from txtool.io.printable import printable
from txtool.io.xmlio import (
    InputError,
    Source,
    XacroOptions,
    is_xacro,
    parse_bytes,
    read_bytes,
    replace_if_unchanged,
)
from txtool.lint.config import Overrides, Settings, SettingsCache
from txtool.lint.discover import expand_paths
from txtool.lint.fixes import fix_tree, fixes_read, might_fix
from txtool.model.core import Dialect
from txtool.rules import Rule, all_rules
from txtool.transform.convert import DEFAULT_HARDWARE_PLUGIN, ConvertedDocument, convert_source
from txtool.transform.edits.core import Edit, EditedText, compose
from txtool.transform.edits.document import DocumentEdits, read_back
from txtool.transform.edits.tree_edits import serialization
from txtool.transform.linediff import unified_text
from txtool.transform.next_steps import package_build_types, package_gazebo_plugins
from txtool.transform.placement.macros import MacroCalls, calls_in_files
from txtool.transform.reversible import MARK

Mode = Literal["check", "diff", "write"]


@dataclass(frozen=True)
class MigrateOptions:
    """What ``txtool migrate`` takes besides the paths."""

    mode: Mode = "check"
    target: Dialect | None = None
    select: tuple[str, ...] | None = None
    ignore: tuple[str, ...] = ()
    config: str | None = None
    allow_lossy: bool = False
    hardware_plugin: str = DEFAULT_HARDWARE_PLUGIN
    plugin_chosen: bool = False  # named by the user: not a placeholder to point out
    # Where the files migrated call each xacro macro (set by migrate_paths, to ROS 2).
    macro_calls: MacroCalls | None = None
    reversible: bool = False
    # --ros-distro: the readers whose findings are fixed, and for whom what is written is
    # checked (lint.target_check); xacro as validate runs it, for that check.
    ros_distro: str | None = None
    xacro: XacroOptions = XacroOptions()
    no_xacro: bool = False
    # Processes that migrate the files, as validate's --jobs (0: one per usable CPU when
    # there are enough files); what is written is written by this one, in order.
    jobs: int = 1


@dataclass
class FileResult:
    """One file: its bytes before and after, and what was done to it."""

    path: str
    original: bytes
    data: bytes
    fixes: Counter[str] = field(default_factory=Counter)  # by code
    converted: int = 0
    target: Dialect | None = None
    losses: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    refused: bool = False
    unwritten: bool = False  # the write failed
    # The edits of the original (its UTF-8 form if UTF-16/32) that made ``data``, where
    # fixes changed it and were written as edits.
    edits: list[Edit] | None = None

    @property
    def changed(self) -> bool:
        return not (self.refused or self.unwritten) and self.data != self.original

    def describe(self) -> str:
        """What changed, e.g. ``TX300 x2, 3 transmission(s) to ros2-p2``."""
        parts = [f"{code} x{count}" for code, count in sorted(self.fixes.items()) if count]
        if self.converted:
            parts.append(f"{self.converted} transmission(s) to {self.target}")
        return ", ".join(parts)


@dataclass
class Report:
    """The outcome of a run: per-file results, unreadable files, text for the two streams."""

    mode: Mode
    files: list[FileResult] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)
    # Each changed file's diff.
    diffs: list[str] = field(default_factory=list)
    messages: list[str] = field(default_factory=list)

    @property
    def changed(self) -> list[FileResult]:
        return [f for f in self.files if f.changed]

    @property
    def refused(self) -> list[FileResult]:
        return [f for f in self.files if f.refused]

    @property
    def exit_code(self) -> int:
        """2 an input or write error; 1 refused losses or (check/diff) changes pending; 0."""
        if self.errors:
            return 2
        if self.refused or (self.mode != "write" and self.changed):
            return 1
        return 0

    def summary(self) -> str:
        parts = []
        if self.changed:
            verb = "changed" if self.mode == "write" else "would be changed"
            parts.append(f"{len(self.changed)} file(s) {verb}")
        if self.refused:
            parts.append(f"{len(self.refused)} file(s) refused (losses; see --allow-lossy)")
        if self.errors:
            parts.append(f"{len(self.errors)} file(s) could not be read or written")
        if not parts:
            return f"nothing to do ({len(self.files)} file(s) checked)"
        return ", ".join(parts)


def migrate_paths(paths: Iterable[str], options: MigrateOptions) -> Report:
    """Migrate files and folders (searched like ``validate`` does); writes in ``write`` mode.

    Every file's configuration is resolved before any file is touched, so a bad configuration
    (:class:`~txtool.lint.config.ConfigError`, exit 2) stops the run with nothing written.
    """
    report = Report(mode=options.mode)
    plan = _plan(paths, options, report)
    if options.target is not None and options.target != "ros1":
        options = dataclasses.replace(options, macro_calls=calls_in_files(_bytes_of(plan)))
    # Each file's result, or why it could not be read, in order: told (and written) as it
    # comes until a changed xacro file, which waits for the robots of the run that include
    # it (_judge_includers), and the files after it with it.
    waiting: list[FileResult | str] = []
    held: list[FileResult] = []
    for last in _migrated_files(plan, options):
        waiting.append(last)
        if isinstance(last, FileResult) and last.changed and is_xacro(last.path):
            held.append(last)
        if not held:
            _tell(report, waiting, options)
    _judge_includers(held, plan, options)
    _tell(report, waiting, options)
    if options.target is not None and options.target != "ros1":
        converted = [f.path for f in report.files if f.converted and f.changed]
        steps = package_gazebo_plugins(converted) + package_build_types(converted)
        report.messages.extend(f"warning: {step}" for step in steps)
    report.messages.append(report.summary())
    return report


def _migrated_files(plan: list[tuple[str, list[Rule], Settings]], options: MigrateOptions
                    ) -> Iterator[FileResult | str]:
    """Each planned file's result, or why it could not be read, in order: from this process
    and, for many files, forks of it (:mod:`txtool.lint.workers`; nothing is written there)."""
    from txtool.lint.api import worker_count

    def one(index: int) -> FileResult | str:
        path, rules, settings = plan[index]
        try:
            return migrate_file(path, rules, options, settings)
        except InputError as exc:
            return str(exc)

    workers = worker_count(len(plan), options.jobs)
    if workers == 1:
        yield from map(one, range(len(plan)))
        return
    from txtool.lint.workers import forked_map

    yield from forked_map(one, len(plan), workers)


def _bytes_of(plan: list[tuple[str, list[Rule], Settings]]) -> Iterator[tuple[str, bytes]]:
    """The bytes of each planned file that can be read (the others are reported when
    migrated)."""
    for path, _, _ in plan:
        try:
            display, data = read_bytes(path)
        except InputError:
            continue
        yield display, data


def _tell(report: Report, waiting: list[FileResult | str], options: MigrateOptions) -> None:
    for each in waiting:
        if isinstance(each, str):
            _error(report, each)
            continue
        report.files.append(each)
        _record(report, each, options)
        if not each.changed:  # nothing of it is written: its bytes are not needed
            each.original = each.data = b""
    waiting.clear()


def _judge_includers(written: list[FileResult], plan: list[tuple[str, list[Rule], Settings]],
                     options: MigrateOptions) -> None:
    """Refuse a written xacro file that a robot of the run includes, where that robot's
    expansion with what would be written has an error it did not have
    (:func:`txtool.lint.target_check.judge_includers`)."""
    if not written:
        return
    from txtool.lint.target_check import Written, judge_includers, target_distro

    settings = {path: each for path, _, each in plan}
    found = judge_includers([Written(r.path, r.original, r.data) for r in written],
                            [path for path, _, _ in plan], options.target,
                            lambda path: settings[path],
                            distro=target_distro(options.target, options.ros_distro))
    for result in written:
        losses = found.get(result.path, [])
        result.losses.extend(losses)
        if losses and not options.allow_lossy:
            result.refused = True


def _plan(
    paths: Iterable[str], options: MigrateOptions, report: Report
) -> list[tuple[str, list[Rule], Settings]]:
    overrides = Overrides(select=options.select, ignore=options.ignore, xacro=options.xacro,
                          no_xacro=options.no_xacro, ros_distro=options.ros_distro)
    settings = SettingsCache(overrides, options.config)
    plan = []
    unread = lambda where, reason: _error(report, f"{where}: {reason}")  # noqa: E731
    for path in expand_paths(paths, report=unread):
        if path == "-":
            raise InputError("-: migrate rewrites files in place; standard input is not supported")
        each = settings.for_file(path)
        enabled = each.enabled
        plan.append((path, [r for r in all_rules().values() if r.fixable and r.code in enabled],
                     each))
    report.messages.extend(f"txtool: note: {note}" for note in settings.notes)
    return plan


def _error(report: Report, message: str) -> None:
    report.errors.append(message)
    report.messages.append(f"txtool: {message}")


def _record(report: Report, result: FileResult, options: MigrateOptions) -> None:
    for note in result.notes:
        report.messages.append(f"note: {result.path}: {note}")
    for left in result.warnings:
        report.messages.append(f"warning: {result.path}: {left}")
    level = "error" if result.refused else "warning"
    for loss in result.losses:
        report.messages.append(f"{level}: {result.path}: {loss}")
    if result.refused:
        report.messages.append(f"refused {result.path}: {len(result.losses)} item(s) would be "
                               "lost; not changed (use --allow-lossy to accept)")
        return
    if not result.changed:
        return
    if options.mode == "diff":
        report.diffs.append(unified_diff(result.path, result.original, result.data))
    if options.mode == "write":
        try:
            _write(result)
        except InputError as exc:
            result.unwritten = True
            _error(report, str(exc))
            return
        report.messages.append(f"changed {result.path} ({result.describe()})")
    else:
        report.messages.append(f"would change {result.path} ({result.describe()})")


def _write(result: FileResult) -> None:
    """Write atomically, unless the file changed on disk since it was read."""
    try:
        replace_if_unchanged(result.path, result.original, result.data, "migration")
    except OSError as exc:
        raise InputError(f"{result.path}: cannot write: {exc.strerror or exc}") from None


def migrate_file(path: str, rules: Sequence[Rule], options: MigrateOptions,
                 settings: Settings | None = None) -> FileResult:
    """The migrated bytes of one file (nothing is written); :class:`InputError` if unreadable.

    A file whose conversion would lose something is refused (left unchanged) unless
    ``allow_lossy``; losses of a file that would not change anyway are only reported. What
    would be written is checked for the target's loaders (:mod:`txtool.lint.target_check`;
    ``settings``: the file's, as validate resolves them): an error they did not have with the
    original is a loss.
    """
    result = _migrated(path, rules, options)
    if not result.refused and result.data != result.original:
        _judge(result, path, options, settings)
    return result


def _judge(result: FileResult, path: str, options: MigrateOptions,
           settings: Settings | None) -> None:
    from txtool.lint.target_check import judge, prepared, target_distro

    if settings is None:
        settings = SettingsCache(Overrides(xacro=options.xacro, no_xacro=options.no_xacro,
                                           ros_distro=options.ros_distro)).for_file(path)
    try:
        distro = target_distro(options.target, options.ros_distro)
    except ValueError as exc:
        raise InputError(str(exc)) from None
    # What is written is given to judge alone, which lets its tree go before it reads the input.
    judged = judge(prepared(path, result.path, result.data, settings),
                   lambda: prepared(path, result.path, result.original, settings),
                   options.target, distro=distro, own=settings.stated, settings=settings)
    result.warnings.extend(judged.warnings)
    result.losses.extend(judged.losses)
    if judged.losses and not options.allow_lossy:
        result.refused = True


def _migrated(path: str, rules: Sequence[Rule], options: MigrateOptions) -> FileResult:
    display, original = read_bytes(path)
    tree = parse_bytes(original, display)
    # What the end needs of the document as read is kept, and its tree is fixed in place.
    comments = [(node.text, node.sourceline) for node in _comment_nodes(tree)]
    result = FileResult(path=display, original=original, data=original, target=options.target)
    clean = not might_fix(tree.getroot(), rules)  # fix_tree() would find nothing
    if not clean:  # only what validate reports under the file's readers is fixed
        rules = fixes_read(Source(display, original, tree), rules, options.ros_distro,
                           options.config)
        clean = not rules
    if clean and options.target is None:
        return result
    source = Source(display, original, tree)
    del tree  # given up to the stages, which free it once converted
    return _steps(result, source, rules, options, comments, clean)


def _steps(result: FileResult, source: Source, rules: Sequence[Rule],
           options: MigrateOptions, comments: list[tuple[str | None, int | None]],
           clean: bool) -> FileResult:
    """Fix ``source.tree`` (the parse of ``result.original``, which the caller gives up;
    ``clean``: no fix finds anything in it), convert, and fix what the conversion wrote: each
    stage says its change as edits of the bytes the stage before wrote (:func:`_fixed`,
    :func:`.convert.convert_source`), and the stages' edits are composed into edits of the
    original, which the one applier makes (:func:`.edits.core.compose`)."""
    original, display = result.original, result.path
    stages: list[list[Edit]] = []  # each stage's edits, of the bytes the stage before wrote
    data = original
    if not clean:
        data = _fix_stage(result, data, source.tree, rules, stages)
    if options.target is None:
        after = _comments(source.tree)
    else:
        if data is not original:
            source.tree = parse_bytes(data, display, limit=None)
            source.data = data
        try:  # the conversion frees the tree once converted
            conversion = convert_source(source, options.target,
                                        hardware_plugin=options.hardware_plugin, consume=True,
                                        reversible=options.reversible,
                                        macro_calls=options.macro_calls)
        except ValueError as exc:
            result.losses.append(f"cannot convert: {exc}")
            result.refused = True
            return result
        _take_messages(result, conversion, options)
        stages.append(conversion.edits or [])
        data = conversion.data
        converted = parse_bytes(data, display, limit=None)
        if might_fix(converted.getroot(), rules):
            data = _fix_stage(result, data, converted, rules, stages)
        after = _comments(converted)
        del converted
    result.losses.extend(_dropped(comments, after))
    if result.losses and not options.allow_lossy and data != original:
        result.refused = True
        return result
    _settle(result, stages, data)
    return result


def _fix_stage(result: FileResult, data: bytes, tree: etree._ElementTree,
               rules: Sequence[Rule], stages: list[list[Edit]]) -> bytes:
    """Fix ``tree`` (the parse of ``data``) as a stage of :func:`_steps`: the fixed bytes."""
    fixed, edits, fixes = _fixed(data, tree, rules, result.path)
    result.fixes.update(fixes)
    stages.append(edits)
    return fixed


def _settle(result: FileResult, stages: list[list[Edit]], final: bytes) -> None:
    """Compose the edits of ``stages`` into edits of the original and make them: the written
    bytes are the original's with those edits, which must be what the stages wrote (where one
    stage alone edited, they are its edits and its bytes)."""
    written_by = [edits for edits in stages if edits]
    if len(written_by) == 1:  # one stage edited the original: ``final`` is its edits made
        result.data, result.edits = final, list(written_by[0])
        return
    text = EditedText(result.original)
    composed: list[Edit] = []
    for edits in written_by:
        composed = compose(composed, edits, text.data) if composed else list(edits)
    written = text.applied(composed)
    if written != final:
        raise InputError(f"{result.path}: cannot migrate: the composed edits do not write "
                         "what the stages wrote; please report this file")
    result.data, result.edits = written, composed or None


def _take_messages(result: FileResult, conversion: ConvertedDocument,
                   options: MigrateOptions) -> None:
    result.notes.extend(conversion.notes)
    result.warnings.extend(conversion.warnings)
    if conversion.placeholder is not None and not options.plugin_chosen and (
            options.allow_lossy or not conversion.losses):
        result.warnings.append(conversion.placeholder)
    result.losses.extend(conversion.losses)
    result.converted = conversion.converted


def _fixed(data: bytes, tree: etree._ElementTree, rules: Sequence[Rule], path: str
           ) -> tuple[bytes, list[Edit], dict[str, int]]:
    """Fix ``tree`` (the parse of ``data``) and say what the fixes changed as edits of
    ``data`` (:mod:`.edits.document`): the fixed bytes, the edits and the fixes by code. The
    bytes are read back: they must parse to the fixed tree."""
    elements = transmission_elements(tree.getroot())  # what the fixes may change
    writer = DocumentEdits(path, data, tree.getroot(), elements)
    del elements
    fixes = fix_tree(tree, rules, data)
    edits, fixed = writer.written()
    if fixed != data:
        read_back(fixed, path, serialization(tree), "fix")
    return fixed, edits, fixes


def _dropped(before: list[tuple[str | None, int | None]], after: list[str | None]) -> list[str]:
    """A loss for each comment of ``before`` (its text and line) that ``after`` (the texts of
    the comments) no longer has: conversions rebuild the transmissions they convert, without
    the comments inside them."""
    left = Counter(after)
    lost = []
    for comment, line in before:
        if (comment or "").strip().startswith(MARK):
            continue  # a carried original, put back by the conversion (--reversible)
        if left[comment] > 0:
            left[comment] -= 1
            continue
        text = " ".join((comment or "").split())
        text = text if len(text) <= 60 else text[:57] + "..."
        lost.append(f"line {line}: comment '{text}' is inside a converted transmission; "
                    "dropped")
    return lost


def _comment_nodes(tree: etree._ElementTree) -> list[etree._Comment]:
    root = tree.getroot()
    around = [*root.itersiblings(preceding=True), *root.itersiblings()]
    inside = root.iter(etree.Comment)
    return [node for node in (*around, *inside) if isinstance(node, etree._Comment)]


def _comments(tree: etree._ElementTree) -> list[str | None]:
    return [node.text for node in _comment_nodes(tree)]


# Diff ------------------------------------------------------------------------------------------


def unified_diff(path: str, before: bytes, after: bytes) -> str:
    """A unified diff with ``a/PATH`` and ``b/PATH`` headers (``git apply`` / ``patch -p1``)
    of the lines of both documents as text (:mod:`.linediff`)."""
    name = path.replace(os.sep, "/")
    while name.startswith("./"):  # a walk of "." names src/robot.urdf, as git diff does
        name = name[2:]
    name = printable(name.lstrip("/"))  # a name's newline: not a new line
    return unified_text(
        document_text(before).splitlines(keepends=True),
        document_text(after).splitlines(keepends=True),
        f"a/{name}",
        f"b/{name}",
    )
