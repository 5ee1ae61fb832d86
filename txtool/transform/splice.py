"""The writer of conversions (``convert``, ``migrate --to``): a line splice.

A conversion changes a parsed tree; :func:`splice` turns the serialized change back into
bytes: only the lines that hold a changed node are written anew, every other line keeps its
original bytes. So the encoding (UTF-16 and UTF-32 too), the byte-order mark, the XML
declaration, line endings (LF, CRLF or CR), attribute order and quoting, ``<x></x>`` against
``<x/>``, character references, comments and blank lines stay as written wherever the
conversion did not change them. migrate's fixes are written as edits instead
(:mod:`.edits`, :mod:`.tree_edits`). Atomic writing of the result is
:func:`txtool.io.xmlio.write_atomic`.
"""
from __future__ import annotations

import codecs
import hashlib
import re

from lxml import etree

from txtool.io.encodings import detect_encoding, utf8_form
from txtool.io.xmlio import InputError, parse_bytes
from txtool.transform.linediff import matching_blocks

# An XML declaration after what may stand before the root element (whitespace, comments,
# processing instructions), each matched one at a time so that a long run cannot backtrack.
_LATE_DECLARATION = re.compile(
    rb"(\xef\xbb\xbf)?((?:[ \t\r\n]|<!--.*?-->|<\?(?!xml[ \t\r\n?])[^>]*\?>)*)"
    rb"(<\?xml[ \t\r\n][^>]*\?>[ \t]*(?:\r\n|\r|\n)?)", re.S)


def splice(original: bytes, baseline: bytes, changed: bytes) -> bytes:
    """``changed``, with the lines the change left alone taken verbatim from ``original``.

    ``baseline`` is ``original`` parsed and serialized unchanged and ``changed`` the changed
    tree serialized the same way, so ``baseline`` differs from ``original`` only in formatting
    (quotes, spaces and line breaks inside tags, character references) and from ``changed``
    only by the change. ``original`` and ``baseline`` are cut into the same blocks, each
    ending with the line where a node (element start tag, comment) ends; a block whose lines
    the change did not touch is copied from ``original``, the rest comes from ``changed``
    with the line ending of ``original``. When the result would not parse to the changed
    document, the serialized document is returned instead. UTF-16 and UTF-32 documents are
    spliced as UTF-8 (see :func:`txtool.io.encodings.utf8_form`) and stored back as they were.
    """
    if changed == baseline:
        return original
    stored = detect_encoding(original)
    if stored.wide:
        texts = (utf8_form(original), utf8_form(baseline), utf8_form(changed))
        return stored.from_utf8(splice(*texts))
    if baseline == original:
        return changed
    for fine in (True, False):
        try:
            merged = _merge(original, baseline, changed, fine=fine)
        except InputError:
            return changed
        if _same_document(merged, changed):
            return without_late_declaration(_keep_ends(original, merged))
    return changed


def _merge(original: bytes, baseline: bytes, changed: bytes, *, fine: bool) -> bytes:
    """Each line of ``changed``, or the original text of the lines it stands for.

    A block the change left whole is copied as written; with ``fine``, so is every kept line
    of a changed block that has as many lines in the original as in the baseline (its lines
    then correspond one to one: the end tags before a changed node keep their text).
    """
    o, b, n = (text.splitlines(keepends=True) for text in (original, baseline, changed))
    cuts = _cuts(_node_lines(_lf(o), "<original>"), _node_lines(_lf(b), "<baseline>"))
    cuts.append((len(b), len(o)))
    in_n = _matches([_key(line) for line in b], [_key(line) for line in n])
    written: dict[int, list[bytes]] = {}
    pb = po = 0
    for eb, eo in cuts:
        if not fine:
            _keep_whole(range(pb, eb), o[po:eo], in_n, written)
        else:
            top, bottom = _alike_ends(b[pb:eb], o[po:eo])
            for k in [*range(top), *range(eb - pb - bottom, eb - pb)]:
                if pb + k in in_n:  # the block's first and last lines that read alike
                    written[in_n[pb + k]] = [o[po + k] if k < top else o[eo - (eb - pb - k)]]
            _keep_whole(range(pb + top, eb - bottom), o[po + top:eo - bottom], in_n, written)
        pb, po = eb, eo
    newline = _newline(o)
    out: list[bytes] = []
    for index, line in enumerate(n):
        out += written[index] if index in written else _lines([line], newline)
    return b"".join(out)


