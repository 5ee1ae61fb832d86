"""What the language server says of one editor buffer, without the protocol: its problems, the
text a fix gives, the edits from one text to another, the effective view of a transmission.

The buffer is checked by the engine that checks files (:func:`txtool.lint.engine.lint_buffer`),
with the configuration, suppressions and xacro handling of ``txtool validate``; fixes are
``txtool migrate``'s (:func:`txtool.transform.migrate.migrate_file`). Lines and columns here
are 0-based and count characters (code points); the server converts them to the client's units.
"""

from __future__ import annotations

import difflib
import os
import re
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass

from txtool.io.xmlio import InputError, Source, XacroOptions, parse_bytes
from txtool.lint.config import Overrides, Settings, SettingsCache
from txtool.lint.config_files import find_config_cache_clear, repository_root
from txtool.lint.discover import SUFFIXES, XML_ROOTS
from txtool.lint.problem import Problem
from txtool.rules import Rule, all_rules

# Comments, processing instructions and a DOCTYPE before the root element.
_PROLOG = re.compile(r"\s*(?:<!--.*?-->|<\?.*?\?>|<!DOCTYPE[^>]*>)", re.DOTALL)
_ROOT_NAME = re.compile(r"\s*<(?:[\w.-]+:)?([\w.-]+)")
_DECLARED = re.compile(r"\s*<\?xml[^>]*?encoding\s*=\s*[\"']([\w.:-]+)[\"']")
_LINE_AND_REST = re.compile(r"^[^:]*?:(\d+):\s*(.*)$", re.DOTALL)


@dataclass(frozen=True)
class Options:
    """What ``txtool lsp`` takes: as ``txtool validate``'s options of the same names."""

    xacro: XacroOptions = XacroOptions()
    no_xacro: bool = False
    config: str | None = None
    ros_distro: str | None = None


@dataclass(frozen=True)
class Failure:
    """Why the buffer could not be checked (a bad configuration, a refused expansion): one
    line, placed at ``line`` (0-based)."""

    line: int
    message: str


def is_robot_file(path: str, text: str) -> bool:
    """Whether the buffer is one ``txtool validate`` checks in a folder: ``*.urdf`` and
    ``*.xacro`` files, and ``.xml`` files whose root is a robot description."""
    if path.endswith(SUFFIXES):
        return True
    if not path.endswith(".xml"):
        return False
    start = 0
    while (prolog := _PROLOG.match(text, start)) is not None:
        start = prolog.end()
    root = _ROOT_NAME.match(text, start)
    return root is not None and root.group(1) in XML_ROOTS


def root_of(path: str, workspace: Sequence[str] = ()) -> str:
    """The run's root for ``path``: the repository of the workspace folder holding it, as
    ``txtool validate`` run there has (else of the file's own folder)."""
    folder = os.path.dirname(os.path.abspath(path))
    for top in sorted(workspace, key=len, reverse=True):
        if folder == top or folder.startswith(top.rstrip(os.sep) + os.sep):
            return repository_root(top)
    return repository_root(folder)


def settings_for(path: str, root: str, options: Options) -> Settings:
    """The settings ``txtool validate`` run from ``root`` applies to ``path``; configuration
    files are read again each time (an edited ``.txtool.toml`` counts at once)."""
    find_config_cache_clear()
    overrides = Overrides(xacro=options.xacro, no_xacro=options.no_xacro,
                          ros_distro=options.ros_distro)
    return SettingsCache(overrides, options.config, root=root).for_file(path)


def encode(text: str) -> tuple[bytes, str]:
    """The buffer's bytes, in the encoding its XML declaration names when that can hold it
    (else UTF-8), and that encoding."""
    declared = _DECLARED.match(text)
    if declared is not None:
        try:
            return text.encode(declared.group(1)), declared.group(1)
        except (LookupError, UnicodeError):
            pass
    return text.encode("utf-8"), "utf-8"


