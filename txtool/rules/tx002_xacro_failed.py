"""xacro could not expand the file: an error in it, or an argument or package this run lacks.

What it does: reports the ``$(arg ...)``, ``$(find ...)``, ``${...}`` or ``<xacro:include>``
where the xacro expansion failed (by txtool's restricted evaluator in a child process, or
upstream xacro under ``--trust-xacro``); produced by the pipeline. The transmissions written
literally in the file are still checked, as for a macro library (values containing ``${...}``
or ``$(...)`` are then unknown). Every file with a TX002 finding is counted in the summary as
"not expanded" (``not_expanded`` in the JSON report), so that a CI log shows what was not
checked. In a folder walk, a file that another checked file includes is a fragment, written
for its includer's scope: its own expansion failing is no finding (its includer's expansion
checks it), and it is checked as written (see :mod:`txtool.lint.fragments`). What the
restricted expansion refuses or stops (a safety limit) is not a finding but an input error,
exit 2: see the *Untrusted xacro* section of the security page.

Why it matters: the severity says whose fault it is. **error**, a fault of the files: an
expression that fails (``name 'width' is not defined``, a macro called with a parameter it
does not take), a file the package itself includes that does not exist, malformed XML; xacro
stops there for everyone, as would ``xacro robot.urdf.xacro`` in the launch file. **info**,
something the command line gives and this run lacks, which the launch files or the installed
workspace supply: an argument without a default (give ``--xacro-arg prefix:=left_``, or
``xacro-args`` in the configuration), a package that is not found (give ``--pkg-dir DIR`` or
``--pkg-path name:=DIR``, or ``pkg-dirs`` / ``pkg-paths``; the message says when the file's
``package.xml`` does not declare it), or a file of another package that the version found
lacks. A linter does not fail a correct file for its environment; ``[severity] TX002 =
"error"`` makes every file not expanded fail, for a CI that must expand them all.

Loader: xacro (ros/xacro ``xacro/__init__.py`` ``process_file``, and ``process_include`` for
includes), as a launch file runs it before any loader reads the result.

Failing example (robot.urdf.xacro)::

    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <link name="${prefix}base"/>
    </robot>

Expected finding: ``2:15 error TX002 xacro: name 'prefix' is not defined``

Passing example (robot.urdf.xacro)::

    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:property name="prefix" value=""/>
      <link name="${prefix}base"/>
    </robot>

Fix: define what the expression uses; for what the launch file gives, pass it with
``--xacro-arg``, ``--pkg-dir`` or ``--pkg-path`` (or the configuration's ``xacro-args``,
``pkg-dirs``, ``pkg-paths``).
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
