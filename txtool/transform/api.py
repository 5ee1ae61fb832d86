"""What the library's :func:`txtool.convert` returns (kept here so validate never builds it)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from txtool.io.xmlio import Source
    from txtool.model.core import Dialect

__all__ = ["Conversion", "converted"]


@dataclass(frozen=True)
class Conversion:
    """What :func:`convert` made: the document's new ``text`` (``data`` in its own encoding),
    what could not be carried over or what the target's loaders would refuse in it
    (``losses``: the CLI exits 1 on them unless told to allow them) and what a reader should
    know (``notes``)."""

    text: str
    data: bytes
    losses: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    converted: int = 0

    @property
    def lossless(self) -> bool:
        return not self.losses


def converted(source: Source, to: Dialect, ros_distro: str | None = None) -> Conversion:
    """``source`` converted as ``txtool convert`` does, what is written checked for the
    target's loaders (:mod:`txtool.lint.target_check`); ``ValueError`` for a ``ros_distro``
    of the other ROS generation."""
    from txtool.io.encodings import document_text
    from txtool.lint.target_check import judge_converted, target_distro
    from txtool.transform.convert import convert_source

    distro = target_distro(to, ros_distro)
    done = convert_source(source, to)  # not consumed: the input is still there to compare
    done.edits = None  # (not returned: released before the check lints what is written)
    judged = judge_converted(done.data, source, to, distro=distro, reload=lambda: source)
    return Conversion(
        text=document_text(done.data), data=done.data,
        losses=[*done.losses, *judged.losses],
        notes=[*done.notes, *done.warnings, *judged.warnings],
        converted=done.converted,
    )