def _keep_whole(block: range, original: list[bytes], in_n: dict[int, int],
                written: dict[int, list[bytes]]) -> None:
    """The original lines of a block that the change left whole."""
    if block and _untouched(block, in_n):
        written.update((in_n[i], []) for i in block)
        written[in_n[block[0]]] = original


def _alike_ends(baseline: list[bytes], original: list[bytes]) -> tuple[int, int]:
    """How many lines at the top and at the bottom of a block read alike in both texts (the
    same but for quotes and spacing: the same nodes, line for line)."""
    if len(baseline) == len(original):
        return len(baseline), 0
    most = min(len(baseline), len(original))
    top = 0
    while top < most and _alike(baseline[top], original[top]):
        top += 1
    bottom = 0
    while bottom < most - top and _alike(baseline[-1 - bottom], original[-1 - bottom]):
        bottom += 1
    return top, bottom


def _alike(first: bytes, second: bytes) -> bool:
    def plain(line: bytes) -> bytes:
        return re.sub(rb"\s+", b" ", line.replace(b"'", b'"')).strip()

    return plain(first) == plain(second)


def _lf(lines: list[bytes]) -> bytes:
    """The text with every line ending as LF: libxml2 counts no line at a bare CR."""
    return b"".join(_key(line) + b"\n" if line != _key(line) else line for line in lines)


def _cuts(original: list[int | None], baseline: list[int | None]) -> list[tuple[int, int]]:
    """(baseline line, original line) pairs, both increasing, where the same node ends."""
    cuts: list[tuple[int, int]] = []
    if len(baseline) != len(original):
        raise InputError("the baseline is not a serialization of the original")
    for b, o in zip(baseline, original, strict=True):
        if b is None or o is None:
            continue
        if cuts and b == cuts[-1][0]:
            cuts[-1] = (b, max(o, cuts[-1][1]))  # a break inside a start tag, not in baseline
        elif not cuts or (b > cuts[-1][0] and o > cuts[-1][1]):
            cuts.append((b, o))
    return cuts


def _node_lines(text: bytes, name: str) -> list[int | None]:
    """The line of each node of ``text`` in document order (one tree alive at a time)."""
    root = parse_bytes(text, name, limit=None).getroot()
    before = list(root.itersiblings(preceding=True))[::-1]
    return [node.sourceline for node in (*before, *root.iter(), *root.itersiblings())]


def _untouched(block: range, in_n: dict[int, int]) -> bool:
    """Whether the change kept every line of ``block`` and put nothing between them."""
    if any(i not in in_n for i in block):
        return False
    return in_n[block[-1]] - in_n[block[0]] == len(block) - 1


def _key(line: bytes) -> bytes:
    return line.rstrip(b"\r\n")


def _matches(a: list[bytes], b: list[bytes]) -> dict[int, int]:
    """Index in ``b`` of each line of ``a`` that the longest matching alignment pairs.

    A line inside a ``<transmission>`` or ``<ros2_control>`` element, which conversions
    rewrite, pairs only with a line inside the element of the same kind and name, so that a
    ``<joint name="j">`` declared in a new ``<ros2_control>`` block cannot hold a line of the
    rest of the document away from its copy. The alignment matches the longest run first and
    so may still pair a run of repeated lines (a ``<link/>`` between scattered transmissions)
    with the wrong copies, leaving one of the rest unpaired although it could keep its text;
    then the reversed texts are matched too, and the alignment that pairs more lines of the
    rest wins.
    """
    keys_a, keys_b = _scoped(a), _scoped(b)
    forward = _pairs(matching_blocks(keys_a, keys_b, autojunk=False))
    paired_b = set(forward.values())
    left_a = {keys_a[i] for i in range(len(a)) if i not in forward and keys_a[i] is a[i]}
    if not left_a.intersection(keys_b[j] for j in range(len(b))
                               if j not in paired_b and keys_b[j] is b[j]):
        return forward
    last_a, last_b = len(a) - 1, len(b) - 1
    backward = {last_a - i: last_b - j for i, j in
                _pairs(matching_blocks(keys_a[::-1], keys_b[::-1], autojunk=False)).items()}

    def rest(pairs: dict[int, int]) -> int:
        return sum(1 for i in pairs if keys_a[i] is a[i])

    return backward if rest(backward) > rest(forward) else forward