def problems_of(path: str, text: str, root: str, options: Options) -> list[Problem] | Failure:
    """The problems ``txtool validate`` finds in the buffer, were it saved at ``path``."""
    from txtool.lint.engine import lint_buffer

    try:
        settings = settings_for(path, root, options)
        return lint_buffer(path, encode(text)[0], settings)
    except InputError as exc:
        return failure(str(exc), path)
    except OSError as exc:  # a configuration file in a folder that cannot be read, say
        if exc.filename is None:
            raise
        return Failure(0, f"{os.fsdecode(exc.filename)}: {(exc.strerror or str(exc)).lower()}")


def failure(message: str, path: str) -> Failure:
    """``path:line: reason`` (or ``path: reason``) as a :class:`Failure` at that line."""
    message = message.removeprefix(f"{path}: ")
    placed = _LINE_AND_REST.match(message) if message.startswith(path) else None
    if placed is None:
        return Failure(0, message)
    return Failure(max(int(placed.group(1)) - 1, 0), placed.group(2))


def fixable_rules(path: str, root: str, options: Options,
                  codes: Sequence[str] | None = None) -> list[Rule]:
    """The fixable rules enabled for ``path`` (of ``codes`` only, when given); none when the
    configuration cannot be read (the diagnostics say why)."""
    try:
        enabled = settings_for(path, root, options).enabled
    except (InputError, OSError):
        return []
    return [rule for rule in all_rules().values()
            if rule.fixable and rule.code in enabled and (codes is None or rule.code in codes)]


def fixed_text(path: str, text: str, rules: Sequence[Rule],
               settings: Settings | None = None) -> tuple[str, dict[str, int]]:
    """The buffer as ``txtool migrate`` fixes it with ``rules`` (suppressions honoured), and
    how many fixes of each code; the text unchanged when nothing applies, or when what the
    fixes write has an error for the file's readers (``settings``: the file's, as validate
    resolves them) that the buffer does not have."""
    from txtool.transform.migrate import MigrateOptions, migrate_file

    if not rules:
        return text, {}
    data, encoding = encode(text)
    # migrate reads a file: the buffer is written to one of the same name in a private folder.
    with tempfile.TemporaryDirectory(prefix="txtool-lsp-") as folder:
        copy = os.path.join(folder, os.path.basename(path))
        with open(copy, "wb") as handle:
            handle.write(data)
        try:
            result = migrate_file(copy, rules, MigrateOptions(), settings)
        except InputError:
            return text, {}
    if not result.changed:
        return text, {}
    return result.data.decode(encoding), {code: n for code, n in result.fixes.items() if n}


@dataclass(frozen=True)
class LineEdit:
    """Replace lines ``start`` up to (not including) ``end`` with ``text``; ``end`` may be the
    number of lines (the end of the document)."""

    start: int
    end: int
    text: str


def line_edits(before: str, after: str) -> list[LineEdit]:
    """The fewest whole-line replacements that turn ``before`` into ``after``."""
    old = before.splitlines(keepends=True)
    new = after.splitlines(keepends=True)
    matcher = difflib.SequenceMatcher(None, old, new, autojunk=False)
    return [LineEdit(i1, i2, "".join(new[j1:j2]))
            for tag, i1, i2, j1, j2 in matcher.get_opcodes() if tag != "equal"]


def end_of(text: str, line: int) -> tuple[int, int]:
    """(line, character) of the start of ``line``, or of the end of the document when that
    is past its last line."""
    lines = text.splitlines(keepends=True)
    if line < len(lines):
        return line, 0
    if not lines or lines[-1].endswith(("\n", "\r")):
        return len(lines), 0
    return len(lines) - 1, len(lines[-1])


def load_buffer(path: str, text: str, settings: Settings) -> Source:
    """The buffer as the rules see it: expanded when xacro expands it (as written when the
    expansion fails)."""
    from txtool.io.load import needs_expansion

    data = encode(text)[0]
    tree = parse_bytes(data, path)
    if settings.no_xacro or not needs_expansion(path, data, tree):
        return Source(path=path, data=data, tree=tree)
    from txtool.io.xacro import expand_xacro

    try:
        expanded = expand_xacro(path, path, settings.xacro, data=data)
    except InputError:
        return Source(path=path, data=data, tree=tree)
    return Source(path=path, data=data, tree=expanded, expanded=True, source_tree=tree)
