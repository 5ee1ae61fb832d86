"""A declaration that does not start a document is never written there."""

from __future__ import annotations

import pytest

from txtool.transform.edits.core import apply_edits
from txtool.transform.edits.declaration import late_declaration


@pytest.mark.parametrize("data, written", [
    (b'\n  <?xml version="1.0"?>\n<robot/>', b'<?xml version="1.0"?>\n<robot/>'),
    (b'\xef\xbb\xbf <?xml version="1.0"?><robot/>', b'\xef\xbb\xbf<?xml version="1.0"?><robot/>'),
    (b'<!-- licence -->\r\n<?xml version="1.0"?>\r\n<robot/>', b"<!-- licence -->\r\n<robot/>"),
    (b'<?pi?><?xml version="1.0"?><robot/>', b"<?pi?><robot/>"),
])
def test_after_whitespace_the_whitespace_goes_after_anything_else_the_declaration(
        data: bytes, written: bytes) -> None:
    edit = late_declaration(data)
    assert edit is not None and apply_edits(data, [edit]) == written


@pytest.mark.parametrize("data", [b'<?xml version="1.0"?>\n<robot/>', b"<robot/>",
                                  b"<!-- c --><robot/>"])
def test_a_declaration_first_or_none_is_no_edit(data: bytes) -> None:
    assert late_declaration(data) is None
