"""xacro expansion with the ``xacro`` package: no ROS install needed.

Untrusted by default: see :mod:`txtool.io.xacro_sandbox` and :mod:`txtool.io.xacro_guard`;
``--trust-xacro`` runs upstream xacro in this process.

``$(find pkg)`` is resolved as in a ROS workspace, without flags: see :mod:`txtool.io.packages`.

xacro parses with ``xml.dom.minidom`` (expat), which expands internal entities. Every file it
reads, the top file and each ``<xacro:include>``, is first checked with a bare expat parser and
refused when it declares entities (see :func:`refuse_unsafe_xml`), so nothing is ever expanded
or pulled in from a DTD.
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import xml.dom.minidom
import xml.parsers.expat
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any

from lxml import etree

from txtool.io.install_layout import installed_source
from txtool.io.packages import (
    PackageNotFound,
    enclosing_manifest,
    find_package,
    package_name,
)
from txtool.io.xacro_sandbox import expand_in_sandbox
from txtool.io.xmlio import (
    ENTITY_REFUSAL,
    MAX_BYTES,
    EntityRefused,
    InputError,
    TooLarge,
    XacroError,
    XacroOptions,
    XMLSyntax,
    parse_bytes,
    read_regular,
)

if TYPE_CHECKING:
    from txtool.io.xacro_guard import XacroGuard

MAX_DEPTH = 256  # libxml2's limit without huge_tree, so both parsers agree
MAX_READ = MAX_BYTES  # what one expansion may read in all: the top file and every include


def expand_xacro(path: str, display: str, options: XacroOptions,
                 data: bytes | None = None) -> etree._ElementTree:
    """Expand ``path`` and parse the result safely; ``data``: the text to read for the file
    at ``path`` instead of what the file holds (an editor's unsaved buffer), its includes
    and ``$(find)`` still found from where it is.

    By default in a bounded child process with the restricted evaluator
    (:mod:`txtool.io.xacro_sandbox`); with ``options.trust`` (``--trust-xacro``) here, by
    upstream xacro with its own Python evaluation.
    """
    if options.trust:
        text = expand_text(path, display, options, data=data)
    else:
        text = expand_in_sandbox(path, display, options, max_read=MAX_READ, data=data)
    try:
        return parse_bytes(text.encode("utf-8"), display)
    except XMLSyntax as exc:
        raise XacroError(display, f"expanded document is not XML: {exc.reason}") from None


def expand_text(path: str, display: str, options: XacroOptions,
                guard: XacroGuard | None = None, data: bytes | None = None) -> str:
    """The expansion of ``path`` as text, in this process: upstream xacro, or with ``guard``
    its hooks installed (restricted evaluator, allowed environment, files inside the roots);
    ``data``, when given, is read for the file at ``path`` (see :func:`expand_xacro`)."""
    import xacro
    from xacro import substitution_args

    def eval_find(pkg: str) -> str:
        return find_package(pkg, near=path, pkg_paths=options.pkg_paths, pkg_dirs=options.pkg_dirs)

    saved_find, saved_parse = substitution_args._eval_find, xacro.parse
    substitution_args._eval_find = eval_find
    top = (os.path.abspath(path), data) if data is not None else None
    xacro.parse = _checked_parse(saved_parse, xacro, guard, top)
    stderr = io.StringIO()
    try:
        with contextlib.redirect_stderr(stderr), _quiet_cwd(), _installed(guard):
            doc = xacro.process_file(os.path.abspath(path), mappings=dict(options.args))
            return str(doc.toxml())
    except Exception as exc:  # xacro raises many kinds, all user-facing
        cause = _root_cause(exc)
        if guard is not None:
            guard.reraise_refusal(cause)
        missing = _missing(cause, path)
        reason = _xacro_reason(cause) + (_hint(cause, path) if missing else "")
        raise XacroError(display, reason, missing=missing) from None
    finally:
        substitution_args._eval_find = saved_find
        xacro.parse = saved_parse
        _reset_xacro_state(xacro)


@contextlib.contextmanager
def _installed(guard: XacroGuard | None) -> Iterator[None]:
    if guard is None:
        yield
        return
    with guard.installed():
        yield


class UnsafeXML(Exception):
    """A file xacro would read declares entities or nests too deep."""

    def __init__(self, path: str, line: int, reason: str) -> None:
        super().__init__(f"{path}:{line}: {reason}")


def _checked_parse(original: Callable[..., Any], xacro: Any, guard: XacroGuard | None,
                   top: tuple[str, bytes] | None = None) -> Callable[..., Any]:
    """xacro's ``parse(inp, filename)``, reading files as bytes checked by refuse_unsafe_xml.

    Only regular files are read, and at most :data:`MAX_READ` bytes in all: a device or FIFO
    included, or a file included over and over, cannot exhaust memory or block forever. With a
    guard, only files inside its roots (the repository and the packages ``$(find)`` found).
    ``top``: (absolute path, bytes) read for that file instead of the file itself.
    """
    budget = MAX_READ

    def parse(inp: Any, filename: str | None = None) -> Any:
        nonlocal budget
        if inp is not None or filename is None:
            return original(inp, filename)
        path = os.path.join(xacro.root_dir, filename)
        if guard is not None:
            guard.check_readable(path, "include")
        given = top is not None and os.path.abspath(path) == top[0]
        if not given and not os.path.exists(path):
            path = installed_source(path) or ""  # the checkout of a package laid out anew
            if not path:
                return original(inp, filename)  # xacro reports a missing file its own way
            if guard is not None:
                guard.check_readable(path, "include")
        try:
            data = _given(top[1], budget) if given and top else read_regular(path, budget)
        except TooLarge:
            reason = (f"xacro would read more than {MAX_READ} bytes in all (the top file and "
                      "its includes; a safety limit)")
            raise UnsafeXML(filename, 1, reason) from None
        except InputError as exc:
            raise UnsafeXML(filename, 1, str(exc).removeprefix(f"{path}: ")) from None
        budget -= len(data)
        refuse_unsafe_xml(data, filename)
        # Bytes, not text: expat then honours the file's BOM and encoding declaration.
        return xml.dom.minidom.parseString(data)

    return parse


def _given(data: bytes, budget: int) -> bytes:
    """``data`` read as :func:`read_regular` reads a file of that content."""
    if len(data) > budget:
        raise TooLarge(f"larger than {budget} bytes")
    return data


def refuse_unsafe_xml(data: bytes, path: str) -> None:
    """Raise :class:`UnsafeXML` if the file declares or refers to entities, or nests too deep.

    expat is asked first (it is what xacro parses with; the check stops at the first
    declaration, before any reference to it can be expanded), then lxml, which also sees
    references in attribute values that expat drops without a word. Malformed XML passes:
    xacro's own parse reports it.
    """
    parser = xml.parsers.expat.ParserCreate()
    parser.SetParamEntityParsing(xml.parsers.expat.XML_PARAM_ENTITY_PARSING_NEVER)
    depth = 0

    def on_entity(*_: Any) -> None:
        raise UnsafeXML(path, parser.CurrentLineNumber, ENTITY_REFUSAL)

    def on_skipped(name: str, is_parameter: bool) -> None:
        # A reference to an entity of a DTD that expat does not load (nor do we).
        reason = (f"Entity '{name}' not defined: txtool loads no DTD and expands no entity; "
                  "write the text itself")
        raise UnsafeXML(path, parser.CurrentLineNumber, reason)

    def on_start(*_: Any) -> None:
        nonlocal depth
        depth += 1
        if depth > MAX_DEPTH:
            reason = f"elements nested more than {MAX_DEPTH} levels deep (a safety limit)"
            raise UnsafeXML(path, parser.CurrentLineNumber, reason)

    def on_end(*_: Any) -> None:
        nonlocal depth
        depth -= 1

    parser.EntityDeclHandler = on_entity
    parser.UnparsedEntityDeclHandler = on_entity
    parser.SkippedEntityHandler = on_skipped
    parser.StartElementHandler = on_start
    parser.EndElementHandler = on_end
    with contextlib.suppress(xml.parsers.expat.ExpatError):
        parser.Parse(data, True)
    try:
        parse_bytes(data, path)
    except EntityRefused as exc:
        raise UnsafeXML(path, exc.line, exc.reason) from None
    except InputError:
        pass


def _root_cause(exc: BaseException) -> BaseException:
    # xacro wraps the original error (XacroException.exc) as it unwinds macro calls.
    seen = 0
    while getattr(exc, "exc", None) is not None and seen < 50:
        exc = exc.exc  # type: ignore[attr-defined]
        seen += 1
    return exc


def _missing(exc: BaseException, path: str) -> str:
    """What the run lacks for the expansion to go on: an argument, a package, or a file of
    another package (the version found is not the one the file was written for)."""
    from xacro import substitution_args

    if isinstance(exc, PackageNotFound):
        return "package"
    if isinstance(exc, substitution_args.ArgException):
        return "argument"
    absent = getattr(exc, "filename", None)
    if isinstance(exc, FileNotFoundError) and isinstance(absent, str):
        own = enclosing_manifest(path)
        if own is not None and enclosing_manifest(absent) not in (None, own):
            return "package"
    return ""


_DEPEND = re.compile(rb"<(?:\w+_)?depend\b[^>]*>\s*([^<\s]+)\s*</")


def _hint(exc: BaseException, path: str) -> str:
    """What more to say of a package or file the run lacks."""
    if isinstance(exc, FileNotFoundError):
        return (" (a file of another package, which the version found lacks: give --pkg-dir "
                "DIR or --pkg-path NAME:=DIR for the version this file needs)")
    manifest = enclosing_manifest(path)
    if not isinstance(exc, PackageNotFound) or manifest is None:
        return ""
    try:
        declared = {m.decode("utf-8", "replace") for m in _DEPEND.findall(read_regular(
            str(manifest), MAX_BYTES))}
    except InputError:
        return ""
    if exc.name in declared:
        return ""
    own = package_name(manifest) or manifest.parent.name
    return (f"; the package.xml of '{own}' does not declare it: a dependency to declare, or a "
            "package that was renamed")


def _xacro_reason(exc: BaseException) -> str:
    from xacro import substitution_args

    if isinstance(exc, PackageNotFound | UnsafeXML):
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
        del xacro.all_includes[:]
