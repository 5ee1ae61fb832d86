"""The readers of one linted document: the readers model (:mod:`txtool.model.readers`) fed
with what the document's package says (:mod:`txtool.io.package_xml`) and what the user said.

:class:`FileReaders` is the record the reports carry for each file: the readers assumed and
why, without the document's elements (it travels between processes).
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import replace
from typing import NamedTuple

from txtool.io.xmlio import Source
from txtool.model.readers import Assumption, Package, Seen, Stated, assume, seen_in


class FileReaders(NamedTuple):
    """The readers assumed for a file, with one reason each; ``decided`` False when nothing
    said (each transmission is then judged by the loader of its dialect)."""

    path: str
    readers: tuple[str, ...]
    because: tuple[str, ...]
    decided: bool

    def as_json(self) -> dict[str, object]:
        return {"path": self.path, "readers": list(self.readers),
                "because": list(self.because), "decided": self.decided}


class Findings(list):  # type: ignore[type-arg]
    """A file's problems, and the readers they were judged for (None: no transmission)."""

    readers: FileReaders | None = None


def assumption_of(source: Source, stated: Stated) -> Assumption:
    """The readers of ``source``: its package is looked up when it is a file on disk."""
    from txtool.io.package_xml import package_of

    path = source.path
    on_disk = path not in ("-", "") and os.path.isfile(path)
    info = package_of(path) if on_disk else None
    package = Package(info.name, info.build_type, info.both) if info is not None else None
    known: dict[str, Mapping[str, str]] = {}

    def types() -> Mapping[str, str]:
        if "types" not in known:  # only a document with a non-standard type asks
            from txtool.io.package_xml import exported_transmission_types

            exported = exported_transmission_types(path if on_disk else None)
            known["types"] = {name: e.describe() for name, e in exported.items()}
        return known["types"]

    def elsewhere() -> Seen | None:
        if info is None:
            return None
        return plugins_of_package(os.path.dirname(info.manifest), path)

    return assume(source.root, package, stated, types, elsewhere)


def plugins_of_package(folder: str, path: str) -> Seen | None:
    """The ``<gazebo>`` plugins of the first other description file of the package in
    ``folder`` that names one (the reason names that file, relative to the package)."""
    from txtool.io.package_xml import plugin_files, read_description

    own = os.path.abspath(path)
    for candidate in plugin_files(folder):
        if os.path.abspath(candidate) == own:
            continue
        root = read_description(candidate)
        if root is None:
            continue
        seen = seen_in(root)
        if seen.plugins:
            return replace(seen, where=os.path.relpath(candidate, folder))
    return None


def record(path: str, assumption: Assumption) -> FileReaders:
    return FileReaders(path, assumption.names(), assumption.because, assumption.decided)
