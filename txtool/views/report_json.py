"""``roundtrip --format json``: the text of ``json.dumps(report.to_json(), indent=2)``,
written without encoding each of hundreds of thousands of alike rows through Python's
indenting encoder (the C encoder does not indent).

A row is its transmission's name and a rest (cycle, fields, verdict, details) that a large
robot shares among thousands of rows: each rest is encoded once, by ``json.dumps`` itself.
"""

from __future__ import annotations

import json
from json.encoder import encode_basestring_ascii  # what json.dumps writes a str with
from typing import Any

_ROW = "    {\n      \"transmission\": "


def roundtrip_json(report: Any) -> str:
    """``report`` (a :class:`txtool.transform.roundtrip.RoundTripReport`) as JSON text."""
    rests: dict[tuple, str] = {}
    rows = []
    for row in report.rows:
        # Rows of repeated transmissions share their fields (all rows are alive: ids differ).
        key = (row.cycle, id(row.fields), row.equivalent, row.details)
        rest = rests.get(key)
        if rest is None:
            rest = rests[key] = _rest(row)
        rows.append(_ROW + encode_basestring_ascii(row.transmission) + rest)
    cycles = "[\n" + ",\n".join(rows) + "\n  ]" if rows else "[]"
    return "".join([
        "{\n  \"path\": ", json.dumps(report.path),
        ",\n  \"against\": null",
        ",\n  \"ok\": ", "true" if report.ok else "false",
        ",\n  \"cycles\": ", cycles,
        ",\n  \"skipped\": ", _indented(json.dumps(report.skipped, indent=2), "  "),
        ",\n  \"transmissions\": []",
        ",\n  \"bb_exporter_dropped\": []",
        "\n}",
    ])


def _rest(row: Any) -> str:
    """A row's encoding after its name: ``,`` and the lines of its other keys, as they stand
    two levels deep."""
    encoded = json.dumps({"transmission": "", "cycle": list(row.cycle), **row.fields,
                          "equivalent": row.equivalent, "details": list(row.details)},
                         indent=2)
    rest = encoded.split("\n", 2)[2]  # after "{" and the name's line
    return ",\n    " + _indented(rest, "    ")


def _indented(text: str, indent: str) -> str:
    """``text`` with every line after the first indented by ``indent``."""
    return text.replace("\n", "\n" + indent)
