"""The diff of ``migrate --diff``: difflib's output on small inputs, linear on large ones."""

from __future__ import annotations

import difflib
import time

import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from txtool.transform.linediff import matching_blocks, unified, unified_ascii, unified_text

LINES = st.lists(st.sampled_from(["<a>\n", "</a>\n", "<b/>\n", "x\n", "\n"]), max_size=40)


@given(LINES, LINES)
def test_small_inputs_give_difflibs_diff(before: list[str], after: list[str]) -> None:
    expected = list(difflib.unified_diff(before, after, "a/f", "b/f"))
    assert list(unified(before, after, "a/f", "b/f")) == expected


def transmissions(count: int, plugin: bool) -> list[str]:
    lines = ["<robot>\n"]
    for i in range(count):
        lines += [f'<transmission name="t{i}">\n',
                  "<plugin>x</plugin>\n" if plugin else "<type>y</type>\n",
                  "<joint>\n", "</joint>\n", "</transmission>\n"]
    return [*lines, "</robot>\n"]


def patched(before: list[str], diff: list[str]) -> list[str]:
    out, at = [], 0
    for line in diff[2:]:
        if line.startswith("@@"):
            first, _, length = line.split()[1][1:].partition(",")
            start = int(first) if length == "0" else int(first) - 1
            out += before[at:start]
            at = start
        elif line[0] in " -":
            assert before[at] == line[1:]
            at += 1
            if line[0] == " ":
                out.append(line[1:])
        else:
            out.append(line[1:])
    return out + before[at:]


def test_repetitive_documents_are_diffed_in_linear_time_and_the_diff_applies() -> None:
    before, after = transmissions(20_000, False), transmissions(20_000, True)
    start = time.perf_counter()
    diff = list(unified(before, after, "a/f", "b/f"))
    assert time.perf_counter() - start < 10  # difflib takes minutes here
    assert sum(line.startswith("-<type>") for line in diff) == 20_000
    assert sum(line.startswith("+<plugin>") for line in diff) == 20_000
    assert not any(line.startswith(("-<joint>", "+<joint>")) for line in diff)
    assert patched(before, diff) == after


def test_matching_blocks_pair_equal_lines_in_order() -> None:
    before, after = transmissions(3_000, False), transmissions(3_000, True)
    blocks = matching_blocks(before, after)
    assert blocks[-1] == (len(before), len(after), 0)
    for (i, j, size), (k, m, _) in zip(blocks, blocks[1:], strict=False):
        assert before[i:i + size] == after[j:j + size]
        assert i + size <= k and j + size <= m
    assert sum(size for _, _, size in blocks) == len(before) - 3_000


ENDED = st.lists(st.sampled_from(["<a>\n", "</a>\r\n", "<b/>\r", "x", "\n", "y\x0c"]),
                 max_size=30)


@given(ENDED, ENDED)
def test_the_diff_text_marks_each_line_without_a_newline(before: list[str],
                                                        after: list[str]) -> None:
    expected = "".join(line if line.endswith("\n") else line + "\n\\ No newline at end of file\n"
                       for line in unified(before, after, "a/f", "b/f"))
    assert unified_text(before, after, "a/f", "b/f") == expected


def test_a_rewritten_stretch_of_a_long_document_is_matched_without_difflib() -> None:
    """No line of the gap is in both texts: nothing to match, whatever its size."""
    before = [f"<link name='l{i}'/>\n" for i in range(5_000)] + ["<type>y</type>\n"] * 5_000
    after = before[:5_000] + ["<plugin>x</plugin>\n"] * 6_000 + ["</robot>\n"]
    assert matching_blocks(before, after) == [(0, 0, 5_000), (10_000, 11_001, 0)]


def test_a_long_document_whose_first_line_changed_keeps_the_rest() -> None:
    rest = [f"<link name='l{i}'/>\n" for i in range(5_000)]
    assert matching_blocks(["<robot a='1'>\n", *rest], ["<robot a='2'>\n", *rest]) == [
        (1, 1, 5_000), (5_001, 5_001, 0)]


