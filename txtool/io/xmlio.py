"""Safe XML parsing, reading an input's bytes (a file or stdin) and atomic writing.

xacro is expanded elsewhere (:mod:`txtool.io.xacro`, through :mod:`txtool.io.load`); what every
input step shares is here: :class:`Source`, the input errors, :class:`XacroOptions`.

Every reader goes through :func:`safe_parser`: no entity expansion, no DTD loading, no network
access, no huge trees. Parsed elements keep ``sourceline`` for diagnostics.
"""

from __future__ import annotations

import codecs
import contextlib
import os
import re
import stat
import sys
import threading
from contextvars import ContextVar
from typing import NamedTuple

from lxml import etree

from txtool.io.encodings import detect_encoding, mislabelled, parsing_form, utf8_form
from txtool.io.targets import refused_target, remember_input, sweep_stale_temporaries

XACRO_NS = "http://www.ros.org/wiki/xacro"
XACRO_SUFFIXES = (".xacro",)
MAX_BYTES = 64 * 1024 * 1024
# libxml2 reads no element nested deeper than this (XML_PARSE_HUGE, which txtool never sets,
# would lift it).
MAX_DEPTH = 256

_DECLARATION = re.compile(rb"^(?:\xef\xbb\xbf)?\s*<\?xml[^>]*\?>")  # after a UTF-8 BOM too
# Whitespace (and nothing else) before the XML declaration: see _movable_declaration.
LEADING_SPACE_DECLARATION = re.compile(rb"(?:\xef\xbb\xbf)?([ \t\r\n]+)<\?xml[ \t\r\n]")
_ENCODING = re.compile(rb"""^\s*<\?xml[^>]*encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")
# Byte-order marks, and how the first "<" looks in UTF-16/32 text that has none.
_UNICODE_STARTS = (
    b"\xff\xfe", b"\xfe\xff", b"\x00\x00\xfe\xff",
    b"<\x00", b"\x00<", b"\x00\x00\x00<",
)
_TEXT_CONTROLS = frozenset(b"\t\n\r")
ENTITY_REFUSAL = (
    "the DOCTYPE declares entities; txtool does not read entity declarations "
    "(they can pull in local files or expand without bound): remove them"
)

_reading: ContextVar[str | None] = ContextVar("txtool_reading", default=None)


class InputError(Exception):
    """A one-line, user-facing error: ``path[:line]: reason``. Exit code 2."""


class TooLarge(InputError):
    """A file over the size limit (refused by its size, before it is read)."""


# What every lxml reader of txtool is given: no entities, no DTD, no network, no huge trees.
SAFE_OPTIONS: dict[str, bool] = {
    "resolve_entities": False,
    "no_network": True,
    "load_dtd": False,
    "dtd_validation": False,
    "huge_tree": False,
}


def safe_parser(*, recover: bool = False) -> etree.XMLParser:
    return etree.XMLParser(
        **SAFE_OPTIONS,
        remove_comments=False,
        remove_pis=False,
        strip_cdata=False,
        recover=recover,
    )


class Source:
    """One input document.

    ``tree`` is what the transmissions are read from: the file itself, or its xacro expansion.
    For xacro inputs ``source_tree`` is the file as written (for locations and in-place edits).
    """

    def __init__(self, path: str, data: bytes, tree: etree._ElementTree, expanded: bool = False,
                 source_tree: etree._ElementTree | None = None,
                 notes: list[str] | None = None) -> None:
        self.path = path
        self.data = data
        self.tree = tree
        self.expanded = expanded
        self.source_tree = source_tree
        self.notes: list[str] = [] if notes is None else notes

    @property
    def root(self) -> etree._Element:
        return self.tree.getroot()


def is_xacro(path: str) -> bool:
    return path.endswith(XACRO_SUFFIXES)


def reading() -> str | None:
    """The input read last (by :func:`read_bytes`), for naming it in an internal error."""
    return _reading.get()


def forget_reading() -> None:
    _reading.set(None)


def read_bytes(path: str, *, stdin_name: str | None = None) -> tuple[str, bytes]:
    """Read a file or ``-`` (stdin); returns the display path and the bytes."""
    from txtool.io.signals import stop_if_received

    stop_if_received()
    if path == "-":
        _reading.set(stdin_name or "<stdin>")
        if sys.stdin is None:  # started with standard input closed (`<&-`)
            raise InputError("-: standard input is closed; nothing to read")
        try:
            return stdin_name or "<stdin>", sys.stdin.buffer.read(MAX_BYTES + 1)
        except OSError as exc:
            raise InputError(f"-: cannot read standard input: {exc.strerror or exc}") from None
    _reading.set(path)
    return path, read_regular(path)


def read_regular(path: str, limit: int = MAX_BYTES) -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes; anything else is refused
    before it is read (a device never ends, a FIFO blocks until someone writes to it)."""
    try:
        mode = os.stat(path).st_mode
        if stat.S_ISDIR(mode):
            raise IsADirectoryError
        refuse_special(path, mode)
        # O_NONBLOCK: a FIFO swapped in after the check cannot block the open.
        handle = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC)
        try:  # plain descriptor reads: a buffered file object costs more than a small read
            status = os.fstat(handle)
            refuse_special(path, status.st_mode)
            remember_input(status)
            if status.st_size > limit:
                raise TooLarge(f"{path}: file is {status.st_size} bytes, larger than the "
                               f"{limit} limit")
            # Asking for the size the file has (not the limit) spares allocating the limit's
            # 64 MB for every small file; one byte more tells whether it grew since fstat.
            data = _read_up_to(handle, status.st_size + 1)
            if len(data) > status.st_size:
                data += _read_up_to(handle, limit + 1 - len(data))
            if len(data) > limit:  # grew since fstat
                raise TooLarge(f"{path}: file is larger than the {limit} limit")
            return data
        finally:
            os.close(handle)
    except IsADirectoryError:
        raise InputError(f"{path}: is a directory") from None
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except PermissionError:
        raise InputError(f"{path}: permission denied") from None
    except OSError as exc:
        raise InputError(f"{path}: {exc.strerror or exc}") from None


