"""The untrusted xacro path's bounds as tables: inside, at and outside each, and the odd values.

Beside ``test_xacro_bounds.py`` (the evaluator's widths, sizes and lengths), this covers what
a bound there leaves open: the values at each remaining bound (concatenation, replacement,
nested sizes, function arguments, expression length, nesting depth, what one expansion
reads, YAML nodes, output bytes), the work each expensive function is charged (an expression
that costs more than the budget only through that charge must stop), the memory bound shared
by a command's processes for 0, negative and large counts, and one worker reused across files
(what one file's request set must not carry into the next).
"""

from __future__ import annotations

import contextlib
from pathlib import Path
from typing import Any

import pytest

from tests.hardening.hostile_inputs import xacro_robot as robot
from txtool.io import packages
from txtool.io import xacro as xacro_support
from txtool.io.packages import packages_below
from txtool.io.xacro import expand_text
from txtool.io.xacro_eval import (
    MAX_EXPRESSION,
    MAX_LENGTH,
    MAX_WORK,
    EvalRefused,
    Meter,
    WorkLimit,
    evaluate,
    make_globals,
    metered,
)
from txtool.io.xacro_guard import MAX_YAML_NODES, YAML_STEPS_PER_BYTE, Refusal, XacroGuard
from txtool.io.xmlio import XacroError, XacroOptions

OK = "ok"
L = MAX_LENGTH
BIG = 2**4095 - 1  # the largest integer the evaluator holds


def verdict(expression: str, names: dict[str, Any] | None = None, budget: int = MAX_WORK) -> str:
    """OK, the evaluator's refusal, or the name of Python's own error."""
    try:
        with metered(Meter(budget)):
            evaluate(expression, {**make_globals({}), **(names or {})})
    except (EvalRefused, WorkLimit) as exc:
        return str(exc)
    except Exception as exc:  # noqa: BLE001 - Python's errors, as xacro reports them
        return type(exc).__name__
    return OK


TOO_LONG = f"more than {L} items"
# (expression, OK or a part of the answer): the bounds test_xacro_bounds.py has no value at,
# and 0, negative, nan, inf and non-numbers where a function reads a number.
EDGES = {
    "1 to a huge power": ("1 ** 10**9", OK),
    "-1 to a huge power": ("(-1) ** 10**9", OK),
    "0 to a huge power": ("0 ** 10**9", OK),
    "concatenation at": (f"python.len('a' * {L // 2} + 'a' * {L // 2})", OK),
    "concatenation outside": (f"'a' * {L // 2} + 'a' * {L // 2 + 1}", TOO_LONG),
    # [x, s]: its size is 1 + the size of x + len(s); s is counted before x
    "a list and its string at": (f"python.len(['b', 'a' * {L - 2}])", OK),
    "a list and its string outside": (f"['b', 'a' * {L - 1}]", TOO_LONG),
    "a list made by a function outside": (f"python.list(['b', 'a' * {L - 1}])", TOO_LONG),
    "replace at": (f"python.len(('a' * {L // 2}).replace('a', 'aa'))", OK),
    "replace outside": (f"('a' * {L // 2 + 1}).replace('a', 'aa')", TOO_LONG),
    "replace with a count at": (f"python.len(('a' * {L - 1}).replace('a', 'aa', 1))", OK),
    "comb at": ("math.comb(1000, 2)", OK),
    "comb outside": ("math.comb(1001, 2)", "comb() of a number over 1000"),
    "lcm negative outside": ("math.lcm(-1001, 2)", "lcm() of a number over 1000"),
    "perm at": ("math.perm(1000, 1)", OK),
    "repetition by 0": ("'ab' * 0", OK),
    "repetition by a negative": ("'ab' * -5", OK),
    "repetition by a float": ("'ab' * 2.0", "TypeError"),
    "padding to a negative width": ("'a'.center(-1)", OK),
    "padding to inf": ("'a'.center(math.inf)", "wider than 1000"),
    "round to nan digits": ("round(1.5, math.nan)", "TypeError"),
    "round of inf": ("round(math.inf)", "OverflowError"),
    "round of nan to digits at the bound": ("python.round(math.nan, 4096)", OK),
    "range of inf": ("range(math.inf)", "TypeError"),
    "range of a negative": ("python.len(range(-5))", OK),
    "a power to inf": ("python.pow(2.0, math.inf)", OK),
    "a shift by a negative": ("1 << -1", "ValueError"),
    "factorial of a string": ("math.factorial('5')", "TypeError"),
    "a name of two underscores": ("__builtins__", "the name '__builtins__' is not allowed"),
    "a name of three underscores": ("___x", "the name '___x' is not allowed"),
    "a name of one underscore": ("_x", "NameError"),
    "a width from a string": ("'a'.center('5')", "TypeError"),
}


