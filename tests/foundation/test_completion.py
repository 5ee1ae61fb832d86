"""``txtool completion bash|zsh|fish``: the script, and what it completes (driven as the shells
drive it, through COMP_WORDS and COMP_CWORD, as click's own tests do)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize(("shell", "marks"), [
    ("bash", ("_txtool_completion() {", "complete -o nosort -F _txtool_completion txtool")),
    ("zsh", ("#compdef txtool", "_TXTOOL_COMPLETE=zsh_complete")),
    ("fish", ("complete --no-files --command txtool", "_TXTOOL_COMPLETE=fish_complete")),
])
def test_each_shell_gets_its_script(run, shell, marks):
    code, out, err = run("completion", shell)
    assert (code, err) == (0, "")
    assert all(mark in out for mark in marks), out


def test_an_unknown_shell_is_refused_with_the_choices(run):
    code, out, err = run("completion", "powershell")
    assert (code, out) == (2, "")
    assert "'powershell' is not one of 'bash', 'zsh', 'fish'" in err


def complete(words: str) -> list[str]:
    """What bash is told to offer for the last word of ``words`` (empty after a space)."""
    cword = len(words.split()) - (0 if words.endswith(" ") else 1)
    env = {"COMP_WORDS": words, "COMP_CWORD": str(cword),
           "_TXTOOL_COMPLETE": "bash_complete"}
    result = CliRunner().invoke(cli, [], prog_name="txtool", env=env, catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return result.stdout.splitlines()


def test_a_command_name_completes():
    assert complete("txtool val") == ["plain,validate"]
    assert complete("txtool co") == ["plain,completion", "plain,convert"]


def test_file_arguments_complete_files_and_choices_their_values():
    for words in ("txtool show rob", "txtool validate rob", "txtool convert rob",
                  "txtool roundtrip rob", "txtool map rob", "txtool simulate rob",
                  "txtool migrate rob", "txtool roundtrip a.urdf --against rob",
                  "txtool simulate a.urdf --candidate rob"):
        assert complete(words) == ["file,rob"], words
    assert complete("txtool convert a.urdf --to ros2") == ["plain,ros2-p1", "plain,ros2-p2"]
    assert complete("txtool completion ") == ["plain,bash", "plain,zsh", "plain,fish"]


def test_deprecated_spellings_are_not_offered():
    offered = [line.split(",", 1)[1] for line in complete("txtool validate --out")]
    assert offered == ["--output"]
    offered = complete("txtool simulate a.urdf --c")
    assert "plain,--candidate" in offered and "plain,--config" not in offered


@pytest.mark.skipif(shutil.which("bash") is None, reason="needs bash")
def test_bash_completes_through_the_script_as_installed(run, tmp_path):
    """The script as the docs install it (eval in bash), the program found on PATH."""
    program = tmp_path / "bin" / "txtool"
    program.parent.mkdir()
    program.write_text(f"#!/bin/sh\nexec {sys.executable} -m txtool \"$@\"\n")
    program.chmod(0o755)
    (tmp_path / "robot.urdf").write_text("<robot name='r'/>")
    script = (
        'eval "$(txtool completion bash)"\n'
        'complete -p txtool\n'
        'COMP_WORDS=(txtool val); COMP_CWORD=1; _txtool_completion txtool\n'
        'printf "reply:%s\\n" "${COMPREPLY[@]}"\n'
    )
    env = {**os.environ, "PATH": f"{program.parent}{os.pathsep}{os.environ['PATH']}",
           "PYTHONPATH": str(ROOT)}
    done = subprocess.run(["bash", "--norc", "-c", script], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["complete -o nosort -F _txtool_completion txtool",
                                        "reply:validate"]


def test_rule_codes_complete_for_select_ignore_and_rules():
    assert complete("txtool validate --select TX30") == [
        f"plain,TX30{n}" for n in range(7)]
    assert complete("txtool validate --ignore TX1,TX10") == [
        f"plain,TX1,TX10{n}" for n in range(10)]  # the last of a comma-separated list
    assert complete("txtool migrate --select tx30") == [f"plain,TX30{n}" for n in range(7)]
    assert complete("txtool rules TX10")[:2] == ["plain,TX100", "plain,TX101"]
    assert complete("txtool rules zero") == ["plain,zero-reduction"]
