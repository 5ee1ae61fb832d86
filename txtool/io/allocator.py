"""How the ``txtool`` command's C allocator frees the trees of large documents (glibc).

libxml2 allocates each node, attribute and text of a parsed document on its own. glibc keeps
such small chunks, once freed, in its "fast bins" and merges them only when a large allocation
comes next, all at once: freeing the tree of a 9 MB robot costs 0.025 s, and the next large
allocation (the bytes of a parse, of a document written or of a diff) 0.09 s more, about half
a parse. A conversion frees two trees of its size (the document converted in place, and what
its check read back). With the fast bins off (``mallopt(M_MXFAST, 0)``), each chunk is merged
as it is freed: 0.048 s in all. Measured in docs/performance.md.

The command line turns it on (:func:`enable`); it takes effect when the first document of a
megabyte or more is parsed (:func:`before_large_tree`), so a small file pays nothing, not even
the import of :mod:`ctypes`. A library leaves its host's allocator alone: scripts that import
txtool get no change. Where the C library has no ``mallopt`` (macOS, Windows) nothing changes;
musl accepts the call and ignores it.
"""

from __future__ import annotations

import sys

LARGE = 1 << 20  # bytes of a document whose tree is worth it
M_MXFAST = 1  # glibc's mallopt parameter: the largest chunk a fast bin holds; 0 turns them off


class _State:
    enabled = False
    asked = False  # mallopt was called (once per process)


def enable() -> None:
    """Let :func:`before_large_tree` turn the fast bins off: the command line's choice."""
    _State.enabled = True


def before_large_tree(size: int) -> None:
    """Called before a document of ``size`` bytes is parsed: the first large one, where
    enabled, turns the fast bins off for the rest of the process."""
    if size >= LARGE and _State.enabled and not _State.asked:
        _State.asked = True
        fast_bins_off()


def fast_bins_off() -> bool:
    """Ask glibc to free small chunks at once; whether the C library took the setting."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        import ctypes

        mallopt = ctypes.CDLL(None).mallopt
    except (ImportError, OSError, AttributeError):  # no ctypes, or no mallopt in this libc
        return False
    return bool(mallopt(M_MXFAST, 0))