_SCOPE = re.compile(rb"<((?:[\w.-]+:)?(?:transmission|ros2_control))(?=[\s/>])([^>]*)>")
_SCOPE_END = re.compile(rb"</(?:[\w.-]+:)?(?:transmission|ros2_control)\s*>")
_NAME = re.compile(rb"""\bname\s*=\s*(?:"([^"]*)"|'([^']*)')""")


def _scoped(lines: list[bytes]) -> list[bytes]:
    """Each line as the key it is matched by: a line inside a ``<transmission>`` or
    ``<ros2_control>`` is prefixed by that element's kind and name (the same object is
    returned for every other line)."""
    keys, scopes = [], []
    for line in lines:
        opened = _SCOPE.search(line)
        if opened is not None:
            name = _NAME.search(opened.group(2))
            label = name.group(1) or name.group(2) or b"" if name else b""
            scopes.append(b"\0" + opened.group(1) + b" " + label + b"\0")
        keys.append(scopes[-1] + line if scopes else line)
        if scopes and (opened is not None and opened.group(2).endswith(b"/")
                       or _SCOPE_END.search(line)):
            scopes.pop()
    return keys


def _pairs(blocks: list[tuple[int, int, int]]) -> dict[int, int]:
    pairs: dict[int, int] = {}
    for i, j, size in blocks:
        for k in range(size):
            pairs[i + k] = j + k
    return pairs


def _lines(lines: list[bytes], newline: bytes) -> list[bytes]:
    return [_key(line) + newline if line != _key(line) else line for line in lines]


def _newline(lines: list[bytes]) -> bytes:
    """The line ending most lines of the original end with (LF when none does)."""
    counts = {b"\r\n": 0, b"\r": 0, b"\n": 0}
    for line in lines:
        ending = line[len(_key(line)):]
        if ending in counts:
            counts[ending] += 1
    best = max(counts, key=lambda ending: counts[ending])
    return best if counts[best] else b"\n"


def _keep_ends(original: bytes, merged: bytes) -> bytes:
    """A UTF-8 byte-order mark and a final line ending stay even when the first or the last
    line was rewritten."""
    if original.startswith(codecs.BOM_UTF8) and not merged.startswith(codecs.BOM_UTF8):
        merged = codecs.BOM_UTF8 + merged
    last = original.splitlines(keepends=True)[-1:]
    ending = last[0][len(_key(last[0])):] if last else b""
    if ending and _key(merged) == merged:
        merged += ending
    return merged


def without_late_declaration(data: bytes) -> bytes:
    """``data`` with its XML declaration first, or without it. A declaration after anything
    but a byte-order mark (some published URDFs put a licence comment, a blank line or spaces
    first; one fuzzed a processing instruction) makes the document malformed for strict
    parsers (expat, libxml2); txtool reads it, but never writes it: after whitespace alone the
    whitespace goes (the declaration may name the encoding), after anything else the
    declaration. UTF-16 and UTF-32 text is worked on in its UTF-8 form."""
    stored = detect_encoding(data)
    if stored.wide:
        text = utf8_form(data)
        fixed = without_late_declaration(text)
        return data if fixed == text else stored.from_utf8(fixed)
    late = _LATE_DECLARATION.match(data)
    if late is None or not late.group(2):
        return data
    bom, head = late.group(1) or b"", late.group(2)
    if not head.strip(b" \t\r\n"):
        return bom + data[late.start(3):]
    return data[:late.start(3)] + data[late.end(3):]


def _same_document(a: bytes, b: bytes) -> bool:
    try:
        first = _canonical(a, "<merged>")
        return first == _canonical(b, "<changed>")
    except InputError:
        return False


def _canonical(data: bytes, name: str) -> bytes:
    """A digest of the canonical form (each tree and its text freed before the next)."""
    tree = parse_bytes(data, name, limit=None)
    return hashlib.sha256(etree.tostring(tree, method="c14n")).digest()
