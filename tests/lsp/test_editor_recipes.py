"""docs/editors.md's recipes run as printed: each Neovim recipe whose range holds the installed
Neovim starts ``txtool lsp`` headless and shows the findings ``txtool validate`` gives; the
Emacs recipe under eglot and the Helix one under ``hx --health`` where those are installed."""

from __future__ import annotations

import os
import re
import shutil
import stat
import subprocess
import sys
from pathlib import Path

import pytest

import txtool

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[2]
PAGE = (ROOT / "docs" / "editors.md").read_text(encoding="utf-8")
BROKEN = ROOT / "fixtures" / "broken_robot.urdf"
RANGE = re.compile(r"-- Neovim (\d+)\.(\d+) (?:and later|to (\d+)\.(\d+))\n")

# Run in the opened buffer once the recipe has attached: wait for the findings and print them.
REPORT = """
vim.wait(60000, function() return #vim.diagnostic.get(0) > 0 end, 50)
local lines = {}
for _, d in ipairs(vim.diagnostic.get(0)) do
  table.insert(lines, string.format("%d %s %s", d.lnum + 1, tostring(d.code), d.source))
end
table.sort(lines, function(a, b) return tonumber(a:match("%d+")) < tonumber(b:match("%d+")) end)
io.stdout:write(vim.bo.filetype .. "\\n" .. table.concat(lines, "\\n") .. "\\n")
vim.cmd("qa!")
"""


