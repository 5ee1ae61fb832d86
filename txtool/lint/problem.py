"""The one value type every lint finding is: small, frozen, sortable."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal, NamedTuple

Severity = Literal["error", "warning", "info"]


class InputFailure(NamedTuple):
    """A file that could not be checked: its path and the one-line message (``path[:line]:
    reason``) that says why. It fails the run with exit 2; machine reports keep it."""

    path: str
    message: str
SEVERITIES: tuple[Severity, ...] = ("error", "warning", "info")


class Note(NamedTuple):
    """A place related to a finding: where the macro whose expansion holds it is written, say
    (SARIF ``relatedLocations``, LSP ``relatedInformation``)."""

    path: str
    line: int
    column: int
    message: str


@dataclass(frozen=True, order=True, slots=True)  # slots: a document may have thousands
class Problem:
    """A finding at a 1-based ``line:column`` of ``path``.

    Rules create problems with ``code`` and ``message``; the pipeline stamps ``name``,
    ``severity`` and ``fixable`` from the rule's registry entry.
    """

    path: str
    line: int
    column: int
    code: str
    message: str = field(compare=False)
    end_line: int | None = field(default=None, compare=False)
    end_column: int | None = field(default=None, compare=False)
    severity: Severity = field(default="error", compare=False)
    name: str = field(default="", compare=False)
    # A rule leaves this None, or sets it False for a finding its fix declines by design;
    # the pipeline stamps True or False.
    fixable: bool | None = field(default=None, compare=False)
    # A rule sets this below its registered severity for a finding the file's own loader
    # accepts (gazebo_ros_control's, say); a configured severity still wins.
    loader_severity: Severity | None = field(default=None, compare=False)
    # The xacro call chain of a finding in an expansion: "in expansion of macro M ...".
    related: tuple[Note, ...] = field(default=(), compare=False)
    # A rule sets this for a finding for which its reader refuses the whole document (the
    # parser throws, no hardware of the robot loads), not one transmission: a conversion
    # that writes such a file fails even when its input had the finding already.
    refuses_whole: bool = field(default=False, compare=False)

    def __str__(self) -> str:
        """The finding as ``txtool validate`` prints it: ``path:line:col: severity CODE name:
        message``."""
        rule = f"{self.code} {self.name}" if self.name else self.code
        return (f"{self.path}:{self.line}:{self.column}: {self.severity} {rule}: "
                f"{self.message}{self.chain()}")

    def chain(self) -> str:
        """`` (in expansion of macro 'arm' defined at arm.xacro:3)`` per note, or ``""``."""
        return "".join(f" ({note.message})" for note in self.related)
