"""A rule's documentation (its module docstring) as a terminal, Markdown and SARIF read it.

Docstrings are written in reStructuredText's small subset: ``literal``, ``:role:`target```
and ``Failing example::`` followed by an indented XML block.

Every rule's docstring has one layout (:data:`SECTIONS`, checked by :func:`layout_problems`;
docs/contributing.md): the summary line, then paragraphs opening with ``What it does:``,
``Why it matters:``, ``Loader:`` (which program reads the file, with its source: repository,
file and line or function), ``Failing example::`` (a whole document) and ``Expected finding:``
(````LINE:COLUMN severity CODE message````, what ``txtool validate`` prints for it, path
left out), ``Passing example::`` and ``Fix:``. An example heading may name the file the example
is written to, for a name that matters: ``Failing example (robot.urdf.xacro)::``.
"""

from __future__ import annotations

import re
import textwrap
from typing import Any, NamedTuple

SECTIONS = ("What it does", "Why it matters", "Loader", "Failing example", "Expected finding",
            "Passing example", "Fix")
_EXAMPLES = ("Failing example", "Passing example")
# A rule about a robot with its controllers (TX5xx) shows the robot its examples control in a
# section of its own after ``Loader``: ``Robot (urdf/robot.urdf)::``.
# A rule about the controllers a launch file starts (TX504) shows it after the robot:
# ``Launch (launch/bringup.launch.py)::``.
ROBOT = "Robot"
LAUNCH = "Launch"
_LABEL = re.compile(r"^(" + "|".join((*SECTIONS, ROBOT, LAUNCH)) +
                    r")(?: \(([^)]*)\))?(::?)(?:[ \t]+|$)")
_SOURCE_FILE = re.compile(r"\b[\w./-]*\w\.(?:cpp|hpp|h|cc|py|ex|exs|xml)\b")
_FINDING = re.compile(r"``(\d+):(\d+) (error|warning|info) (TX\d{3}) ([^`]+)``")
_ROLE = re.compile(r":(?:func|mod|class|meth|data|attr):`~?([^`]+)`")
_LITERAL = re.compile(r"``([^`]+)``")


def plain(doc: str) -> str:
    """For a terminal: no markup; ``x`` becomes x, ``Example::`` becomes ``Example:``."""
    text = _ROLE.sub(lambda m: m.group(1).rsplit(".", 1)[-1], doc)
    text = _LITERAL.sub(r"\1", text)
    return re.sub(r"(?m)::$", ":", text)


def markdown(rule: Any, *, heading: str = "**") -> str:
    """The docstring as Markdown: literals in backticks, examples as fenced XML."""
    title = f"{rule.code} {rule.name}"
    out = [f"# {title}" if heading == "#" else f"**{title}**", ""]
    fenced = False
    for line in _inline(rule.doc).splitlines():  # literals may span lines
        if fenced and line.strip() and not line.startswith("    "):
            while out[-1] == "":
                out.pop()
            out += ["```", ""]
            fenced = False
        if line.rstrip().endswith("::") and not fenced:
            fence = ("```yaml" if ".yaml)" in line or ".yml)" in line else
                     "```python" if ".py)" in line else "```xml")
            out += [line.rstrip()[:-1], "", fence]
            fenced = True
            continue
        label = None if fenced else _LABEL.match(line)
        if label is not None:  # "Why it matters: ..." opens its paragraph in bold
            line = f"**{line[:label.end(3)]}** {line[label.end():]}".rstrip()
        out.append(line[4:] if fenced else line)
    if fenced:
        out.append("```")
    text = "\n".join(out)
    for fence in ("```xml", "```yaml", "```python"):
        text = text.replace(f"{fence}\n\n", f"{fence}\n")
    return text


def _inline(text: str) -> str:
    text = _ROLE.sub(lambda m: f"`{m.group(1).rsplit('.', 1)[-1]}`", text)
    return _LITERAL.sub(r"`\1`", text)


class Section(NamedTuple):
    """One section of a rule's documentation: its label, the file an example is written to
    (empty: ``robot.urdf``) and its text (an example's XML without its indentation)."""

    label: str
    filename: str
    text: str


class Finding(NamedTuple):
    line: int
    column: int
    severity: str
    code: str
    message: str


def sections(doc: str) -> list[Section]:
    """The labelled sections of ``doc``, in order (the summary before them is left out)."""
    found: list[tuple[str, str, list[str]]] = []
    for line in doc.splitlines():
        match = _LABEL.match(line)
        if match:
            label, filename, colons = match.group(1), match.group(2) or "", match.group(3)
            rest = line[match.end():]
            found.append((label, filename if colons == "::" else "", [rest] if rest else []))
        elif found:
            found[-1][2].append(line)
    result = []
    for label, filename, lines in found:
        if label in (*_EXAMPLES, ROBOT, LAUNCH):
            text = textwrap.dedent("\n".join(lines)).strip("\n") + "\n"
        else:
            text = " ".join(" ".join(lines).split())
        result.append(Section(label, filename, text))
    return result


def expected_finding(text: str) -> Finding | None:
    """The finding an ``Expected finding:`` section gives, or None if it gives none."""
    match = _FINDING.search(text)
    if match is None:
        return None
    line, column, severity, code, message = match.groups()
    return Finding(int(line), int(column), severity, code, " ".join(message.split()))


def layout_problems(code: str, doc: str) -> list[str]:
    """What keeps ``doc`` from the layout every rule's documentation has (empty: none)."""
    problems = []
    summary = doc.split("\n\n", 1)[0]
    if not summary.strip() or _LABEL.match(summary):
        problems.append("no summary line first")
    found = sections(doc)
    labels = [s.label for s in found]
    if labels[3:4] == [ROBOT]:
        labels.pop(3)
        if labels[3:4] == [LAUNCH]:
            labels.pop(3)
    if labels != list(SECTIONS):
        problems.append(f"sections {labels}, expected {list(SECTIONS)} in that order, each once")
    by_label = {s.label: s for s in found}
    for section in found:
        if not section.text.strip():
            problems.append(f"'{section.label}' is empty")
    loader = by_label.get("Loader")
    if loader is not None and not _SOURCE_FILE.search(loader.text):
        problems.append("'Loader' names no source file (repository path/file.cpp, with the "
                        "line or function)")
    finding = by_label.get("Expected finding")
    if finding is not None:
        parsed = expected_finding(finding.text)
        if parsed is None:
            problems.append("'Expected finding' gives no ``LINE:COLUMN severity CODE message``")
        elif parsed.code != code:
            problems.append(f"'Expected finding' is a {parsed.code}, not a {code}")
    return problems
