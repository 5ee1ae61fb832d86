"""xacro could not expand the file: an error in it, or an argument or package this run lacks.

Produced by the pipeline when the xacro expansion fails (by txtool's restricted evaluator in
a child process, or upstream xacro under ``--trust-xacro``); the finding points at the
``$(arg ...)``, ``$(find ...)``, ``${...}`` or ``<xacro:include>`` that failed. The
transmissions written literally in the file are still checked, as for a macro library (values
containing ``${...}`` or ``$(...)`` are then unknown). Every file with a TX002 finding is
counted in the summary as "not expanded" (``not_expanded`` in the JSON report), so that a
CI log shows what was not checked.

The severity says whose fault it is:

* **error**, a fault of the files: an expression that fails (``name 'width' is not
  defined``, a macro called with a parameter it does not take), a file the package itself
  includes that does not exist, malformed XML. xacro stops there for everyone, as would
  ``xacro robot.urdf.xacro`` in the launch file.
* **info**, something the command line gives and this run lacks, which the launch files or
  the installed workspace supply: an argument without a default (``xacro robot.urdf.xacro
  prefix:=left_`` in a launch file; give ``--xacro-arg prefix:=left_``, or ``xacro-args`` in
  the configuration), a package that is not found (a dependency not installed here; give
  ``--pkg-dir DIR`` or ``--pkg-path name:=DIR``, or ``pkg-dirs`` / ``pkg-paths``; the message
  says when the file's ``package.xml`` does not declare it), or a file of another package
  that the version found lacks. A linter does not fail a correct file for its environment.
  ``[severity] TX002 = "error"`` makes every file not expanded fail, for a CI that must
  expand them all.

In a folder walk, a file that another checked file includes (``<xacro:include>``) is a
fragment: it is written for its includer's scope (the properties and arguments defined before the
include; xacro reads it only there, ros/xacro ``xacro/__init__.py`` ``process_include``), so
its own expansion failing is no finding: its includer's expansion checks it, and it is
checked as written. The includes are read without expanding (see
:mod:`txtool.lint.fragments`). A file named on the command line is expanded alone and gets
TX002 as any other.

What the restricted expansion refuses (a Python attribute, ``$(env)`` of a name not allowed, a
file outside the repository) or stops (a safety limit) is not a finding but an input error,
exit 2: see the *Untrusted xacro* section of the security page.

Failing example::

    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <link name="${prefix}base"/>  <!-- no property "prefix" defined -->
    </robot>

Passing example::

    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:property name="prefix" value=""/>
      <link name="${prefix}base"/>
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
