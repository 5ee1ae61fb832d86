"""Line matching and unified diffs that stay fast on long, repetitive documents.

:class:`difflib.SequenceMatcher` searches the longest matching run over the whole of both
sequences again for every gap it recurses into: quadratic when thousands of transmissions
repeat the same lines (``</joint>``, ``<type>...</type>``). Here a document is first cut at
the lines that occur exactly once in each text and in the same order (the anchors of a
patience diff: a transmission's ``<transmission name=...>`` line is one), and
:class:`~difflib.SequenceMatcher` matches only the short gaps between anchors. Documents up
to about 4,000 lines (every robot of the test corpus) go to :class:`~difflib.SequenceMatcher`
whole, so their result is exactly difflib's; a repetitive one of that size costs it about a
second at worst.
"""

from __future__ import annotations

import bisect
import difflib
from collections import Counter
from collections.abc import Hashable, Iterator, Sequence

WHOLE = 16_000_000  # line pairs (4,000 lines each) that SequenceMatcher matches in one piece


def matching_blocks(a: Sequence[Hashable], b: Sequence[Hashable], *,
                    autojunk: bool = True) -> list[tuple[int, int, int]]:
    """``(i, j, size)`` runs where ``a[i:i+size] == b[j:j+size]``, increasing in both, ending
    with ``(len(a), len(b), 0)`` like :meth:`difflib.SequenceMatcher.get_matching_blocks`."""
    blocks: list[tuple[int, int, int]] = []
    _match(a, b, 0, len(a), 0, len(b), autojunk, blocks)
    merged: list[tuple[int, int, int]] = []
    for i, j, size in blocks:
        if size and merged and merged[-1][0] + merged[-1][2] == i \
                and merged[-1][1] + merged[-1][2] == j:
            merged[-1] = (merged[-1][0], merged[-1][1], merged[-1][2] + size)
        elif size:
            merged.append((i, j, size))
    merged.append((len(a), len(b), 0))
    return merged


def _match(a: Sequence[Hashable], b: Sequence[Hashable], a0: int, a1: int, b0: int, b1: int,
           autojunk: bool, out: list[tuple[int, int, int]]) -> None:
    if (a1 - a0) * (b1 - b0) <= WHOLE:
        _difflib(a, b, a0, a1, b0, b1, autojunk, out)
        return
    head = 0
    while a0 + head < a1 and b0 + head < b1 and a[a0 + head] == b[b0 + head]:
        head += 1
    if head:
        out.append((a0, b0, head))
        a0, b0 = a0 + head, b0 + head
    tail = 0
    while a0 < a1 - tail and b0 < b1 - tail and a[a1 - 1 - tail] == b[b1 - 1 - tail]:
        tail += 1
    a1, b1 = a1 - tail, b1 - tail
    anchors = _anchors(a, b, a0, a1, b0, b1)
    if anchors:
        for i, j in anchors:
            _match(a, b, a0, i, b0, j, autojunk, out)
            out.append((i, j, 1))
            a0, b0 = i + 1, j + 1
        _match(a, b, a0, a1, b0, b1, autojunk, out)
    else:
        _difflib(a, b, a0, a1, b0, b1, autojunk, out)
    if tail:
        out.append((a1, b1, tail))


def _difflib(a: Sequence[Hashable], b: Sequence[Hashable], a0: int, a1: int, b0: int, b1: int,
             autojunk: bool, out: list[tuple[int, int, int]]) -> None:
    """:class:`~difflib.SequenceMatcher`'s blocks of the two ranges; none when they have no
    line in common (a gap where every line was rewritten, which difflib would index whole)."""
    if a0 >= a1 or b0 >= b1 or set(a[a0:a1]).isdisjoint(b[b0:b1]):
        return
    matcher = difflib.SequenceMatcher(None, a[a0:a1], b[b0:b1], autojunk=autojunk)
    out.extend((a0 + i, b0 + j, size) for i, j, size in matcher.get_matching_blocks())


