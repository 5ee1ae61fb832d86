"""How the ``txtool`` command's C allocator serves the trees of large documents (glibc).

libxml2 allocates each node, attribute and text of a parsed document on its own. glibc keeps
such small chunks, once freed, in its "fast bins" and merges them only when a large allocation
comes next, all at once: freeing the tree of a 9 MB robot costs 0.025 s, and the next large
allocation (the bytes of a parse, of a document written or of a diff) 0.09 s more, about half
a parse. A conversion frees two trees of its size (the document converted in place, and what
its check read back). With the fast bins off (``mallopt(M_MXFAST, 0)``), each chunk is merged
as it is freed: 0.048 s in all.

What a freed tree leaves is then reused, if glibc keeps it: by default it gives the top of its
heap back to the system past 128 KB free, and serves each allocation of 128 KB or more (a
document's bytes, a written block, a diff: megabytes each) from pages of its own, returned when
freed. Each page the process touches for the first time costs a fault, about 4 us on a virtual
machine: a bare parse of the 9 MB robot takes 25,000 of them, a tenth of a second. So the heap
is kept (``M_TRIM_THRESHOLD``) and allocations below 32 MB come from it (``M_MMAP_THRESHOLD``):
a command exits soon after its documents. Measured in docs/performance.md.

The command line turns it on (:func:`enable`); it takes effect when the first document of a
megabyte or more is parsed (:func:`before_large_tree`), so a small file pays nothing, not even
the import of :mod:`ctypes`. A library leaves its host's allocator alone: scripts that import
txtool get no change. Where the C library has no ``mallopt`` (macOS, Windows) nothing changes;
musl accepts the calls and ignores them.
"""

from __future__ import annotations

import sys

LARGE = 1 << 20  # bytes of a document whose tree is worth it
# glibc's mallopt parameters, and the values the command line sets.
M_MXFAST = 1  # the largest chunk a fast bin holds: 0 turns them off
M_TRIM_THRESHOLD = -1  # free bytes at the top of the heap past which it is given back
M_MMAP_THRESHOLD = -3  # allocations this large or larger get pages of their own
SETTINGS = ((M_MXFAST, 0), (M_TRIM_THRESHOLD, 1 << 30), (M_MMAP_THRESHOLD, 32 << 20))


class _State:
    enabled = False
    asked = False  # mallopt was called (once per process)


def enable() -> None:
    """Let :func:`before_large_tree` set the allocator for large trees: the command line's
    choice."""
    _State.enabled = True


def before_large_tree(size: int) -> None:
    """Called before a document of ``size`` bytes is parsed: the first large one, where
    enabled, sets the allocator for large trees for the rest of the process."""
    if size >= LARGE and _State.enabled and not _State.asked:
        _State.asked = True
        for_large_trees()


def for_large_trees() -> bool:
    """Ask glibc to free small chunks at once and to keep and reuse what is freed
    (:data:`SETTINGS`); whether the C library took every setting."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        import ctypes

        mallopt = ctypes.CDLL(None).mallopt
    except (ImportError, OSError, AttributeError):  # no ctypes, or no mallopt in this libc
        return False
    return all([bool(mallopt(parameter, value)) for parameter, value in SETTINGS])
