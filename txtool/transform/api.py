"""What the library's :func:`txtool.convert` returns (kept here so validate never builds it)."""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["Conversion"]


@dataclass(frozen=True)
class Conversion:
    """What :func:`convert` made: the document's new ``text`` (``data`` in its own encoding),
    what could not be carried over (``losses``: the CLI exits 1 on them unless told to allow
    them) and what a reader should know (``notes``)."""

    text: str
    data: bytes
    losses: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    converted: int = 0

    @property
    def lossless(self) -> bool:
        return not self.losses