def _anchors(a: Sequence[Hashable], b: Sequence[Hashable], a0: int, a1: int, b0: int,
             b1: int) -> list[tuple[int, int]]:
    """The longest increasing chain of lines unique in both ranges (patience sorting)."""
    in_a, in_b = Counter(a[a0:a1]), Counter(b[b0:b1])
    unique = {line for line, count in in_a.items() if count == 1 and in_b.get(line) == 1}
    if not unique:
        return []
    where_a = {a[i]: i for i in range(a0, a1) if a[i] in unique}
    pairs = sorted((where_a[b[j]], j) for j in range(b0, b1) if b[j] in unique)
    tops: list[int] = []  # b index at the top of each pile
    piles: list[int] = []  # index into pairs at the top of each pile
    back: list[int] = []
    for k, (_, j) in enumerate(pairs):
        pile = bisect.bisect_left(tops, j)
        back.append(piles[pile - 1] if pile else -1)
        if pile == len(tops):
            tops.append(j)
            piles.append(k)
        else:
            tops[pile], piles[pile] = j, k
    chain = []
    k = piles[-1] if piles else -1
    while k >= 0:
        chain.append(pairs[k])
        k = back[k]
    return chain[::-1]


def unified(a: Sequence[str], b: Sequence[str], fromfile: str, tofile: str,
            context: int = 3) -> Iterator[str]:
    """The lines of :func:`difflib.unified_diff` (no dates), from :func:`matching_blocks`."""
    for prefix, lines in _runs(a, b, fromfile, tofile, context):
        yield from (prefix + line for line in lines)


NO_NEWLINE = "\n\\ No newline at end of file\n"


def unified_text(a: Sequence[str], b: Sequence[str], fromfile: str, tofile: str,
                 context: int = 3) -> str:
    """The lines of :func:`unified` as one text, each line that does not end with a newline
    followed by a newline and ``diff``'s ``\\ No newline at end of file``."""
    out = []
    for prefix, lines in _runs(a, b, fromfile, tofile, context):
        run = prefix.join(lines)
        if run.count("\n") == len(lines):  # every line ends with one (and holds no other)
            out += (prefix, run)
            continue
        out += (prefix + line if line.endswith("\n") else prefix + line + NO_NEWLINE
                for line in lines)
    return "".join(out)


def _runs(a: Sequence[str], b: Sequence[str], fromfile: str, tofile: str,
          context: int) -> Iterator[tuple[str, Sequence[str]]]:
    """:func:`unified`'s lines as runs: (prefix, the lines it goes before)."""
    matcher = _Matcher(a, b)
    started = False
    for group in matcher.get_grouped_opcodes(context):
        if not started:
            started = True
            yield "", (f"--- {fromfile}\n", f"+++ {tofile}\n")
        first, last = group[0], group[-1]
        yield "", (f"@@ -{_range(first[1], last[2])} +{_range(first[3], last[4])} @@\n",)
        for tag, i1, i2, j1, j2 in group:
            if tag == "equal":
                yield " ", a[i1:i2]
                continue
            if tag in {"replace", "delete"}:
                yield "-", a[i1:i2]
            if tag in {"replace", "insert"}:
                yield "+", b[j1:j2]


class _Matcher(difflib.SequenceMatcher):
    """A :class:`~difflib.SequenceMatcher` whose matching blocks come from the anchored
    search (its opcodes and groups are then computed as difflib computes them)."""

    def __init__(self, a: Sequence[str], b: Sequence[str]) -> None:
        super().__init__(None, (), (), autojunk=True)
        # Set directly: difflib's index of ``b`` (set_seq2) serves only its own search.
        self.a, self.b = a, b

    def get_matching_blocks(self) -> list[difflib.Match]:  # type: ignore[override]
        if self.matching_blocks is None:
            self.matching_blocks = [difflib.Match(*block)
                                    for block in matching_blocks(self.a, self.b)]
        return self.matching_blocks