@pytest.mark.parametrize(("expression", "expected"), EDGES.values(), ids=EDGES.keys())
def test_each_edge_of_the_evaluator(expression, expected):
    said = verdict(expression)
    assert (said == OK) if expected == OK else (expected in said), said


@pytest.mark.parametrize(("padding", "expected"), [
    (0, OK), (MAX_EXPRESSION - 3, OK), (MAX_EXPRESSION - 2, OK),
    (MAX_EXPRESSION - 1, f"more than {MAX_EXPRESSION}"),
])
def test_the_expression_length_inside_at_and_outside(padding, expected):
    """Counted after stripping, as xacro strips: spaces around it never count."""
    expression = "  '" + "a" * padding + "'  "
    said = verdict(expression)
    assert (said == OK) if expected == OK else (expected in said), said


# Work charged by one function or operation: n terms cost more than the budget only through
# that charge (every other charge together is well under it), n // 2 terms are within it.
BUDGET = 200_000
PRICED = {  # term, n, names
    "modular powers": ("python.pow(3, a, a)", 8, {"a": 2**1023 - 1}),
    "what functions return": ("python.len(t.replace('a', 'bb'))", 50, {"t": "a" * 16000}),
    "the string a method reads": ("s.count('y')", 40, {"s": "x" * 99999}),
    "arithmetic on large integers": ("a // b", 400, {"a": BIG, "b": BIG // 3}),
    "the fields of a % template": ("python.len(t % r)", 2,
                                   {"t": "%.0s" * 12000, "r": tuple(range(12000))}),
    "the fields of a format template": ("python.len(t.format(''))", 3, {"t": "{0}" * 8000}),
}


@pytest.mark.parametrize(("term", "n", "names"), PRICED.values(), ids=PRICED.keys())
def test_each_expensive_function_is_charged(term, n, names):
    def terms(count: int) -> str:
        return "[" + ", ".join([term] * count) + "]"

    assert verdict(terms(n), names, BUDGET) == f"{BUDGET} steps of work"
    assert verdict(terms(n // 2), names, BUDGET) == OK


# -- whole expansions under the guard, in this process ------------------------------------------

def guarded(path: Path, options: XacroOptions | None = None,
            environment: dict[str, str] | None = None, data: bytes | None = None) -> str:
    """The expansion of ``path`` under the guard, or what stopped it, as one line."""
    options = options or XacroOptions()
    guard = XacroGuard(str(path), options, environment or {})
    try:
        return expand_text(str(path), path.name, options, guard, data)
    except Refusal as exc:
        return f"refused: {exc.reason}"
    except XacroError as exc:
        return f"failed: {exc.reason}"
    except WorkLimit as exc:
        return f"limit: {exc}"


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


NESTED = "nested more than 256 levels deep"


@pytest.mark.parametrize("where", ["the top file", "an include"])
@pytest.mark.parametrize(("depth", "expected"), [(255, OK), (256, OK), (257, NESTED)])
def test_the_nesting_depth_inside_at_and_outside(repo, where, depth, expected):
    """Counted with the root element, in every file xacro reads."""
    inner = "<a>" * (depth - 1) + "</a>" * (depth - 1)
    doc = f'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">{inner}</robot>\n'
    if where == "an include":
        write(repo / "deep.xacro", doc)
        doc = robot('<xacro:include filename="deep.xacro"/>')
    text = guarded(write(repo / "robot.urdf.xacro", doc))
    assert (not text.startswith(("refused", "failed"))) if expected == OK else expected in text


def read_in_all(size: int) -> str:
    return f"xacro would read more than {size} bytes in all"


@pytest.mark.parametrize(("spare", "expected"), [(1, OK), (0, OK), (-1, "more than")])
def test_what_one_expansion_reads_inside_at_and_outside(repo, monkeypatch, spare, expected):
    """The top file and each include, the same one twice too, against one budget; an editor's
    unsaved text for the top file counts as the file would."""
    part = write(repo / "part.xacro", robot('<link name="p"/>'))
    top = write(repo / "robot.urdf.xacro", robot('<xacro:include filename="part.xacro"/>' * 2))
    size = top.stat().st_size + 2 * part.stat().st_size
    monkeypatch.setattr(xacro_support, "MAX_READ", size + spare)
    text = guarded(top)
    assert ('name="p"' in text) if expected == OK else read_in_all(size + spare) in text, text
    unsaved = robot('<link name="unsaved"/>').encode()
    monkeypatch.setattr(xacro_support, "MAX_READ", len(unsaved) + spare)
    text = guarded(top, data=unsaved)
    assert ('name="unsaved"' in text) if expected == OK else read_in_all(len(unsaved) + spare) \
        in text, text


# -- load_yaml: its reading priced, a file read once, its nodes counted -------------------------

YAML_STEPS = MAX_WORK // YAML_STEPS_PER_BYTE  # bytes of YAML the budget holds, with nothing else


@pytest.mark.parametrize(("size", "expected"), [
    (YAML_STEPS * 96 // 100, OK), (YAML_STEPS + 1, "steps of work")])
def test_the_yaml_a_file_reads_is_priced_by_its_size(repo, size, expected):
    write(repo / "big.yaml", "a: " + "x" * (size - 4) + "\n")
    text = guarded(write(repo / "robot.urdf.xacro", robot(
        '<link name="${python.len(xacro.load_yaml(\'big.yaml\').a)}"/>')))
    assert (f'name="{size - 4}"' in text) if expected == OK else expected in text, text


def test_a_yaml_file_loaded_again_is_read_and_paid_once(repo):
    """Under any of its names: each load alone is over half the budget."""
    write(repo / "config" / "half.yaml", "a: " + "x" * (YAML_STEPS * 6 // 10) + "\n")
    (repo / "same").symlink_to(repo / "config")
    loads = [f"python.len(xacro.load_yaml('{name}').a)"
             for name in ("config/half.yaml", "./config/half.yaml", "same/half.yaml")]
    text = guarded(write(repo / "robot.urdf.xacro", robot(
        f'<link name="${{{" + ".join(loads)}}}"/>')))
    assert f'name="{3 * (YAML_STEPS * 6 // 10)}"' in text, text


def shared_lists(copies: int, items: int) -> str:
    """A YAML list of ``copies`` references to one list of ``items`` scalars: 1 + copies *
    (1 + items) nodes once its aliases are expanded."""
    first = "- &l [" + ", ".join(["x"] * items) + "]\n"
    return first + "- *l\n" * (copies - 1)


ALIASES = "once its aliases are expanded"


@pytest.mark.parametrize(("yaml", "expected"), [
    (shared_lists(999, 1000), OK),     # 1,000,000 nodes: the bound
    (shared_lists(1000, 999), ALIASES),  # 1,000,001
    ("a: &a [*a]\n", ALIASES),        # a cycle is as large as can be
    ("a: &a {b: *a}\n", ALIASES),
], ids=["at", "outside", "a list in itself", "a mapping in itself"])
def test_the_yaml_nodes_inside_at_and_outside(repo, yaml, expected):
    assert MAX_YAML_NODES == 1_000_000
    write(repo / "n.yaml", yaml)
    text = guarded(write(repo / "robot.urdf.xacro", robot(
        '<link name="${xacro.load_yaml(\'n.yaml\')[0][0]}"/>')))
    assert ('name="x"' in text) if expected == OK else expected in text, text


# -- $(find): hostile names through every variable, and where a package may come from ----------

SECRET = "s3cr3t-77c1"


def secret_package(folder: Path, name: str) -> Path:
    write(folder / "package.xml", f"<package><name>{name}</name></package>\n")
    write(folder / "secret.xacro", robot(f'<link name="{SECRET}"/>'))
    return folder


FIND = '<xacro:include filename="$(find NAME)/secret.xacro"/>'
# Names no ROS 2 package has (REP 127: two or more of letters, digits, '_' and '-'), which,
# joined to a prefix's folders, lead elsewhere: each prefix below holds, where the name leads,
# an index entry and a package of that name.
HOSTILE_NAMES = ["../evil", "../../evil", "x/../../evil", "sub/evil", "e", "evil.pkg",
                 "{tmp}/evil"]


def crafted_prefix(prefix: Path, name: str) -> None:
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    for base in (index, prefix / "share"):
        (base / "x").mkdir(parents=True, exist_ok=True)
    with contextlib.suppress(OSError):
        write(index / name, "")
    with contextlib.suppress(OSError):
        secret_package(prefix / "share" / name, name)


@pytest.mark.parametrize("variable", ["AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH"])
@pytest.mark.parametrize("name", HOSTILE_NAMES)
def test_a_name_no_package_has_finds_nothing_in_a_prefix(repo, monkeypatch, variable, name):
    name = name.format(tmp=repo.parent)
    crafted_prefix(repo.parent / "prefix", name)
    monkeypatch.setenv(variable, str(repo.parent / "prefix"))
    text = guarded(write(repo / "robot.urdf.xacro", robot(FIND.replace("NAME", name))))
    assert text.startswith(f"failed: package '{name}' not found"), text
    assert SECRET not in text


@pytest.mark.parametrize("variable", ["AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH",
                                      "ROS_PACKAGE_PATH"])
def test_a_package_of_the_ros_environment_is_read(repo, monkeypatch, variable):
    prefix = repo.parent / "prefix"
    secret_package(prefix / "share" / "evil", "evil")
    write(prefix / "share" / "ament_index" / "resource_index" / "packages" / "evil", "")
    monkeypatch.setenv(variable, str(prefix / "share" if variable == "ROS_PACKAGE_PATH"
                                     else prefix))
    assert SECRET in guarded(write(repo / "robot.urdf.xacro", robot(FIND.replace("NAME", "evil"))))


def test_a_package_in_a_hidden_folder_is_not_found(repo):
    secret_package(repo / ".cache" / "evil", "evil")
    text = guarded(write(repo / "robot.urdf.xacro", robot(FIND.replace("NAME", "evil"))))
    assert text.startswith("failed: package 'evil' not found"), text


def test_a_package_beside_a_package_outside_any_repository_is_not_read(tmp_path, monkeypatch):
    """With no repository, what may be read is the file's own package: a sibling package
    found by the crawl of its parent folder is no root."""
    monkeypatch.chdir(tmp_path)
    packages_below.cache_clear()
    assert not any((p / ".git").exists() for p in (tmp_path, *tmp_path.parents))
    secret_package(tmp_path / "pkgs" / "evil", "evil")
    own = secret_package(tmp_path / "pkgs" / "mine", "mine")
    text = guarded(write(own / "robot.urdf.xacro", robot(FIND.replace("NAME", "evil"))))
    assert text.startswith("refused: $(find evil) leads outside the repository"), text
    assert SECRET in guarded(write(own / "robot.urdf.xacro", robot(FIND.replace("NAME", "mine"))))


def test_a_repository_whose_git_is_a_file_is_one_root(repo):
    """A git worktree or submodule has a .git file: the checkout is still the repository."""
    (repo / ".git").rmdir()
    write(repo / ".git", "gitdir: ../elsewhere/.git/worktrees/repo\n")
    write(repo / "common" / "part.xacro", robot(f'<link name="{SECRET}"/>'))
    text = guarded(write(repo / "robots" / "robot.urdf.xacro", robot(
        '<xacro:include filename="../common/part.xacro"/>')))
    assert SECRET in text, text


@pytest.mark.parametrize(("folders", "found"), [(14, True), (13, True), (12, False)])
def test_the_crawl_for_a_package_stops_after_its_folders(repo, monkeypatch, folders, found):
    """The repository, ten empty folders, zz, then the package: the thirteenth folder."""
    monkeypatch.setattr(packages, "MAX_FOLDERS", folders)
    for index in range(10):
        (repo / f"f{index}").mkdir()
    secret_package(repo / "zz" / "evil", "evil")
    text = guarded(write(repo / "robot.urdf.xacro", robot(FIND.replace("NAME", "evil"))))
    assert (SECRET in text) if found else text.startswith("failed: package 'evil' not found")


# -- every substitution that reads the environment -----------------------------------------------

# xacro's lexer ends a $(...) at its first ')': a call in $(eval) comes from a property.
EVAL = '<xacro:property name="e" value="CALL"/><link name="$(eval ${e})"/>'
ENV_ROUTES = {  # body reading NAME: (what it gives without --xacro-env NAME, with it)
    "$(env)": ('<link name="$(env NAME)"/>', ("refused", 'name="value"')),
    "$(optenv)": ('<link name="v$(optenv NAME)"/>', ('name="v"', 'name="vvalue"')),
    "$(optenv) with a default": ('<link name="$(optenv NAME d)"/>',
                                 ('name="d"', 'name="value"')),
    "$(eval env())": (EVAL.replace("CALL", "env(\'NAME\')"), ("refused", 'name="value"')),
    "$(eval optenv())": (EVAL.replace("CALL", "optenv(\'NAME\', \'d\')"),
                         ('name="d"', 'name="value"')),
    "an include's name": ('<xacro:include filename="$(optenv NAME none).xacro"/>',
                          ('name="none_included"', 'name="value_included"')),
    "load_yaml's name": ('<link name="${xacro.load_yaml(\'$(optenv NAME none).yaml\').k}"/>',
                         ('name="none_loaded"', 'name="value_loaded"')),
}


@pytest.mark.parametrize("given", [False, True], ids=["not given", "given"])
@pytest.mark.parametrize("route", ENV_ROUTES)
def test_each_substitution_reads_only_a_variable_given(repo, route, given):
    for stem in ("none", "value"):
        write(repo / f"{stem}.xacro", robot(f'<link name="{stem}_included"/>'))
        write(repo / f"{stem}.yaml", f"k: {stem}_loaded\n")
    body, expected = ENV_ROUTES[route]
    options = XacroOptions(env=("NAME",) if given else ())
    text = guarded(write(repo / "robot.urdf.xacro", robot(body)), options,
                   {"NAME": "value", "OTHER": "other"})
    said = expected[given]
    assert (text.startswith("refused: ") if said == "refused" else said in text), text
    if not given:
        assert "value" not in text


# -- a folder beside the repository whose name begins with the repository's ---------------------

SIBLINGS = ["../repo-old/secret", "../repo2/secret", "../rep/secret", "{tmp}/repo-old/secret",
            "{tmp}/repo.bak/secret"]
FILE_ROUTES = {
    "include": lambda p: f'<xacro:include filename="{p}.xacro"/>',
    "load_yaml": lambda p: f'<link name="${{xacro.load_yaml(\'{p}.yaml\')}}"/>',
}


@pytest.mark.parametrize("route", FILE_ROUTES)
@pytest.mark.parametrize("name", SIBLINGS)
def test_a_sibling_sharing_the_repositorys_prefix_is_outside(repo, route, name):
    """Outside, not merely hidden: the repository's folder is no prefix of the sibling's."""
    for sibling in ("repo-old", "repo2", "rep", "repo.bak"):
        write(repo.parent / sibling / "secret.xacro", robot(f'<link name="{SECRET}"/>'))
        write(repo.parent / sibling / "secret.yaml", f"k: {SECRET}\n")
    path = FILE_ROUTES[route](name.format(tmp=repo.parent))
    text = guarded(write(repo / "robot.urdf.xacro", robot(path)))
    assert text.startswith("refused: ") and "is outside the repository" in text, text
    assert SECRET not in text


@pytest.mark.parametrize(("children", "expected"), [(4000, OK), (6000, f"{MAX_WORK} steps")])
def test_moving_a_macro_body_into_its_caller_is_priced_by_the_lists_it_scans(
        repo, children, expected):
    """Each child moved scans the list it leaves and the one it joins (minidom's C loops):
    quadratic in a body of many children, and stopped at the budget."""
    text = guarded(write(repo / "robot.urdf.xacro", robot(
        '<xacro:macro name="m" params="">' + "<a/>" * children + "</xacro:macro>"
        "<g><xacro:m/></g>")))
    assert (text.count("<a/>") == children) if expected == OK else expected in text, text[:200]


# Three sums: about 4,400,000 steps of the budget, whatever else the file does.
SUMS = ('<s a="${python.sum(range(999999))}" b="${python.sum(range(999999))}" '
        'c="${python.sum(range(200000))}"/>')


@pytest.mark.parametrize(("calls", "expected"), [(5, OK), (15, f"{MAX_WORK} steps")])
def test_each_cloned_node_is_priced(repo, calls, expected):
    """A macro body of 5,000 comments in one element: each call clones 5,002 nodes (well under
    the node bound at 15 calls), and moves one; what the clones cost decides."""
    text = guarded(write(repo / "robot.urdf.xacro", robot(
        '<xacro:macro name="m" params=""><g>' + "<!---->" * 5000 + "</g></xacro:macro>"
        + "<xacro:m/>" * calls + SUMS)))
    assert (text.count("<g>") == calls) if expected == OK else expected in text, text[:200]


@pytest.mark.parametrize(("calls", "expected"), [(1000, OK), (3000, f"{MAX_WORK} steps")])
def test_each_macro_call_is_priced(repo, calls, expected):
    """Calls of an empty macro, each in an element of its own (nothing cloned, no long list
    scanned): what the calls cost decides."""
    text = guarded(write(repo / "robot.urdf.xacro", robot(
        '<xacro:macro name="e" params=""/>' + "<p><xacro:e/></p>" * calls + SUMS)))
    assert (text.count("<p/>") == calls) if expected == OK else expected in text, text[:200]
