"""The document as it was serialized before a conversion, without serializing it twice.

Splicing (:func:`txtool.transform.splice.splice`) compares the serialization of the tree as
parsed (the baseline) with the serialization of the converted tree. A conversion changes the
tree in place, so the baseline is serialized before the first change, unless the change is
the common one for a large robot: its transmissions stand together and all go into the block
generated for the document, written as text (:mod:`.block_text`). Then everything before and
after that block is serialized alike in both, and the baseline is the converted document with
the block's text replaced by the serializations of the transmissions it replaced (their
``tostring``, which keying them already made, see :mod:`.renamings`) and the blank text between
them. :class:`Rebuild` keeps those; :meth:`Rebuild.baseline` puts them in.

That holds where a transmission's ``tostring`` is the very text the whole document's
serialization gives it: no namespace in scope (``tostring`` repeats the declarations on the
element), and ASCII without character references (``tostring`` writes every other character
as a reference, the document in its own encoding); :func:`rebuildable` and
:meth:`Rebuild.make` check both. The transmissions the block replaces are children of the
root: only the root's declarations are in scope.
"""

from __future__ import annotations

from lxml import etree

from txtool.io.encodings import detect_encoding

_END = b"</ros2_control>"


def rebuildable(original: bytes, root: etree._Element) -> bool:
    """Whether the document stored as ``original`` (whose root element is ``root``) may have
    its baseline rebuilt: one byte a character for ASCII, no namespace declared on the root
    (the block and the transmissions it replaces are the root's children), and no text like
    the block's marker (so the serialization holds the marker once: ``<!--`` starts a comment
    only, and a comment's text is literal)."""
    return not detect_encoding(original).wide and not root.nsmap and (
        b"txtool-block-" not in original)


def _blank(tail: str | None) -> bool:
    return not (tail or "").strip(" \t\n")


class Rebuild:
    """What the baseline has in place of the written block: the transmissions it replaced,
    each followed by its blank tail (the last one's stays, as the block's)."""

    __slots__ = ("replaced", "_head")

    def __init__(self, replaced: bytes, head: bytes) -> None:
        self.replaced = replaced
        self._head = head  # the block's text up to its marker

    @classmethod
    def make(cls, block: etree._Element, marker: etree._Comment,
             run: list[etree._Element], texts: list[bytes], kinds: set[str | None]
             ) -> Rebuild | None:
        """For ``block`` (holding ``marker`` as its last child) replacing ``run``, elements
        standing together whose serializations are ``texts`` and whose tails (but the last
        one's) are ``kinds``, each once; None where those do not make the baseline (see the
        module)."""
        if not all(map(_blank, kinds)):
            return None
        if len(kinds) <= 1:  # one tail between them all (none: one transmission)
            between = next(iter(kinds), None) or ""
            replaced = between.encode("ascii").join(texts)
        else:
            tails = [element.tail or "" for element in run[:-1]]
            pieces = [piece for text, tail in zip(texts, tails, strict=False)
                      for piece in (text, tail.encode("ascii"))]
            pieces.append(texts[-1])
            replaced = b"".join(pieces)
        token = f"<!--{marker.text}-->".encode("ascii")
        head, found, end = etree.tostring(block, with_tail=False).partition(token)
        if not found or end != _END or b"&#" in head or b"&#" in replaced:
            return None
        return cls(replaced, head)

    def baseline(self, data: bytes, marker: etree._Comment, original: bytes) -> bytes:
        """The baseline, from ``data``: the converted document serialized with the block's
        marker in it (before :func:`.block_text.fill`), which holds the block's text once;
        ``original`` itself when they are the same (most generated documents: then no copy
        is made)."""
        whole = self._head + f"<!--{marker.text}-->".encode("ascii") + _END
        at = data.find(whole)
        assert at >= 0 and data.find(whole, at + 1) < 0, "the written block is not found once"
        view = memoryview(data)
        after = at + len(whole)
        if len(original) == len(data) - len(whole) + len(self.replaced) and (
                original.startswith(view[:at]) and original.startswith(self.replaced, at)
                and original.endswith(view[after:])):
            return original
        return b"".join([view[:at], self.replaced, view[after:]])
