"""A transmission on its way: the old element and its conversion, as the placer moves it."""

from __future__ import annotations

from lxml import etree

from txtool.model.core import Transmission

Carried = dict[tuple[str, str | None], list[etree._Element]]


class Move:
    """``old`` and its conversion ``new``; ``carried``: children of ``old`` (by owner) that
    go along as written."""

    __slots__ = ("old", "new", "carried")

    def __init__(self, old: etree._Element, new: Transmission,
                 carried: Carried | None = None) -> None:
        self.old = old
        self.new = new
        self.carried = carried
