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


NO_NEWLINE = "\n\\ No newline at end of file\n"


def unified_text(a: Sequence[str], b: Sequence[str], fromfile: str, tofile: str,
                 context: int = 3) -> str:
    """The lines of :func:`difflib.unified_diff` (no dates), from :func:`matching_blocks`, as
    one text, each line that does not end with a newline followed by a newline and
    ``diff``'s ``\\ No newline at end of file``."""
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
    """The diff's lines as runs: (prefix, the lines it goes before)."""
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