def lines_of(count: int, stem: str) -> list[str]:
    return [f"<{stem} n='{i % 7}'/>\n" for i in range(count)]


BIG = 4_100  # lines: 4,100 x 4,100 pairs are more than difflib matches whole


@given(st.integers(0, 30), st.integers(0, 30), st.sampled_from([0, 1, 2, 3, 4, 7, BIG - 3, BIG]),
       st.booleans(), st.booleans())
def test_large_documents_changed_in_one_run_are_diffed_from_the_bytes(
        removed: int, added: int, tail: int, final_newline: bool, shared_line: bool) -> None:
    """As the lines would be diffed, head, tail, a missing final newline and all."""
    common = lines_of(BIG, "link")
    before = common[:BIG - tail] + lines_of(removed, "type") + common[BIG - tail:]
    after = common[:BIG - tail] + lines_of(added, "plugin") + common[BIG - tail:]
    if shared_line and removed and added:
        after[BIG - tail] = before[BIG - tail]  # a line in common: the lines are diffed
    if not final_newline:
        before[-1], after[-1] = before[-1].rstrip("\n"), after[-1].rstrip("\n")
    a, b = "".join(before).encode(), "".join(after).encode()
    fast = unified_ascii(a, b, "a/f", "b/f")
    expected = unified_text(a.decode().splitlines(keepends=True),
                            b.decode().splitlines(keepends=True), "a/f", "b/f")
    if fast is not None:
        assert fast[0] + b"".join(fast[1]).decode("ascii") == expected
    elif a == b:
        assert expected == ""
    else:  # a line in common (a last line may differ from it by its newline only)
        assert shared_line and removed and added or not final_newline


@pytest.mark.parametrize(("a", "b"), [
    (b"x\n" * 3_000, b"x\n" * 3_000 + b"y\n"),  # small in lines: difflib diffs it whole
    ("\u00e9\n".encode() * BIG + b"a\n", "\u00e9\n".encode() * BIG + b"b\n"),  # not ASCII
    (b"x\r\n" * BIG + b"a\n", b"x\r\n" * BIG + b"b\n"),  # CR
])
def test_the_bytes_are_not_diffed_where_their_lines_may_not_be_cut_at_lf(a: bytes,
                                                                        b: bytes) -> None:
    assert unified_ascii(a, b, "a/f", "b/f") is None


LINE = st.sampled_from(["", "a", "ab", "<joint>", "<joint n='1'/>", "<joint n='2'/>",
                        "  <joint n='1'/>", "<plugin>x</plugin>", "abcdefgh", "abcdefghi"])


@given(st.lists(LINE, min_size=1, max_size=12), st.lists(LINE, min_size=1, max_size=60),
       st.booleans())
@example(["abcdefghi"], ["abcdefghi", *["<plugin>x</plugin>"] * 8], True)  # b's first line
@example(["ab"], [*["<plugin>x</plugin>"] * 8, "ab"], False)  # b's last, with no newline
@example(["ab"], [*["<plugin>x</plugin>"] * 8, "abcdefgh"], True)  # starts alike only
@example([""], [*["<plugin>x</plugin>"] * 8, ""], True)  # an empty line
def test_two_stretches_share_a_line_as_their_sets_of_lines_say(a_lines: list[str],
                                                               b_lines: list[str],
                                                               final_newline: bool) -> None:
    """Told apart by where their lines start (far fewer lines on one side) or by the lines
    themselves, the answer is the sets' (a last line may lack its newline)."""
    from txtool.transform.linediff import _line_count, _share_a_line

    a = ("\n".join(a_lines) + "\n").encode()
    b = ("\n".join(b_lines) + ("\n" if final_newline else "")).encode()
    around_b = b"<head/>\n" + b + (b"" if not final_newline else b"<tail/>\n")
    stretch_b = (around_b, 8, 8 + len(b))
    expected = bool(set(a.splitlines()) & set(b.splitlines()))
    assert _share_a_line((a, 0, len(a)), stretch_b, _line_count(*stretch_b)) == expected