def _read_up_to(handle: int, size: int) -> bytes:
    """Up to ``size`` bytes, fewer only at the end of the file (as a file object's read)."""
    data = os.read(handle, size)
    if len(data) == size or not data:
        return data
    parts = [data]
    size -= len(data)
    while size > 0:
        data = os.read(handle, size)
        if not data:
            break
        parts.append(data)
        size -= len(data)
    return b"".join(parts)


_KINDS = (
    (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
    (stat.S_ISFIFO, "a named pipe (FIFO)"), (stat.S_ISSOCK, "a socket"),
)


def refuse_special(path: str, mode: int, *, writing: bool = False) -> None:
    """Refuse a device, FIFO or socket (a folder has its own message)."""
    if stat.S_ISREG(mode) or stat.S_ISDIR(mode):
        return
    kind = next((name for test, name in _KINDS if test(mode)), "not a regular file")
    rest = "writes only regular files" if writing else "reads only regular files (or '-')"
    raise InputError(f"{path}: is {kind}, not a regular file; txtool {rest}")


def parse_bytes(data: bytes, path: str, *, limit: int | None = MAX_BYTES) -> etree._ElementTree:
    """Parse a document safely; malformed XML becomes :class:`XMLSyntax`. ``limit=None`` reads
    back what txtool made from an input within the limit (a conversion may make it larger)."""
    if limit is not None and len(data) > limit:
        raise InputError(f"{path}: document larger than the {limit} byte limit")
    if _is_blank(data):
        raise XMLSyntax(path, 1, 1, "document is empty")
    wrong = mislabelled(data)
    if wrong is not None:
        raise XMLSyntax(path, *wrong)
    parser = _reused_parser()
    try:
        text = parsing_form(data)
        root = etree.fromstring(_movable_declaration(text), parser)
    except etree.XMLSyntaxError as exc:
        if is_binary(data):
            raise XMLSyntax(path, 1, 1, "not an XML document (binary data)") from None
        reason = _syntax_message(exc)
        if reason == ENTITY_REFUSAL:
            raise EntityRefused(path, _entity_line(text), 1, reason) from None
        line, column = exc.position if exc.position else (1, 1)
        raise XMLSyntax(path, max(line, 1), max(column, 1), reason) from None
    except (LookupError, UnicodeError) as exc:  # an encoding name or text Python cannot decode
        raise XMLSyntax(path, 1, 1, f"cannot decode the document: {exc}") from None
    tree = root.getroottree()
    _refuse_entities(tree, parser, text, path)
    return tree


_PARSERS = threading.local()


def _reused_parser() -> etree.XMLParser:
    """This thread's :func:`safe_parser`, made once: making one costs about as much as parsing
    a small file, and each parse starts from a clean state (its error log included)."""
    parser: etree.XMLParser | None = getattr(_PARSERS, "parser", None)
    if parser is None:
        parser = _PARSERS.parser = safe_parser()
    return parser


_NON_BLANK = re.compile(rb"[^ \t\n\r\x0b\x0c]")  # what bytes.strip() strips


def _is_blank(data: bytes) -> bool:
    encoding = detect_encoding(data)
    if encoding.wide:
        return not data.removeprefix(encoding.mark).decode(encoding.codec, "replace").strip()
    return _NON_BLANK.search(data, len(codecs.BOM_UTF8) if data.startswith(codecs.BOM_UTF8)
                             else 0) is None


def is_binary(data: bytes) -> bool:
    """NUL or many other control bytes (which XML text cannot hold), and not UTF-16/32 text."""
    head = data[:1024]
    if head.startswith(_UNICODE_STARTS) or detect_encoding(head).wide:
        return False
    controls = sum(1 for byte in head if byte < 0x20 and byte not in _TEXT_CONTROLS)
    return b"\x00" in head or controls > max(8, len(head) // 50)


def _refuse_entities(
    tree: etree._ElementTree, parser: etree.XMLParser, data: bytes, path: str
) -> None:
    """Entities are never expanded (see :func:`safe_parser`); declaring them is refused.

    Unexpanded references would read as empty text (libxml2 drops them from attribute values),
    and xacro's parser (expat) would expand internal ones, so a document that declares entities
    is not read at all, nor one that refers to entities of a DTD that is never loaded.
    """
    dtd = tree.docinfo.internalDTD
    if dtd is not None and dtd.entities():
        raise EntityRefused(path, _entity_line(data), 1, ENTITY_REFUSAL)
    for entry in parser.error_log:
        if entry.type_name in ("WAR_UNDECLARED_ENTITY", "ERR_UNDECLARED_ENTITY"):
            reason = (f"{entry.message.strip()}: txtool loads no DTD and expands no entity; "
                      "write the text itself")
            raise EntityRefused(path, max(entry.line, 1), max(entry.column, 1), reason)


def _entity_line(data: bytes) -> int:
    """The line of the first entity declaration (1 when the encoding hides it)."""
    index = data.find(b"<!ENTITY")
    return data.count(b"\n", 0, index) + 1 if index >= 0 else 1


def _movable_declaration(data: bytes) -> bytes:
    """Blank out an XML declaration that does not start the document, keeping line numbers.

    Some published URDFs prepend a licence comment before ``<?xml ...?>``, others a blank line
    or spaces; libxml2 rejects both, while tinyxml2 (urdfdom, ros2_control) skips whitespace
    before the declaration. The declaration carries nothing a transmission needs beyond its
    encoding, which we honour by decoding first.
    """
    head = data[:4096]
    index = head.find(b"<?xml")
    if index <= 0:
        return data
    if not head[:index].strip() and not LEADING_SPACE_DECLARATION.match(head):
        return data
    match = re.compile(rb"<\?xml[^>]*\?>").search(data, index)
    if match is None:
        return data
    encoding = _ENCODING.match(data[index:])
    text = data
    if encoding and encoding.group(1).lower() not in (b"utf-8", b"utf8"):
        text = data.decode(encoding.group(1).decode("ascii")).encode("utf-8")
        match = re.compile(rb"<\?xml[^>]*\?>").search(text)
        if match is None:
            return text
    blank = b" " * (match.end() - match.start())
    return text[: match.start()] + blank + text[match.end() :]


def _syntax_message(exc: etree.XMLSyntaxError) -> str:
    message = re.sub(r", line \d+, column \d+$", "", str(exc.msg or exc)).strip()
    if "amplification" in message:
        return ENTITY_REFUSAL
    depth = re.match(r"Excessive depth in document: (\d+)", message)
    if depth:
        return f"elements nested more than {depth.group(1)} levels deep (a safety limit)"
    if "XML_PARSE_HUGE" in message:
        # libxml2's limits without huge_tree: 10 MB for one text or attribute value.
        reason = message.split(",")[0].removeprefix("Resource limit exceeded: ")
        return f"{reason.strip()}: a single text or attribute value over 10 MB (a safety limit)"
    return message


class XMLSyntax(InputError):
    """Malformed XML: a lint finding (TX001) for ``validate``, an input error elsewhere."""

    def __init__(self, path: str, line: int, column: int, reason: str) -> None:
        super().__init__(f"{path}:{line}:{column}: {reason}")
        self.path = path
        self.line = line
        self.column = column
        self.reason = reason


class EntityRefused(XMLSyntax):
    """A document that declares entities, or refers to entities of a DTD (never loaded)."""


class XacroError(InputError):
    """xacro could not expand the file (missing arg, package or property). Lint code TX002.

    ``missing`` is ``"argument"`` or ``"package"`` when what lacks is something the command
    line gives (``--xacro-arg``, ``--pkg-dir``), not a fault of the files; else empty.
    """

    def __init__(self, path: str, reason: str, line: int = 1, missing: str = "") -> None:
        super().__init__(f"{path}:{line}: xacro: {reason}")
        self.path = path
        self.line = line
        self.reason = reason
        self.missing = missing


class XacroOptions(NamedTuple):
    args: tuple[tuple[str, str], ...] = ()
    pkg_dirs: tuple[str, ...] = ()
    pkg_paths: tuple[tuple[str, str], ...] = ()
    trust: bool = False  # --trust-xacro: upstream xacro, in process; never from a file
    env: tuple[str, ...] = ()  # names $(env)/$(optenv) may read: --xacro-env, never a file
    # Folders the command line names (--pkg-dir, --pkg-path): the only package folders besides
    # the ROS environment's that an untrusted expansion may read outside the repository.
    readable: tuple[str, ...] = ()


def serialize(tree: etree._ElementTree, original: bytes | None = None) -> bytes:
    """Write a tree back, keeping the original XML declaration text when there was one, and
    the original's encoding and byte-order mark."""
    if original is not None:
        stored = detect_encoding(original)
        if stored.wide:
            return stored.from_utf8(serialize(tree, utf8_form(original)))
    encoding = "utf-8"
    declaration = _DECLARATION.match(original) if original is not None else None
    if declaration:
        declared = _ENCODING.match(original or b"")
        if declared and declared.group(1).lower() not in (b"utf-8", b"utf8"):
            encoding = declared.group(1).decode("ascii")
    parts = _top_level(tree, encoding)
    if declaration:
        gap = re.match(rb"\s*", original[declaration.end() :]).group(0)  # type: ignore[union-attr, index]
        parts[:0] = (re.sub(rb"^(\xef\xbb\xbf)?\s*", rb"\1", declaration.group(0)), gap or b"\n")
    if original is not None and original.endswith(b"\n") and not parts[-1].endswith(b"\n"):
        parts.append(b"\n")
    return b"".join(parts)  # one copy of the document, however many parts


def _top_level(tree: etree._ElementTree, encoding: str) -> list[bytes]:
    """The document without declaration, in parts to join: top-level comments each on a line
    of their own."""
    root = tree.getroot()
    before = list(root.itersiblings(preceding=True))[::-1]
    after = list(root.itersiblings())
    parts = [tree.docinfo.doctype.encode(encoding)] if tree.docinfo.doctype else []
    for node in [*before, root, *after]:
        if parts:
            parts.append(b"\n")
        parts.append(etree.tostring(node, encoding=encoding, xml_declaration=False,
                                    with_tail=False))
    return parts


def replace_if_unchanged(path: str, original: bytes, data: bytes, during: str) -> None:
    """Write ``data`` over ``path`` atomically (through a symbolic link), unless the file no
    longer holds ``original``: someone edited it while this command ran (``during`` names the
    command's work). The file's status when it is compared is checked again right before the
    rename, so an edit made while the new text is written is not lost either."""
    try:
        status = os.stat(path)
    except OSError as exc:
        raise InputError(f"{path}: cannot write: {exc.strerror or exc}") from None
    _, current = read_bytes(path)
    if current != original:
        raise InputError(f"{path}: changed on disk during the {during}; not written")
    write_atomic(path, data, in_place=Unchanged(status, during))


class Unchanged(NamedTuple):
    """An input rewritten in place: its status when its text was last compared."""

    status: os.stat_result
    during: str


def write_atomic(path: str, data: bytes, *, in_place: Unchanged | None = None,
                 inputs: tuple[str, ...] = (), report: bool = False) -> None:
    """Replace ``path`` with ``data``, or leave it byte for byte as it was.

    The data goes to a temp file in the same folder, is flushed to disk, gets the old file's
    owner, group, mode and extended attributes (ACLs among them; a new file: 0o666 less the
    umask, as ``open`` would) and is renamed over the target, whose folder is then flushed too.
    Refused, leaving it as it was: a target that is not a regular file (device, FIFO, socket),
    one with several hard links (a rename would split them), one the user could not write, one
    whose owner, group or attributes the replacement could not keep. Any failure removes the
    temp file and is an :class:`InputError`; so does SIGINT or SIGTERM (see
    :mod:`txtool.io.signals`). Temporary files a killed run left in the folder are removed
    (:func:`txtool.io.targets.sweep_stale_temporaries`).

    A new output (``in_place`` None) is never written through a symbolic link nor over a file
    read as an input (or named in ``inputs``); a ``report`` not over a robot description either
    (:func:`txtool.io.targets.refused_target`), and its missing folders are made. An input
    rewritten ``in_place`` is written through a symbolic link to its target, and only if its
    status is still the one compared.
    """
    import tempfile

    from txtool.io.signals import held, stop_if_received

    stop_if_received()
    if in_place is None:
        refusal = refused_target(path, inputs, report=report)
        if refusal is not None:
            raise InputError(f"{path}: {refusal}")
    # A new output is renamed over the name as given (a link there is replaced, not followed;
    # "x/../name" resolved by the system, not by text).
    target = os.path.realpath(path) if in_place is not None else path
    folder = os.path.dirname(target) or "."
    temp = None
    try:
        if report and in_place is None:  # ``-o out/report.sarif``, as other linters do
            os.makedirs(folder, exist_ok=True)
        old = _replaceable(path, target)
        sweep_stale_temporaries(folder)
        with held():  # a signal must not fall between creating the file and naming it
            handle, temp = tempfile.mkstemp(prefix=".txtool-", suffix=".tmp", dir=folder)
        with os.fdopen(handle, "wb") as out:
            out.write(data)
            out.flush()
            if old is None:
                os.fchmod(out.fileno(), 0o666 & ~_umask())
            else:
                _keep_identity(path, target, out.fileno(), old)
            os.fsync(out.fileno())
        if in_place is not None:
            _still_unchanged(path, target, in_place)
        os.replace(temp, target)
        temp = None
        _sync_folder(folder)
    except OSError as exc:
        raise InputError(f"{path}: cannot write: {exc.strerror or exc}") from None
    finally:
        if temp is not None:
            with held(), contextlib.suppress(OSError):
                os.unlink(temp)


def _still_unchanged(path: str, target: str, expected: Unchanged) -> None:
    """Refuse when the file is no longer the one compared: another inode (replaced), another
    size, modification or status-change time (written meanwhile)."""
    try:
        now = os.stat(target)
    except OSError:
        now = None
    then = expected.status
    if now is None or _identity(now) != _identity(then):
        raise InputError(f"{path}: changed on disk during the {expected.during}; not written")


def _identity(status: os.stat_result) -> tuple[int, ...]:
    return (status.st_dev, status.st_ino, status.st_size, status.st_mtime_ns,
            status.st_ctime_ns)


def _replaceable(path: str, target: str) -> os.stat_result | None:
    """The target's status (None when it does not exist), or why it may not be replaced."""
    try:
        status = os.stat(target)
    except FileNotFoundError:
        return None
    refuse_special(path, status.st_mode, writing=True)
    if not stat.S_ISREG(status.st_mode):
        return status  # a folder: the rename fails with "Is a directory"
    if status.st_nlink > 1:
        raise InputError(f"{path}: has {status.st_nlink} hard links; replacing it would leave "
                         "the other names with the old text, so it is not written (copy the "
                         "file to break the link)")
    effective = os.access in os.supports_effective_ids
    if not os.access(target, os.W_OK, effective_ids=effective):
        raise InputError(f"{path}: cannot write: permission denied (the file is read-only for "
                         "you; its folder being writable is not enough)")
    return status


def _keep_identity(path: str, target: str, handle: int, old: os.stat_result) -> None:
    """Give the new file (open as ``handle``) the old one's owner, group, mode and xattrs."""
    new = os.fstat(handle)
    if (new.st_uid, new.st_gid) != (old.st_uid, old.st_gid):
        try:
            os.fchown(handle, old.st_uid, old.st_gid)
        except PermissionError:
            raise InputError(
                f"{path}: cannot write: the file belongs to user {old.st_uid}, group "
                f"{old.st_gid}, which a replacement written by you could not keep"
            ) from None
    os.fchmod(handle, stat.S_IMODE(old.st_mode))  # after chown, which clears set-id bits
    wanted = _xattrs(target)
    for name in set(_xattrs(handle)) - set(wanted):  # inherited from the folder's defaults
        with contextlib.suppress(OSError):
            os.removexattr(handle, name)
    for name, value in wanted.items():
        try:
            os.setxattr(handle, name, value)
        except OSError as exc:
            raise InputError(f"{path}: cannot write: its extended attribute {name} could not "
                             f"be kept ({exc.strerror or exc})") from None


def _xattrs(file: str | int) -> dict[str, bytes]:
    """Extended attributes (POSIX ACLs are ``system.posix_acl_*``); none where unsupported."""
    if not hasattr(os, "listxattr"):
        return {}
    try:
        return {name: os.getxattr(file, name) for name in os.listxattr(file)}
    except OSError:
        return {}


def _sync_folder(folder: str) -> None:
    """Make the rename itself durable (a no-op where folders cannot be opened)."""
    try:
        handle = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(handle)
    except OSError:
        pass  # some file systems refuse fsync on a folder; the data itself is already synced
    finally:
        os.close(handle)


def _umask() -> int:
    current = os.umask(0)
    os.umask(current)
    return current


def attributes(element: etree._Element) -> dict[str, str]:
    """An element's attributes by name, in document order. lxml's ``attrib`` (its ``items``,
    ``values``, ``dict(...)``) finds each value by walking the attribute list from its start,
    which is quadratic in their number; an XPath reads them in one walk."""
    return dict(zip(element.keys(), element.xpath("@*", smart_strings=False), strict=True))


def local(element: etree._Element) -> str:
    """Tag without namespace; '' for comments and processing instructions."""
    tag = element.tag
    if not isinstance(tag, str):
        return ""
    return tag.rsplit("}", 1)[-1]


def is_xacro_element(element: etree._Element) -> bool:
    """A xacro directive or macro call (``xacro:`` prefix or the xacro namespace)."""
    tag = element.tag
    if not isinstance(tag, str):
        return False
    return element.prefix == "xacro" or tag.startswith(f"{{{XACRO_NS}}}")