def blocks(language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", PAGE, flags=re.S)


def neovim_recipes() -> list[tuple[tuple[int, int], tuple[int, int] | None, str]]:
    found = []
    for block in blocks("lua"):
        stated = RANGE.match(block)
        assert stated, f"a Neovim recipe without its range: {block[:60]!r}"
        low = (int(stated[1]), int(stated[2]))
        high = (int(stated[3]), int(stated[4])) if stated[3] else None
        found.append((low, high, block))
    return found


def neovim_version() -> tuple[int, int] | None:
    if shutil.which("nvim") is None:
        return None
    shown = subprocess.run(["nvim", "--version"], capture_output=True, text=True, check=True)
    major, minor = re.match(r"NVIM v(\d+)\.(\d+)", shown.stdout).groups()  # type: ignore[union-attr]
    return int(major), int(minor)


def txtool_on_path(tmp_path: Path) -> dict[str, str]:
    """The environment an editor starts ``txtool`` in: this checkout's, first on PATH."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    script = bin_dir / "txtool"
    script.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m txtool "$@"\n')
    script.chmod(script.stat().st_mode | stat.S_IXUSR)
    env = dict(os.environ, PATH=f"{bin_dir}{os.pathsep}{os.environ['PATH']}",
               PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT),
                                                        os.environ.get("PYTHONPATH")])),
               HOME=str(tmp_path), XDG_CONFIG_HOME=str(tmp_path / "config"))
    return env


def expected_findings(path: Path) -> list[str]:
    return sorted((f"{p.line} {p.code} txtool" for p in txtool.validate(path)),
                  key=lambda line: int(line.split()[0]))


def test_the_neovim_recipes_cover_every_version_from_debian_12s_on():
    recipes = neovim_recipes()
    for version in [(0, 7), (0, 8), (0, 9), (0, 10), (0, 11), (0, 12)]:
        fitting = [low for low, high, _ in recipes
                   if low <= version and (high is None or version <= high)]
        assert fitting, f"no recipe for Neovim {version[0]}.{version[1]}"


def test_every_neovim_recipe_is_lua_the_installed_neovim_compiles(tmp_path):
    """The recipes for other versions cannot run here; their Lua is compiled, not run."""
    if neovim_version() is None:
        pytest.skip("Neovim is not installed (apt-get install neovim)")
    for index, (_, _, recipe) in enumerate(neovim_recipes()):
        init = tmp_path / f"recipe{index}.lua"
        init.write_text(recipe)
        shown = subprocess.run(
            ["nvim", "--headless", "--clean", "-u", "NONE", "-c",
             f"lua local ok, why = loadfile('{init}'); io.stdout:write(tostring(why))",
             "-c", "qa!"], capture_output=True, text=True, timeout=60)
        assert (shown.returncode, shown.stdout) == (0, "nil"), recipe


def test_the_neovim_recipe_for_the_installed_neovim_shows_the_findings(tmp_path):
    version = neovim_version()
    if version is None:
        pytest.skip("Neovim is not installed (apt-get install neovim)")
    recipes = [block for low, high, block in neovim_recipes()
               if low <= version and (high is None or version <= high)]
    assert recipes, f"docs/editors.md has no recipe for Neovim {version[0]}.{version[1]}"
    project = tmp_path / "robot_description"
    (project / ".git").mkdir(parents=True)
    robot = project / "urdf" / "arm.urdf"  # .urdf: the recipe makes it XML
    robot.parent.mkdir()
    shutil.copy(BROKEN, robot)
    (tmp_path / "report.lua").write_text(REPORT)
    env = txtool_on_path(tmp_path)
    for index, recipe in enumerate(recipes):
        init = tmp_path / f"init{index}.lua"
        init.write_text(recipe)
        shown = subprocess.run(
            ["nvim", "--headless", "--clean", "-u", str(init), str(robot),
             "-c", f"luafile {tmp_path / 'report.lua'}"],
            cwd=project, env=env, capture_output=True, text=True, timeout=120)
        assert (shown.returncode, shown.stdout.splitlines()) == (
            0, ["xml", *expected_findings(robot)]), shown.stderr


ELISP_REPORT = """
(find-file (car command-line-args-left))
(setq command-line-args-left nil)
(eglot-ensure)
(run-hooks 'post-command-hook)  ; eglot-ensure connects after the command that opened the file
(let ((deadline (+ (float-time) 60)))
  (while (and (null (flymake-diagnostics)) (< (float-time) deadline))
    (accept-process-output nil 0.05)))
(princ (format "%s\\n" major-mode) #'external-debugging-output)
(dolist (line (sort (mapcar (lambda (d) (format "%d %s"
                                               (line-number-at-pos (flymake-diagnostic-beg d))
                                               (flymake-diagnostic-text d)))
                            (flymake-diagnostics))
                    (lambda (a b) (< (string-to-number a) (string-to-number b)))))
  (princ (format "%s\\n" line) #'external-debugging-output))
(kill-emacs 0)
"""


def test_the_emacs_recipe_shows_the_findings(tmp_path):
    if shutil.which("emacs") is None:
        pytest.skip("Emacs is not installed")
    has_eglot = subprocess.run(["emacs", "--batch", "--eval", "(require 'eglot)"],
                               capture_output=True)
    if has_eglot.returncode != 0:
        pytest.skip("Emacs without eglot (Emacs 29, or apt-get install elpa-eglot)")
    (recipe,) = blocks("elisp")
    robot = tmp_path / "arm.urdf"
    shutil.copy(BROKEN, robot)
    (tmp_path / "recipe.el").write_text(recipe)
    (tmp_path / "report.el").write_text(ELISP_REPORT)
    shown = subprocess.run(
        ["emacs", "--batch", "-l", str(tmp_path / "recipe.el"), "-l", str(tmp_path / "report.el"),
         str(robot)], cwd=tmp_path, env=txtool_on_path(tmp_path), capture_output=True,
        text=True, timeout=120)
    lines = [line for line in shown.stderr.splitlines()
             if line == "nxml-mode" or re.match(r"\d+ ", line)]
    codes = [f"{line.split()[0]} {code}" for line in lines[1:]
             for code in re.findall(r"TX\d{3}", line)[:1]]
    assert (shown.returncode, lines[:1], codes) == (
        0, ["nxml-mode"], [" ".join(e.split()[:2]) for e in expected_findings(robot)]), \
        shown.stderr


def test_the_helix_recipe_names_txtool_for_xml(tmp_path):
    (recipe,) = blocks("toml")
    settings = tomllib.loads(recipe)
    assert settings["language-server"]["txtool"] == {"command": "txtool", "args": ["lsp"]}
    (xml,) = settings["language"]
    assert (xml["name"], xml["language-servers"]) == ("xml", ["txtool"])
    assert {"urdf", "xacro"} <= set(xml["file-types"])
    if shutil.which("hx") is None:
        pytest.skip("Helix is not installed: the recipe was read, not run")
    config = tmp_path / "config" / "helix"
    config.mkdir(parents=True)
    (config / "languages.toml").write_text(recipe)
    shown = subprocess.run(["hx", "--health", "xml"], env=txtool_on_path(tmp_path),
                           capture_output=True, text=True, timeout=60)
    assert shown.returncode == 0 and re.search(r"txtool.*✓|✓.*txtool", shown.stdout), shown.stdout
