"""Reading the rich tables txtool prints, so tests can check each column by its header."""

from __future__ import annotations


def table_rows(text: str, title: str) -> list[dict[str, str]]:
    """The rows of the table titled ``title`` in ``text``, each as {header: cell}.

    One printed line is one row (tests use tables whose cells do not wrap); a header that
    wraps onto two lines is joined with a space.
    """
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.strip() == title)
    headers: list[str] = []
    rows: list[dict[str, str]] = []
    for line in lines[start + 1:]:
        if line.startswith("┃"):
            cells = [cell.strip() for cell in line.strip("┃").split("┃")]
            headers = cells if not headers else [f"{h} {c}".strip() for h, c in
                                                 zip(headers, cells, strict=True)]
        elif line.startswith("│"):
            cells = [cell.strip() for cell in line.strip("│").split("│")]
            rows.append(dict(zip(headers, cells, strict=True)))
        elif line.startswith("└"):
            break
    return rows
