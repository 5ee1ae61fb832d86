"""The readers part of ``txtool show --effective``: which programs read the file, and why.

The values each loader binds are :mod:`txtool.views.effective`'s; this says whose loaders
those are for this file (:mod:`txtool.model.readers`), and which transmissions none of them
reads.
"""

from __future__ import annotations

import textwrap
from typing import Any

from lxml import etree

from txtool.model.readers import Assumption, placement_of

WIDTH = 100  # the effective view's width


def unread_names(assumption: Assumption, elements: list[etree._Element]) -> list[str]:
    """The names of the transmissions (``elements``) none of the readers reads."""
    if not assumption.decided:
        return []
    return [element.get("name", "") for element in elements
            if not assumption.reads(placement_of(element))]


def readers_text(assumption: Assumption, unread: list[str]) -> str:
    """``Readers: ...`` lines printed below the effective values."""
    if not assumption.readers:
        lines = ["Readers: not known (nothing names them); each transmission is shown as",
                 "  the loader of its dialect reads it"]
    else:
        lines = ["Readers:"]
        for name, why in zip(assumption.names(), assumption.because, strict=True):
            lines += textwrap.wrap(f"  {name} ({why})", WIDTH, subsequent_indent="    ")
        if not assumption.decided:
            lines.append("  (nothing rules ROS 1 out: ros_control may read the top-level ones)")
    if unread:
        names = ", ".join(f"'{n}'" for n in unread)
        lines += textwrap.wrap(f"Read by none of them: {names}", WIDTH, subsequent_indent="  ",
                               break_on_hyphens=False)
    return "\n" + "\n".join(lines) + "\n"


def readers_json(assumption: Assumption, unread: list[str]) -> dict[str, Any]:
    return {"readers": list(assumption.names()), "because": list(assumption.because),
            "decided": assumption.decided, "unread": unread}
