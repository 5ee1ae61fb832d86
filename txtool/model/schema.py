"""JSON Schemas generated from the model's pydantic schema (checked in under ``schemas/``)."""

from __future__ import annotations

import json

from txtool.model.core import json_schema
from txtool.model.show_document import ShowDocument

SCHEMA_FILES = {"transmission.schema.json": ShowDocument}


def schema_text(model: type = ShowDocument) -> str:
    schema = json_schema(model)
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "txtool transmissions (txtool show --format json)"
    return json.dumps(schema, indent=2, sort_keys=True) + "\n"
