"""In-process xacro expansion with the ``xacro`` package: no ROS install needed.

``$(find pkg)`` is resolved from ``--pkg-path name:=DIR`` and from folders given with
``--pkg-dir`` (a package is a sub-folder named like it, or one whose ``package.xml`` names it).
"""

from __future__ import annotations

import contextlib
import io
import os
from pathlib import Path

from lxml import etree

from txtool.xmlio import InputError, XacroOptions, XMLSyntax, parse_bytes


class XacroError(InputError):
    """xacro could not expand the file (missing arg, package or property). Lint code TX002."""

    def __init__(self, path: str, reason: str, line: int = 1) -> None:
        super().__init__(f"{path}:{line}: xacro: {reason}")
        self.path = path
        self.line = line
        self.reason = reason


def find_package(name: str, options: XacroOptions) -> str:
    for pkg, folder in options.pkg_paths:
        if pkg == name:
            return folder
    for root in options.pkg_dirs:
        candidate = Path(root) / name
        if candidate.is_dir():
            return str(candidate)
        for manifest in sorted(Path(root).glob("*/package.xml")):
            if f"<name>{name}</name>" in manifest.read_text(errors="replace"):
                return str(manifest.parent)
    raise XacroPackageMissing(name)


class XacroPackageMissing(Exception):
    def __init__(self, name: str) -> None:
        super().__init__(
            f"package '{name}' not found (give --pkg-dir DIR or --pkg-path {name}:=DIR)"
        )


def expand_xacro(path: str, display: str, options: XacroOptions) -> etree._ElementTree:
    """Expand ``path`` and parse the result safely."""
    import xacro
    from xacro import substitution_args

    def eval_find(pkg: str) -> str:
        return find_package(pkg, options)

    saved = substitution_args._eval_find
    substitution_args._eval_find = eval_find
    stderr = io.StringIO()
    try:
        with contextlib.redirect_stderr(stderr), _quiet_cwd():
            doc = xacro.process_file(os.path.abspath(path), mappings=dict(options.args))
            text = doc.toxml()
    except Exception as exc:  # xacro raises many kinds, all user-facing
        raise XacroError(display, _xacro_reason(_root_cause(exc))) from None
    finally:
        substitution_args._eval_find = saved
        _reset_xacro_state(xacro)
    try:
        return parse_bytes(text.encode("utf-8"), display)
    except XMLSyntax as exc:
        raise XacroError(display, f"expanded document is not XML: {exc.reason}") from None


def _root_cause(exc: BaseException) -> BaseException:
    # xacro wraps the original error (XacroException.exc) as it unwinds macro calls.
    seen = 0
    while getattr(exc, "exc", None) is not None and seen < 50:
        exc = exc.exc  # type: ignore[attr-defined]
        seen += 1
    return exc


def _xacro_reason(exc: BaseException) -> str:
    from xacro import substitution_args

    if isinstance(exc, XacroPackageMissing):
        return str(exc)
    if isinstance(exc, substitution_args.ArgException):
        return f"missing argument '{exc}' (give --xacro-arg {exc}:=VALUE)"
    text = " ".join(str(exc).split()) or type(exc).__name__
    if type(exc).__name__ == "ExpatError":
        return f"not well-formed XML ({text})"
    return text


@contextlib.contextmanager
def _quiet_cwd():
    cwd = os.getcwd()
    try:
        yield
    finally:
        os.chdir(cwd)


def _reset_xacro_state(xacro) -> None:
    # xacro keeps the include and macro stacks in module globals.
    with contextlib.suppress(Exception):
        xacro.init_stacks(None)
