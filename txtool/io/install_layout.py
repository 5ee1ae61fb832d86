"""Where a file of an installed package lies in the package's source folder.

``$(find pkg)`` in a checkout names the package's source folder, but a xacro file is written for
the installed package (``share/pkg``), which CMake lays out by the package's ``install(DIRECTORY
... DESTINATION share/${PROJECT_NAME})`` and ``install(FILES ...)`` rules: ros2_control_demos'
``description/ros2_control`` folder is installed as ``share/<package>/ros2_control``, and its
robots include ``$(find <package>)/ros2_control/...``. A path missing from the source folder is
looked up through those rules (a folder named with a trailing ``/`` installs its contents), so
the robot expands from the checkout as it does once installed. Only ``CMakeLists.txt`` of the
package itself is read (at most :data:`MAX_CMAKE` bytes); variables other than
``${PROJECT_NAME}`` are not evaluated, so a rule naming another one is passed over.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from txtool.io.packages import enclosing_manifest, package_name
from txtool.io.xmlio import InputError, read_regular

MAX_CMAKE = 1 << 20
_COMMENT = re.compile(r"#[^\n]*")
_INSTALL = re.compile(r"\binstall\s*\(([^()]*)\)", re.IGNORECASE)
_ARGUMENT = re.compile(r'"([^"]*)"|(\S+)')
_SOURCES = {"DIRECTORY", "FILES"}


def installed_source(path: str) -> str | None:
    """The existing source file that the installed package's ``path`` is made from, or None
    (``path`` below no package, no rule of its package installs it, or the source is absent)."""
    manifest = enclosing_manifest(path)
    if manifest is None:
        return None
    package = str(manifest.parent)
    relative = os.path.relpath(os.path.abspath(path), package)
    for source, installed in install_rules(package):
        if relative == installed or relative.startswith(installed + os.sep) or not installed:
            rest = relative[len(installed):].lstrip(os.sep)
            candidate = os.path.normpath(os.path.join(package, source, rest))
            if candidate != os.path.abspath(path) and os.path.isfile(candidate):
                return candidate
    return None


def install_rules(package: str) -> tuple[tuple[str, str], ...]:
    """(source below ``package``, where it lands below ``share/<name>``) for each folder and
    file the package's CMakeLists.txt installs into its share folder."""
    try:
        text = read_regular(os.path.join(package, "CMakeLists.txt"), MAX_CMAKE).decode(
            "utf-8", "replace")
    except (InputError, OSError):
        return ()
    name = package_name(Path(package, "package.xml")) or os.path.basename(package)
    shares = {"share/${PROJECT_NAME}", f"share/{name}"}
    rules = []
    for body in _INSTALL.findall(_COMMENT.sub("", text)):
        words = [quoted or plain for quoted, plain in _ARGUMENT.findall(body)]
        if not words or words[0].upper() not in _SOURCES or "DESTINATION" not in words:
            continue
        at = words.index("DESTINATION")
        destination = words[at + 1].rstrip("/") if at + 1 < len(words) else ""
        base = next((s for s in shares if destination == s or destination.startswith(s + "/")),
                    None)
        if base is None:
            continue
        below = destination[len(base):].lstrip("/")
        for source in words[1:at]:
            if "$" in source or os.path.isabs(source) or ".." in source.split("/"):
                continue
            contents = source.endswith("/") and words[0].upper() == "DIRECTORY"
            landed = below if contents else os.path.join(below, os.path.basename(
                source.rstrip("/")))
            rules.append((os.path.normpath(source), os.path.normpath(landed) if landed else ""))
    return tuple(rules)
