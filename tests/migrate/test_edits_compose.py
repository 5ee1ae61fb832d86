"""Two rounds of edits as one: the edits of the original that make what the first round and then
the second make, merged where they meet, and no byte that neither round touched inside them."""

from __future__ import annotations

from itertools import pairwise

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from txtool.transform.edits.core import Edit, apply_edits, compose


def test_disjoint_edits_stay_apart_at_their_places_in_the_original() -> None:
    original = b"one two three"
    first = [Edit(0, 3, b"1")]  # b"1 two three"
    second = [Edit(6, 11, b"3")]  # b"1 two 3"
    assert compose(first, second, original) == [Edit(0, 3, b"1"), Edit(8, 13, b"3")]


def test_an_edit_inside_inserted_content_edits_the_insertion() -> None:
    first = [Edit.insertion(1, b"XYZ")]  # b"aXYZb"
    second = [Edit(2, 3, b"-")]  # b"aX-Zb"
    assert compose(first, second, b"ab") == [Edit.insertion(1, b"X-Z")]


def test_an_edit_across_the_end_of_a_first_edit_takes_both_ranges() -> None:
    first = [Edit(1, 3, b"XY")]  # b"aXYdef"
    second = [Edit(2, 4, b"*")]  # b"aX*ef": Y and d go
    assert compose(first, second, b"abcdef") == [Edit(1, 4, b"X*")]


def test_insertions_at_the_boundaries_of_a_first_edit_join_it() -> None:
    first = [Edit(1, 2, b"B")]  # b"aBc"
    second = [Edit.insertion(2, b">"), Edit.insertion(1, b"<")]  # b"a<B>c"
    assert compose(first, second, b"abc") == [Edit(1, 2, b"<B>")]


def test_an_insertion_where_the_first_round_deleted_replaces_what_it_deleted() -> None:
    first = [Edit.deletion(1, 2)]  # b"ac"
    second = [Edit.insertion(1, b"X")]  # b"aXc"
    assert compose(first, second, b"abc") == [Edit(1, 2, b"X")]


def test_edits_side_by_side_become_one() -> None:
    first = [Edit(1, 2, b"B")]  # b"aBcd"
    second = [Edit(2, 3, b"C")]  # b"aBCd"
    assert compose(first, second, b"abcd") == [Edit(1, 3, b"BC")]


def test_insertions_at_one_offset_keep_the_order_given() -> None:
    first = [Edit.insertion(1, b"1"), Edit.insertion(1, b"2")]  # b"a12b"
    assert compose(first, [Edit.insertion(3, b"3"), Edit.insertion(3, b"4")], b"ab") == [
        Edit.insertion(1, b"1234")]
    assert compose(first, [Edit.insertion(3, b"4"), Edit.insertion(3, b"3")], b"ab") == [
        Edit.insertion(1, b"1243")]
    # Before what the first round inserted there, not after it.
    assert compose(first, [Edit.insertion(1, b"0")], b"ab") == [Edit.insertion(1, b"012")]


def test_with_one_round_empty_the_other_is_the_result_in_order() -> None:
    edits = [Edit(4, 5, b"E"), Edit.insertion(2, b"+"), Edit(0, 1, b"A")]
    in_order = [Edit(0, 1, b"A"), Edit.insertion(2, b"+"), Edit(4, 5, b"E")]
    assert compose([], edits, b"abcdef") == in_order
    assert compose(edits, [], b"abcdef") == in_order
    assert compose([], [], b"abcdef") == []


def test_overlapping_edits_or_edits_past_the_end_are_refused() -> None:
    with pytest.raises(ValueError, match="overlap at byte 1"):
        compose([Edit(0, 2, b"x"), Edit(1, 3)], [], b"abc")
    with pytest.raises(ValueError, match="overlap at byte 2"):
        compose([], [Edit(0, 3), Edit.insertion(2, b"x")], b"abc")
    with pytest.raises(ValueError, match="past the end"):
        compose([Edit.deletion(0, 1)], [Edit(1, 3, b"x")], b"abc")


@st.composite
def edits_of(draw: st.DrawFn, document: bytes) -> list[Edit]:
    """Edits of ``document`` that do not overlap (insertions among them, several at one offset
    too), in any order."""
    drawn = draw(st.lists(st.tuples(st.integers(0, len(document)), st.integers(0, 3),
                                    st.lists(st.sampled_from(b"xyz"), max_size=3).map(bytes)),
                          max_size=6))
    edits: list[Edit] = []
    taken = 0
    for start, length, content in sorted(drawn, key=lambda row: row[0]):
        if start < taken:
            continue  # inside the last one (an insertion or another edit may follow at its end)
        end = min(start + length, len(document))
        edits.append(Edit(start, end, content))
        taken = end
    return draw(st.permutations(edits))


def covers(edits: list[Edit], at: int) -> bool:
    return any(edit.start <= at < edit.end for edit in edits)


@settings(max_examples=200, deadline=None)
@given(st.data(), st.lists(st.sampled_from(b"abc"), max_size=12).map(bytes))
def test_the_composition_makes_the_final_document_and_leaves_untouched_bytes_outside(
        data: st.DataObject, original: bytes) -> None:
    first = data.draw(edits_of(original), label="first")
    middle = apply_edits(original, first)
    second = data.draw(edits_of(middle), label="second")
    final = apply_edits(middle, second)

    composed = compose(first, second, original)

    assert apply_edits(original, composed) == final
    # In order, and no two of them overlap or touch (edits that meet are merged).
    assert all(one.end < other.start for one, other in pairwise(composed))
    # Where each byte outside the first round's edits is in middle: after every edit of first
    # that ends at or before it (insertions at its offset go before it).
    for at in range(len(original)):
        if covers(first, at):
            continue
        image = at + sum(len(edit.content) - (edit.end - edit.start)
                         for edit in first if edit.end <= at)
        assert middle[image] == original[at]
        if not covers(second, image):
            assert not covers(composed, at), (at, composed)