def _range(start: int, stop: int) -> str:
    """A unified diff's ``start,length`` (as :func:`difflib.unified_diff` writes it)."""
    beginning = start + 1
    length = stop - start
    if length == 1:
        return f"{beginning}"
    if not length:
        beginning -= 1
    return f"{beginning},{length}"


_CHUNK = 1 << 16


def unified_ascii(a: bytes, b: bytes, fromfile: str, tofile: str
                  ) -> tuple[str, list[bytes]] | None:
    """:func:`unified_text` of the lines of two large XML documents stored in ASCII, as its
    header and the pieces of the rest in ASCII (to join), where
    they differ in one run of lines that has no line in common: the anchored search then
    keeps the common head and tail and nothing between, and the diff is written from the
    bytes without a Python object per line, a piece at a time (no copy of either document).
    None where that does not hold (the caller diffs the lines) or ``a == b``.

    Both must be well-formed XML, which holds no control character but tab, LF and CR: then
    only LF and CR end lines (as :meth:`str.splitlines` cuts them), and with no CR, LF alone.
    """
    if a == b or not (a.isascii() and b.isascii()) or b"\r" in a or b"\r" in b:
        return None
    cut = a.rfind(b"\n", 0, _common_prefix(a, b)) + 1
    tail_bytes, tail = _common_tail(a, b, cut)
    middle_a, middle_b = (a, cut, len(a) - tail_bytes), (b, cut, len(b) - tail_bytes)
    head = a.count(b"\n", 0, cut)
    changed_b = _line_count(*middle_b)
    lines_a = head + _line_count(*middle_a) + tail
    lines_b = head + changed_b + tail
    if lines_a * lines_b <= WHOLE:
        return None  # matched whole by difflib
    # Without their ends, lines that differ only there (a last line without one) count as
    # common too: then the lines are diffed.
    if _share_a_line(middle_a, middle_b, changed_b):
        return None
    end_a, end_b = lines_a - tail, lines_b - tail
    first = max(0, head - 3)
    before = (a, _line_start(a, cut, head - first), cut)
    after = (a, len(a) - tail_bytes, _line_end(a, len(a) - tail_bytes, min(tail, 3)))
    header = (f"--- {fromfile}\n+++ {tofile}\n"
              f"@@ -{_range(first, min(end_a + 3, lines_a))} "
              f"+{_range(first, min(end_b + 3, lines_b))} @@\n")
    parts: list[bytes] = []
    for prefix, text in ((b" ", before), (b"-", middle_a), (b"+", middle_b), (b" ", after)):
        parts += _prefixed(prefix, *text)
    return header, parts


Stretch = tuple[bytes, int, int]  # a text and the range of it meant


def _line_count(data: bytes, start: int, end: int) -> int:
    """The lines of ``data[start:end]``."""
    return data.count(b"\n", start, end) + (
        0 if end == start or data[end - 1] == 0x0A else 1)


_PIECE = 1 << 16


_START = 8  # bytes that a line starts with, looked for in the other text
_FEW_STARTS = 2  # each is a scan of the other text; splitting it costs about three


def _share_a_line(a: Stretch, b: Stretch, lines_b: int) -> bool:
    """Whether two stretches whose lines end with "\n" have a line in common (without its
    end), their lines split a piece at a time: no list of every line, which for a large
    document costs more memory than the document. The lines of ``b`` (``lines_b`` of them)
    are split only where a few distinct starts of the far fewer different lines of ``a``
    cannot show that none of them begins a line of ``b`` (a line in common would)."""
    seen: set[bytes] = set()
    for piece in _pieces(*a):
        seen.update(piece.splitlines())
    if not seen:
        return False
    if len(seen) * 4 <= lines_b:
        starts: set[bytes] = set()
        for line in seen:
            starts.add(line[:_START])
            if len(starts) > _FEW_STARTS:
                break
        else:
            if not any(_begins_a_line(b, start) for start in starts):
                return False
    return any(not seen.isdisjoint(piece.splitlines()) for piece in _pieces(*b))


