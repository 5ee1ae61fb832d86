"""An unexpected exception: one line naming the input being read, exit 2; ``--debug`` shows
the traceback.

Each test runs ``txtool`` through its real entry point (``txtool.cli.main``) in a fresh
interpreter, after replacing one core function with a failing one.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

from tests.hardening.hostile_inputs import robot

ROOT = Path(__file__).resolve().parents[2]


def txtool_with(sabotage: str, *args: str) -> tuple[int, str, str]:
    """Run ``txtool ARGS`` after executing ``sabotage`` (Python that breaks something)."""
    program = textwrap.dedent(sabotage) + textwrap.dedent("""
        import sys
        from txtool.cli import main
        sys.argv = ["txtool", *sys.argv[1:]]
        main()
    """)
    result = subprocess.run([sys.executable, "-c", program, *args], capture_output=True,
                            text=True, timeout=120, cwd=ROOT)
    return result.returncode, result.stdout, result.stderr


BROKEN_READER = """
import txtool.dialects.read

def read_source(source):
    raise RuntimeError("reader broke\\n  on purpose")

txtool.dialects.read.read_source = read_source
"""


def test_internal_error_is_one_line_naming_the_file(tmp_path):
    document = tmp_path / "robot.urdf"
    document.write_text(robot())
    code, out, err = txtool_with(BROKEN_READER, "show", str(document))
    assert (code, out) == (2, "")
    assert err == (f"txtool: internal error: RuntimeError: reader broke on purpose "
                   f"(while reading {document}; please report)\n")


def test_debug_shows_the_traceback(tmp_path):
    document = tmp_path / "robot.urdf"
    document.write_text(robot())
    code, out, err = txtool_with(BROKEN_READER, "--debug", "show", str(document))
    assert code == 1 and out == ""
    assert err.startswith("Traceback (most recent call last):")
    assert "in read_source" in err and err.endswith("RuntimeError: reader broke\n  on purpose\n")
    assert "internal error" not in err


def test_the_file_named_is_the_one_being_read(tmp_path):
    folder = tmp_path / "robots"
    folder.mkdir()
    for name in ("a_first.urdf", "b_second.urdf", "c_third.urdf"):
        (folder / name).write_text(robot())
    sabotage = """
        import txtool.lint.engine as engine

        real = engine.context_for

        def context_for(source, settings):
            if source.path.endswith("b_second.urdf"):
                raise KeyError("no such rule")
            return real(source, settings)

        engine.context_for = context_for
    """
    code, out, err = txtool_with(sabotage, "validate", str(folder))
    assert (code, out) == (2, "")
    assert err == (f"txtool: internal error: KeyError: 'no such rule' "
                   f"(while reading {folder / 'b_second.urdf'}; please report)\n")


def test_internal_error_before_any_file_names_none():
    sabotage = """
        import txtool.model.schema

        def schema_text():
            raise ValueError("schema broke")

        txtool.model.schema.schema_text = schema_text
    """
    code, out, err = txtool_with(sabotage, "schema")
    assert (code, out) == (2, "")
    assert err == "txtool: internal error: ValueError: schema broke (please report)\n"


def test_input_errors_are_not_internal_errors(tmp_path):
    code, out, err = txtool_with("", "show", str(tmp_path / "missing.urdf"))
    assert (code, out, err) == (2, "", f"txtool: {tmp_path / 'missing.urdf'}: no such file\n")


INTERRUPTED_READER = """
import txtool.dialects.read

def read_source(source, **options):
    raise KeyboardInterrupt

txtool.dialects.read.read_source = read_source
"""


def test_ctrl_c_is_one_line_and_exit_130_not_the_findings_code(tmp_path):
    document = tmp_path / "robot.urdf"
    document.write_text(robot())
    code, out, err = txtool_with(INTERRUPTED_READER, "show", str(document))
    assert (code, out, err) == (130, "", "txtool: interrupted\n")
