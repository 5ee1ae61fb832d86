"""A transmission on its way: the old element and its conversion, as the placer moves it."""

from __future__ import annotations

from lxml import etree

from txtool.model.core import Dialect, Transmission
from txtool.transform.repeated.renamings import Follower, Renaming

Carried = dict[tuple[str, str | None], list[etree._Element]]
Joints = list[tuple[str, tuple[str, ...], tuple[str, ...]]]  # names and interfaces


class Move:
    """``old`` and its conversion ``new`` (a follower's is built only when it is read);
    ``carried``: children of ``old`` (by owner) that go along as written."""

    __slots__ = ("old", "_new", "carried", "_renaming", "follower")

    def __init__(self, old: etree._Element, new: Transmission | None,
                 carried: Carried | None = None, renaming: Renaming | None = None,
                 follower: Follower | None = None) -> None:
        self.old = old
        self._new = new
        self.carried = carried
        self._renaming = renaming
        self.follower = follower

    @property
    def renaming(self) -> Renaming | None:
        """The old element's, when it was keyed (:mod:`txtool.transform.repeated.renamings`)."""
        if self._renaming is None and self.follower is not None:
            self._renaming = self.follower.renaming()
        return self._renaming

    @property
    def new(self) -> Transmission:
        if self._new is None:
            assert self.follower is not None
            self._new = self.follower.translated()
        return self._new

    @new.setter
    def new(self, value: Transmission) -> None:
        self._new = value

    @property
    def dialect(self) -> Dialect:
        if self._new is None:
            assert self.follower is not None
            return self.follower.record.dialect
        return self._new.dialect

    def joints(self) -> Joints:
        if self._new is None:
            assert self.follower is not None
            return self.follower.record.joints_for(self.follower.names)
        return [(j.name, j.interfaces, j.state_interfaces) for j in self._new.joints]
