"""TX001, TX002, TX003, TX005 and TX006 are the pipeline's own findings (a document that does
not parse or expand, suppressions, a file without transmissions): the engine reports them and
does not run them over a parsed document, whose transmissions give them nothing to say."""

from __future__ import annotations

from txtool.io.xmlio import Source, parse_bytes
from txtool.lint.engine import PIPELINE_CODES, as_settings, context_for, run_rules
from txtool.rules import all_rules

DOCUMENT = b"""<robot name="r">
  <!-- txtool: disable-next-line TX999 -->
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type></transmission>
</robot>
"""


def test_pipeline_rules_find_nothing_in_a_parsed_document():
    source = Source("robot.urdf", DOCUMENT, parse_bytes(DOCUMENT, "robot.urdf"))
    settings = as_settings(None)
    ctx = context_for(source, settings)
    assert {"TX001", "TX002", "TX003", "TX005", "TX006"} == PIPELINE_CODES
    for code in sorted(PIPELINE_CODES):
        assert list(all_rules()[code].check(ctx)) == [], code
    # The document's own findings come from the other rules (TX103: no joint, no actuator).
    assert "TX103" in {p.code for p in run_rules(ctx, settings)}
