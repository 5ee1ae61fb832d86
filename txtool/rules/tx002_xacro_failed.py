"""xacro could not expand the file: a missing argument, package or property.

Produced by the pipeline when the xacro expansion fails (by txtool's restricted evaluator in
a child process, or upstream xacro under ``--trust-xacro``); the message names what is
missing and how to provide it (``--xacro-arg name:=VALUE``, ``--pkg-dir DIR``,
``--pkg-path name:=DIR``, or ``xacro-args`` / ``pkg-dirs`` / ``pkg-paths`` in the
configuration). The transmissions written literally in the file are still checked, as for a
macro library (values containing ``${...}`` or ``$(...)`` are then unknown). What the
restricted expansion refuses (a Python attribute, ``$(env)`` of a name not allowed, a file
outside the repository) or stops (a safety limit) is not a finding but an input error, exit 2:
see the *Untrusted xacro* section of the security page.

Failing example::

    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <link name="$(arg prefix)base"/>  <!-- no argument "prefix" given -->
    </robot>

Passing example::

    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:arg name="prefix" default=""/>
      <link name="$(arg prefix)base"/>
    </robot>
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem

CODE = "TX002"
NAME = "xacro-failed"
SEVERITY = "error"
FIXABLE = False


def check(ctx: LintContext) -> Iterator[Problem]:
    """Nothing to check on an expanded document: the pipeline reports expansion errors."""
    return iter(())
