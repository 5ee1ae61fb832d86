"""Conversions of large documents without Python's cycle collector running through them.

A conversion holds a few model objects per transmission until it ends, and makes no reference
cycles of its own; each of the collector's full passes walks every one of those objects, so
with 20,000 transmissions the passes took a quarter of ``convert``'s time. They are paused for
the duration (plain reference counting still frees everything as it goes) and resumed after;
:func:`paused` may nest.
"""

from __future__ import annotations

import gc
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from functools import wraps
from typing import ParamSpec, TypeVar

P = ParamSpec("P")
R = TypeVar("R")


@contextmanager
def paused_collection() -> Iterator[None]:
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def paused(function: Callable[P, R]) -> Callable[P, R]:
    """``function`` run under :func:`paused_collection`."""

    @wraps(function)
    def run(*args: P.args, **kwargs: P.kwargs) -> R:
        with paused_collection():
            return function(*args, **kwargs)

    return run
