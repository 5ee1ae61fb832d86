"""The diff of ``migrate --diff``: difflib's output on small inputs, linear on large ones."""

from __future__ import annotations

import difflib
import time

from hypothesis import given
from hypothesis import strategies as st

from txtool.transform.linediff import matching_blocks, unified_text

LINES = st.lists(st.sampled_from(["<a>\n", "</a>\n", "<b/>\n", "x\n", "\n"]), max_size=40)


@given(LINES, LINES)
def test_small_inputs_give_difflibs_diff(before: list[str], after: list[str]) -> None:
    expected = "".join(difflib.unified_diff(before, after, "a/f", "b/f"))
    assert unified_text(before, after, "a/f", "b/f") == expected


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
    diff = unified_text(before, after, "a/f", "b/f").splitlines(keepends=True)
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
                       for line in difflib.unified_diff(before, after, "a/f", "b/f"))
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