def _begins_a_line(stretch: Stretch, start: bytes) -> bool:
    """Whether a line of the stretch (whole lines) begins with ``start``."""
    text, begin, end = stretch
    return text.startswith(start, begin, end) or text.find(b"\n" + start, begin, end) >= 0


def _pieces(text: bytes, start: int, end: int) -> Iterator[bytes]:
    """``text[start:end]`` in pieces of whole lines, of about :data:`_PIECE` bytes each."""
    while start < end:
        stop = min(text.find(b"\n", start + _PIECE, end) + 1 or end, end)
        yield text[start:stop]
        start = stop


def _common_prefix(a: bytes, b: bytes) -> int:
    """The length of the longest common prefix of ``a`` and ``b``."""
    size = min(len(a), len(b))
    at = 0
    while at < size and a[at:at + _CHUNK] == b[at:at + _CHUNK]:
        at += _CHUNK
    low, high = at, min(at + _CHUNK, size)  # the answer lies in [low, high]
    while low < high:
        middle = (low + high + 1) // 2
        if a[low:middle] == b[low:middle]:
            low = middle
        else:
            high = middle - 1
    return low


def _common_suffix(a: bytes, b: bytes, limit: int) -> int:
    """The length of the longest common suffix of ``a`` and ``b``, at most ``limit``."""
    at = 0  # bytes matched from the end
    while at < limit:
        size = min(_CHUNK, limit - at)
        if a[len(a) - at - size:len(a) - at] != b[len(b) - at - size:len(b) - at]:
            break
        at += size
    else:
        return limit
    low, high = at, min(at + _CHUNK, limit)  # the answer lies in [low, high]
    while low < high:
        middle = (low + high + 1) // 2
        if a[len(a) - middle:len(a) - low] == b[len(b) - middle:len(b) - low]:
            low = middle
        else:
            high = middle - 1
    return low


def _common_tail(a: bytes, b: bytes, cut: int) -> tuple[int, int]:
    """The bytes and lines of the longest run of whole lines that ``a`` and ``b`` end with,
    after their common head (both start a line at ``cut``)."""
    room = min(len(a), len(b)) - cut
    same = _common_suffix(a, b, room)
    tail = a[len(a) - same:]
    if same == room:  # one rest ends the other: whole if the other starts a line there
        longer = b if len(a) == cut + room else a
        if longer[len(longer) - same - 1:len(longer) - same] == b"\n":
            return same, _line_count(tail, 0, len(tail))
    start = tail.find(b"\n") + 1
    if not start:
        return 0, 0
    return same - start, _line_count(tail, start, len(tail))


def _line_start(data: bytes, at: int, lines: int) -> int:
    """Where the line ``lines`` lines before the one starting at ``at`` starts."""
    for _ in range(lines):
        at = data.rfind(b"\n", 0, at - 1) + 1
    return at


def _line_end(data: bytes, at: int, lines: int) -> int:
    """Where ``lines`` lines after ``at`` (a line start) end."""
    for _ in range(lines):
        found = data.find(b"\n", at)
        at = len(data) if found < 0 else found + 1
    return at


def _prefixed(prefix: bytes, text: bytes, start: int, end: int) -> list[bytes]:
    """Each line of ``text[start:end]`` after ``prefix``, a last line without "\\n" marked as
    diff marks it, as texts to join: a piece at a time, each piece's last "\\n" followed by
    the next one's first prefix."""
    if start >= end:
        return []
    parts = [prefix]
    newline = b"\n" + prefix
    parts += (piece.replace(b"\n", newline) for piece in _pieces(text, start, end))
    if text[end - 1] == 0x0A:
        parts[-1] = parts[-1][:-len(prefix)]  # no prefix after the last "\n"
    else:
        parts.append(NO_NEWLINE.encode("ascii"))
    return parts
