"""SARIF 2.1.0 for GitHub code scanning: every registered rule, one result per problem.

Paths become URIs relative to ``%SRCROOT%`` (the working folder, given in
``originalUriBaseIds``) with forward slashes, so code scanning maps them onto the repository
and results stay stable across checkouts; a file outside the working folder keeps an absolute
``file://`` URI. Files that could not be read are ``toolExecutionNotifications`` of the
invocation, which is then not ``executionSuccessful``. A finding ``txtool validate --fix``
fixes carries ``fixes``: the replacements that command makes in the lines of the finding (in
the whole file when the fix changes other lines), from the summary's ``edits``.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from pathlib import Path, PurePath
from typing import Any
from urllib.parse import quote

from txtool import __version__
from txtool.lint.problem import InputFailure, Note, Problem
from txtool.lint.readers import FileReaders
from txtool.lint.ruledoc import markdown, plain
from txtool.reporters import Summary, end_of, fingerprints
from txtool.reporters.fixes import Edit, edits_for

SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
HOME = "https://github.com/txtool/txtool"
RULE_DOCS = HOME + "/blob/main/docs/rules/{code}.md"  # docs/generate_rules.py writes them
SRCROOT = "%SRCROOT%"
LEVELS = {"error": "error", "warning": "warning", "info": "note"}
FINGERPRINT = "txtoolFinding/v1"  # path, code, message and occurrence: see fingerprints()


def render(problems: Sequence[Problem], summary: Summary, *, color: bool = False) -> str:
    log = sarif_log(problems, summary.failures, summary.readers, summary.edits or {})
    return json.dumps(log, indent=2) + "\n"


def sarif_log(
    problems: Sequence[Problem], failures: Sequence[InputFailure] = (),
    readers: Sequence[FileReaders] = (), edits: Mapping[str, Sequence[Edit]] | None = None,
) -> dict[str, Any]:
    """The SARIF log; the run's ``properties.readers`` lists, for each file holding
    transmissions, the readers it was judged for and why (as the JSON report's ``readers``)."""
    from txtool.rules import all_rules

    rules = list(all_rules().values())
    index = {rule.code: i for i, rule in enumerate(rules)}
    uris: dict[str, str] = {}  # one per file, not per problem
    driver = {
        "name": "txtool",
        "informationUri": HOME,
        "version": __version__,
        "semanticVersion": __version__,
        "rules": [_rule(rule) for rule in rules],
    }
    return {
        "$schema": SCHEMA,
        "version": "2.1.0",
        "runs": [
            {
                "tool": {"driver": driver},
                "invocations": [_invocation(failures, uris)],
                "originalUriBaseIds": {SRCROOT: {"uri": Path(os.getcwd()).as_uri() + "/"}},
                "columnKind": "unicodeCodePoints",
                "results": [_result(p, index, uris, (edits or {}).get(p.path, ()), digest)
                            for p, digest in zip(problems, fingerprints(problems), strict=True)],
                "properties": {"readers": [file.as_json() for file in readers]},
            }
        ],
    }


def _rule(rule: Any) -> dict[str, Any]:
    doc = rule.doc
    return {
        "id": rule.code,
        "name": rule.name,
        "shortDescription": {"text": plain(rule.summary)},
        "fullDescription": {"text": _first_paragraphs(plain(doc))},
        "helpUri": RULE_DOCS.format(code=rule.code),
        "help": {"text": plain(doc), "markdown": markdown(rule)},
        "defaultConfiguration": {"level": LEVELS[rule.severity]},
        "properties": {"tags": ["ros", "transmission"]},
    }


def _first_paragraphs(doc: str) -> str:
    """The prose before the examples, on one line per paragraph."""
    prose = doc.split("Failing example", 1)[0].split("Options (", 1)[0]
    paragraphs = [" ".join(p.split()) for p in prose.split("\n\n") if p.strip()]
    return "\n\n".join(paragraphs)


def _invocation(failures: Sequence[InputFailure], uris: dict[str, str]) -> dict[str, Any]:
    return {
        "executionSuccessful": not failures,
        "toolExecutionNotifications": [
            {
                "level": "error",
                "message": {"text": failure.message},
                "locations": [
                    {"physicalLocation": {"artifactLocation": _artifact(failure.path, uris)}}
                ],
            }
            for failure in failures
        ],
    }


def _artifact(path: str, uris: dict[str, str]) -> dict[str, str]:
    uri = uris.get(path)
    if uri is None:
        uri = uris[path] = artifact_uri(path)
    if uri.startswith("file:"):
        return {"uri": uri}
    return {"uri": uri, "uriBaseId": SRCROOT}


def _result(problem: Problem, index: dict[str, int], uris: dict[str, str],
            edits: Sequence[Edit] = (), fingerprint: str = "") -> dict[str, Any]:
    end_line, end_column = end_of(problem)
    result: dict[str, Any] = {
        "ruleId": problem.code,
        "level": LEVELS.get(problem.severity, "error"),
        "message": {"text": problem.message},
        "locations": [
            {
                "physicalLocation": {
                    "artifactLocation": _artifact(problem.path, uris),
                    "region": {
                        "startLine": problem.line,
                        "startColumn": problem.column,
                        "endLine": end_line,
                        "endColumn": end_column,
                    },
                }
            }
        ],
        # Code scanning matches a result across commits by this, not by its line.
        "partialFingerprints": {FINGERPRINT: fingerprint},
    }
    if problem.related:
        result["relatedLocations"] = [_related(number, note, uris)
                                      for number, note in enumerate(problem.related, 1)]
    if problem.code in index:
        result["ruleIndex"] = index[problem.code]
    if problem.fixable and edits:
        result["fixes"] = [_fix(problem, edits_for(edits, problem.line, end_line), uris)]
    return result


def _related(number: int, note: Note, uris: dict[str, str]) -> dict[str, Any]:
    return {
        "id": number,
        "physicalLocation": {
            "artifactLocation": _artifact(note.path, uris),
            "region": {"startLine": note.line, "startColumn": note.column},
        },
        "message": {"text": note.message},
    }


def _fix(problem: Problem, edits: Sequence[Edit], uris: dict[str, str]) -> dict[str, Any]:
    return {
        "description": {"text": f"Apply txtool's fixes to these lines ({problem.code} among "
                                "them): txtool validate --fix"},
        "artifactChanges": [{
            "artifactLocation": _artifact(problem.path, uris),
            "replacements": [_replacement(edit) for edit in edits],
        }],
    }


def _replacement(edit: Edit) -> dict[str, Any]:
    (start_line, start_column), (end_line, end_column) = edit.start, edit.end
    return {
        "deletedRegion": {
            "startLine": start_line, "startColumn": start_column,
            "endLine": end_line, "endColumn": end_column,
            "charOffset": edit.offset, "charLength": edit.length,
        },
        "insertedContent": {"text": edit.text},
    }


def artifact_uri(path: str) -> str:
    """A relative URI for ``path`` when possible, else a ``file://`` URI."""
    pure = PurePath(path)
    if pure.is_absolute():
        try:
            pure = Path(path).relative_to(Path(os.getcwd()))
        except ValueError:
            return Path(path).as_uri()
    return quote(os.fsencode(pure.as_posix()))  # a name's bytes, UTF-8 or not
