from __future__ import annotations

from tests.rules.helpers import check, problems


def test_malformed_xml_is_a_finding_at_the_parser_position():
    found = problems('<robot name="r">\n  <transmission name="t">\n</robot>\n')
    assert [(p.line, p.code, p.severity, p.name) for p in found] == [
        (3, "TX001", "error", "xml-syntax")
    ]
    assert "mismatch" in found[0].message.lower()


def test_declaration_after_a_comment_is_reported_but_the_file_is_still_checked():
    xml = '<!-- licence -->\n<?xml version="1.0"?>\n<robot name="r">\n  <transmission/>\n</robot>\n'
    assert check(xml, select=["TX001", "TX100"]) == [(2, 1, "TX001", "error"), (4, 3, "TX100", "error")]


def test_well_formed_xml_passes():
    assert check('<?xml version="1.0"?>\n<robot name="r"/>\n', select=["TX001"]) == []
