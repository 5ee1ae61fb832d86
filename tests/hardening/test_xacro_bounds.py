"""Every bound of the untrusted xacro evaluator, as tables: just inside, at, just outside.

The restricted evaluator (``txtool/io/xacro_eval.py``) refuses a value too large before it
builds it, and charges every step to the file's budget of work (``Meter``), so that any small
file is refused in well under a second or expands. The tables below run the evaluator in this
process (each bound is the evaluator's own); a few cases run the whole command, and the child
process's own limits (time, memory, nodes, output, the variables that set them) end the file.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli
from txtool.io.xacro import expand_text
from txtool.io.xacro_eval import (
    MAX_DIGITS,
    MAX_INT_BITS,
    MAX_LENGTH,
    MAX_WIDTH,
    MAX_WORK,
    EvalRefused,
    Meter,
    WorkLimit,
    evaluate,
    make_globals,
    metered,
)
from txtool.io.xacro_guard import MAX_NODES, Refusal, XacroGuard, tokenize
from txtool.io.xacro_sandbox import DEFAULT_MEMORY_MB, DEFAULT_TIMEOUT, limits
from txtool.io.xmlio import XacroOptions

OK = "ok"
# The time bounds are the shipped program's; under a line tracer (coverage, as .ci/run measures
# the suite) every Python line of the evaluator costs two to three times as much.
TRACED = 3.0 if sys.gettrace() is not None or "coverage" in sys.modules else 1.0
W, L, B, D = MAX_WIDTH, MAX_LENGTH, MAX_INT_BITS, MAX_DIGITS

# (expression, OK or a part of the refusal): for each bound the value just inside, at, and
# just outside it. Widths in every syntax of a format (literal, flags, nested %(key), '*',
# precision, str.format, f-string, padding methods), integer sizes through every operator
# and function that grows them, lengths, digits of round().
BOUNDS = {
    # -- % format: width and precision, with and without keys --------------------------------
    "% width inside": (f"'%{W - 1}d' % 1", OK),
    "% width at": (f"'%{W}d' % 1", OK),
    "% width outside": (f"'%{W + 1}d' % 1", "wider than"),
    "% width with flags": (f"'%-+ #0{W + 1}d' % 1", "wider than"),
    "% precision at": (f"'%.{W}f' % 1.5", OK),
    "% precision outside": (f"'%.{W + 1}f' % 1.5", "wider than"),
    "% star width": ("'%*d' % (5, 1)", "wider than"),
    "% star precision": ("'%.*f' % (5, 1.5)", "wider than"),
    "% keyed width at": (f"'%(a)-{W}s' % {{'a': 1}}", OK),
    "% keyed width outside": (f"'%(a){W + 1}s' % {{'a': 1}}", "wider than"),
    "% nested key at": (f"'%(a(b)c){W}d' % {{'a(b)c': 1}}", OK),
    "% nested key outside": (f"'%(a(b)c){W + 1}d' % {{'a(b)c': 1}}", "wider than"),
    "% deeper key outside": (f"'%(a(b(c))d){W + 1}d' % {{'a(b(c))d': 1}}", "wider than"),
    "% second field outside": (f"'%s%(k){W + 1}d' % {{'k': 1}}", "wider than"),
    "% after %% outside": (f"'%%%{W + 1}d' % 1", "wider than"),
    "% thousands of digits": ("'%" + "9" * 5000 + "d' % 1", "wider than"),
    # -- str.format, f-strings, padding ------------------------------------------------------
    "format at": (f"'{{:{W}}}'.format(1)", OK),
    "format outside": (f"'{{:{W + 1}}}'.format(1)", "wider than"),
    "format precision outside": (f"'{{:.{W + 1}f}}'.format(1.5)", "wider than"),
    "format nested spec": ("'{:{}}'.format(1, 5)", "nested format field"),
    "f-string at": (f"f'{{1:{W}}}'", OK),
    "f-string outside": (f"f'{{1:{W + 1}}}'", "wider than"),
    "f-string spec from a value": (f"f'{{1:{{{W + 1}}}}}'", "wider than"),
    "center at": (f"'a'.center({W + 1})", OK),
    "center outside": (f"'a'.center({W + 2})", "wider than"),
    "zfill outside": (f"'1'.zfill({W + 2})", "wider than"),
    "ljust outside": (f"'a'.ljust({W + 2})", "wider than"),
    # -- integers ----------------------------------------------------------------------------
    "power at": (f"2 ** {B // 2}", OK),
    "power outside": (f"2 ** {B // 2 + 1}", "over 4096 bits"),
    "large base, small exponent inside": ("(2 ** 1000) ** 4", OK),
    "large base, small exponent at": ("(2 ** 1023) ** 4", OK),
    "large base, small exponent outside": ("(2 ** 1024) ** 4", "over 4096 bits"),
    "pow() outside": (f"python.pow(2, {B // 2 + 1})", "over 4096 bits"),
    "pow() with modulo None": ("python.pow(2, 10**9, None)", "over 4096 bits"),
    "pow() with a modulo": ("python.pow(2, 10**9, 7)", OK),
    "shift at": (f"1 << {B - 1}", OK),
    "shift outside": (f"1 << {B}", "over 4096 bits"),
    "product at": ("(2 ** 2047) * (2 ** 2047)", OK),
    "product outside": ("(2 ** 2048) * (2 ** 2047)", "over 4096 bits"),
    "math.prod inside": ("math.prod(range(1, 400))", OK),
    "math.prod outside": ("math.prod(range(1, 10**6))", "over 4096 bits"),
    "math.prod at the bits": (f"math.prod([2] * {B - 1})", OK),
    "math.prod over the bits": (f"math.prod([2] * {B})", "over 4096 bits"),
    "factorial at": ("math.factorial(500)", OK),
    "factorial argument outside": ("math.factorial(1001)", "factorial() of a number over"),
    "comb argument outside": ("math.comb(1001, 2)", "comb() of a number over"),
    "perm argument outside": ("math.perm(1001, 2)", "perm() of a number over"),
    "lcm argument outside": ("math.lcm(1001, 2)", "lcm() of a number over"),
    # -- rounding digits ---------------------------------------------------------------------
    "round digits at": (f"round(5, -{D})", OK),
    "round digits outside": (f"round(5, -{D + 1})", "round() to more than"),
    "round huge negative digits": ("round(10**1000, -10**8)", "round() to more than"),
    "round float digits outside": (f"python.round(1.5, {D + 1})", "round() to more than"),
    # -- lengths -----------------------------------------------------------------------------
    "string at": (f"python.len('ab' * {L // 2})", OK),
    "string outside": (f"'ab' * {L // 2 + 1}", "more than 1000000 items"),
    "list at": (f"python.len([0] * {L // 2})", OK),
    "list outside": (f"[0] * {L // 2 + 1}", "more than 1000000 items"),
    "range at": (f"python.len(range({L}))", OK),
    "range outside": (f"range({L + 1})", "more than 1000000 items"),
    # [range(1000)] is 1002 items (the list, the range, its 1000 numbers)
    "ranges in a list at": (f"python.sum(python.map(python.sum, [range(1000)] * {L // 1002}))",
                            OK),
    "ranges in a list outside": (f"[range(1000)] * {L // 1002 + 1}", "more than 1000000 items"),
    "nested sum of maps": ("python.sum(python.map(python.sum, [range(10**6)] * 900))",
                           "more than 1000000 items"),
    "map of a long list": (f"python.sum(python.map(python.len, ['a' * {L}] * {L}))",
                           "more than 1000000 items"),
    "zip outside": (f"python.zip(range({L}), range({L}))", "more than 1000000 items"),
    "replace outside": (f"('a' * {L // 2 + 1}).replace('a', 'aa')", "more than 1000000"),
    "join outside": (f"'--'.join(['a'] * {L // 2})", "more than 1000000"),
}


def refusal_of(expression: str, budget: int = MAX_WORK) -> str:
    """OK, or the reason the evaluator gave; within ``budget`` steps."""
    try:
        with metered(Meter(budget)):
            evaluate(expression, make_globals({}))
    except (EvalRefused, WorkLimit) as exc:
        return str(exc)
    return OK


@pytest.mark.parametrize(("expression", "expected"), BOUNDS.values(), ids=BOUNDS.keys())
def test_each_bound_inside_at_and_outside(expression, expected):
    start = time.process_time()
    said = refusal_of(expression)
    assert (said == OK) if expected == OK else (expected in said), said
    assert time.process_time() - start < 1.0 * TRACED


def cost_of(expression: str) -> int:
    meter = Meter(10**12)
    with metered(meter):
        evaluate(expression, make_globals({}))
    return meter.budget - meter.left


# Expressions whose cost is in their size: the budget is spent by what they read and make.
PRICED = ["python.sum(range(1000))", "python.sorted(range(5000))", "'x' * 100000",
          "python.len(python.map(str, range(300)))", "[[0] * 100] * 100 == [[0] * 100] * 100",
          "'a,b;c'.split(',')"]


@pytest.mark.parametrize("expression", PRICED)
def test_a_budget_holds_at_its_exact_cost(expression):
    """Every step is charged: at the expression's cost it runs, one step less it stops."""
    cost = cost_of(expression)
    assert cost > 1
    assert refusal_of(expression, cost) == OK
    assert refusal_of(expression, cost - 1) == f"{cost - 1} steps of work"


def test_the_cost_follows_the_size():
    assert cost_of("python.sum(range(100000))") > 9 * cost_of("python.sum(range(10000))")
    assert cost_of("'x' * 100000") > 9 * cost_of("'x' * 10000")
    assert cost_of("python.sorted(range(5000)) == python.sorted(range(5000))") > 20000


# Work no single bound catches: each operation within its own size, many of them.
WORK = {
    "sorted twice and compared": "python.sorted(range(999999)) == python.sorted(range(999999))",
    "deep compare": "[[0] * 999] * 1000 == [[0] * 999] * 1000",
    "many sums": " + ".join(["python.sum(range(999999))"] * 30),
    "a % template of many fields": "python.len(('%s' * 499999) % python.tuple(range(499999)))",
    "a % template of %%": "python.len(('%%' * 499999) % ())",
    "a format template of many fields": "python.len(('{0}' * 333333).format(1)) * 0 + "
                                        "python.len(('{0}' * 333333).format(1))",
    "repeated deep sizes": "python.len(str([[0] * 999] * 1000) * 1)",
    "a long pipeline": ("python.len(python.list(python.map(str, python.filter(None, "
                        "python.map(python.abs, range(999999))))))"),
}


@pytest.mark.parametrize("expression", WORK.values(), ids=WORK.keys())
def test_work_past_the_budget_stops_within_a_second(expression):
    start = time.process_time()
    said = refusal_of(expression)
    assert said in (OK, f"{MAX_WORK} steps of work") or "more than" in said
    assert time.process_time() - start < 1.5 * TRACED


# -- xacro.tokenize: the separator is text ---------------------------------------------------

@pytest.mark.parametrize(("text", "sep", "expected"), [
    ("a,b; c", ",; ", ["a", "b", "c"]),                 # upstream's default, as upstream
    ("a|b|c", "|", ["a", "b", "c"]),
    ("a]b[c", "][", ["a", "b", "c"]),                  # class brackets are characters
    ("a-b^c", "^-", ["a", "b", "c"]),                  # a range or negation would differ
    ("x" * 5000 + "y", "(x+)+z", ["y"]),               # a backtracking pattern upstream
    ("abc", "", ["abc"]),
])
def test_tokenize_splits_on_the_characters_of_its_separator(text, sep, expected):
    start = time.process_time()
    assert tokenize(text, sep) == expected
    assert time.process_time() - start < 0.1 * TRACED


def test_tokenize_agrees_with_upstream_for_plain_separators():
    import xacro

    for text, sep in [("a, b;c", ",; "), ("1 2  3", " "), ("a:b", ":")]:
        assert tokenize(text, sep) == xacro.tokenize(text, sep)
        assert tokenize(text, sep, False) == xacro.tokenize(text, sep, False)


# -- whole expansions: macros, nodes, work per file -------------------------------------------

def robot(body: str) -> str:
    return ('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            f"  <link name=\"base\"/>\n{body}\n</robot>\n")


def fan_out(levels: int, width: int, leaf: str) -> str:
    macros = [f'<xacro:macro name="m0" params="">{leaf}</xacro:macro>']
    for level in range(1, levels + 1):
        macros.append(f'<xacro:macro name="m{level}" params="">'
                      + f"<xacro:m{level - 1}/>" * width + "</xacro:macro>")
    return "\n".join(macros) + f"\n<xacro:m{levels}/>"


@pytest.fixture
def repo(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    root = tmp_path / "repo"
    (root / ".git").mkdir(parents=True)
    monkeypatch.chdir(root)
    monkeypatch.delenv("TXTOOL_NO_XACRO", raising=False)
    for name in ("TXTOOL_XACRO_TIMEOUT", "TXTOOL_XACRO_MEMORY_MB"):
        monkeypatch.delenv(name, raising=False)
    return root


def guarded(repo: Path, body: str) -> tuple[str, XacroGuard]:
    path = repo / "robot.urdf.xacro"
    path.write_text(robot(body))
    guard = XacroGuard(str(path), XacroOptions(), {})
    try:
        return expand_text(str(path), str(path), XacroOptions(), guard), guard
    except (Refusal, WorkLimit, EvalRefused) as exc:
        return f"refused: {exc}", guard
    except Exception as exc:  # noqa: BLE001 - NodeLimit and xacro's own errors
        return f"refused: {type(exc).__name__} {exc}", guard


# A small file, and what it asks for: every one ends in well under a second (CPU).
EXPANSIONS = {
    "a 2^15-node fan-out": (fan_out(15, 2, "<a/>"), "steps of work"),
    "a 10^4 fan-out of width 10": (fan_out(4, 10, "<a/>"), "steps of work"),
    "a fan-out of big bodies": (fan_out(3, 10, "<g>" + "<a/>" * 400 + "</g>"), "NodeLimit"),
    "a fan-out of evaluations": (fan_out(12, 2, '<a n="${python.sum(range(999))}"/>'),
                                 "steps of work"),
    "a fan-out of long values": ('<xacro:property name="big" value="${\'_\' * 999000}" '
                                 'lazy_eval="false"/>' + fan_out(3, 10, '<a n="${big}"/>'),
                                 "steps of work"),
    "tokenize with a backtracking separator": (
        '<xacro:property name="s" value="${\'a\' * 1500}"/>'
        '<a n="${xacro.tokenize(s, \'(a+)+b\')}"/>', OK),
    "a block re-read with many $ tokens": (  # xacro's lexer copies the rest at each token
        '<xacro:property name="big" value="${(\'a$\' + \'$\' + \'{\') * 240000}"/>'
        '<xacro:macro name="m" params="*b"><xacro:insert_block name="b"/></xacro:macro>'
        "<xacro:m><t>${big}</t></xacro:m>", "steps of work"),
    "a block re-read with fewer $ tokens": (
        '<xacro:property name="big" value="${(\'a$\' + \'$\' + \'{\') * 1000}"/>'
        '<xacro:macro name="m" params="*b"><xacro:insert_block name="b"/></xacro:macro>'
        "<xacro:m><t>${big}</t></xacro:m>", OK),
    "a 2^10 fan-out": (fan_out(10, 2, "<a/>"), OK),
}


@pytest.mark.parametrize(("body", "expected"), EXPANSIONS.values(), ids=EXPANSIONS.keys())
def test_a_small_file_is_refused_or_expands_within_a_second(repo, body, expected):
    assert len(robot(body).encode()) < 3000
    start = time.process_time()
    text, _ = guarded(repo, body)
    elapsed = time.process_time() - start
    assert (not text.startswith("refused")) if expected == OK else (expected in text), text
    assert elapsed < 1.5 * TRACED


def test_the_node_budget_inside_at_and_outside(repo):
    """Clones counted one by one: a fan-out of exactly MAX_NODES cloned nodes expands, one
    node more is refused."""
    def body(calls: int, last: int) -> str:  # each call clones its body: <g> and its children
        return ('<xacro:macro name="m" params=""><g>' + "<a/>" * 99 + "</g></xacro:macro>"
                + '<xacro:macro name="n" params=""><g>' + "<a/>" * (last - 2) + "</g></xacro:macro>"
                + "<h><xacro:m/></h>" * calls + "<h><xacro:n/></h>")

    per_call = 101  # the macro call's body element and its <g> and 99 <a/>
    calls = MAX_NODES // per_call - 1
    left = MAX_NODES - calls * per_call  # what the last call, of n, clones at the bound
    text, guard = guarded(repo, body(calls, left))
    assert not text.startswith("refused") and guard.nodes == 0
    text, _ = guarded(repo, body(calls, left + 1))
    assert text == "refused: NodeLimit "


# -- the child's limits, read from the job's environment ---------------------------------------

LIMIT_VALUES = {  # value: OK (the number) or the refusal's end
    "TXTOOL_XACRO_TIMEOUT": {
        "0.001": 0.001, "3600": 3600.0, "30": 30.0,
        "0": "seconds above 0 to 3600", "-1": "seconds above 0 to 3600",
        "3600.001": "seconds above 0 to 3600", "nan": "seconds above 0 to 3600",
        "inf": "seconds above 0 to 3600", "-inf": "seconds above 0 to 3600",
        "1e300": "seconds above 0 to 3600", "soon": "seconds above 0 to 3600",
        "": "seconds above 0 to 3600", "0x10": "seconds above 0 to 3600",
    },
    "TXTOOL_XACRO_MEMORY_MB": {
        "64": 64, "1048576": 1048576, "512.9": 512,
        "63.9": "MiB from 64 to 1.04858e+06", "0": "MiB from 64 to 1.04858e+06",
        "-512": "MiB from 64 to 1.04858e+06", "1048577": "MiB from 64 to 1.04858e+06",
        "nan": "MiB from 64 to 1.04858e+06", "inf": "MiB from 64 to 1.04858e+06",
        "1e300": "MiB from 64 to 1.04858e+06", "lots": "MiB from 64 to 1.04858e+06",
    },
}
LIMIT_CASES = [(name, value, expected) for name, table in LIMIT_VALUES.items()
               for value, expected in table.items()]


@pytest.mark.parametrize(("name", "value", "expected"), LIMIT_CASES,
                         ids=[f"{n}={v!r}" for n, v, _ in LIMIT_CASES])
def test_each_limit_variable_is_a_number_in_its_range(monkeypatch, name, value, expected):
    from txtool.io.xmlio import InputError

    monkeypatch.setenv(name, value)
    index = 0 if name == "TXTOOL_XACRO_TIMEOUT" else 1
    if isinstance(expected, str):
        with pytest.raises(InputError) as raised:
            limits()
        assert str(raised.value) == f"{name}={value!r}: expected a number of {expected}"
    else:
        assert limits()[index] == expected


def test_the_defaults_without_the_variables(monkeypatch):
    monkeypatch.delenv("TXTOOL_XACRO_TIMEOUT", raising=False)
    monkeypatch.delenv("TXTOOL_XACRO_MEMORY_MB", raising=False)
    assert limits() == (DEFAULT_TIMEOUT, DEFAULT_MEMORY_MB)


@pytest.mark.parametrize("value", ["inf", "1e300", "nan", "0"])
def test_a_bad_limit_is_one_line_from_the_command(repo, monkeypatch, value):
    monkeypatch.setenv("TXTOOL_XACRO_MEMORY_MB", value)
    (repo / "robot.urdf.xacro").write_text(robot('<link name="x"/>'))
    line = (f"txtool: TXTOOL_XACRO_MEMORY_MB={value!r}: expected a number of MiB from 64 to "
            "1.04858e+06\n")
    result = CliRunner().invoke(cli, ["show", "robot.urdf.xacro"], catch_exceptions=False)
    assert (result.exit_code, result.stdout, result.stderr) == (2, "", line)
    result = CliRunner().invoke(cli, ["validate", "robot.urdf.xacro"], catch_exceptions=False)
    assert (result.exit_code, result.stderr) == (2, line)


def test_the_work_limit_is_one_line_from_the_command(repo):
    (repo / "robot.urdf.xacro").write_text(robot(fan_out(15, 2, "<a/>")))
    start = time.monotonic()
    result = CliRunner().invoke(cli, ["show", "robot.urdf.xacro"], catch_exceptions=False)
    assert (result.exit_code, result.stdout, result.stderr) == (
        2, "", f"txtool: robot.urdf.xacro: xacro: expansion exceeded {MAX_WORK} steps of work "
        "(a safety limit)\n")
    assert time.monotonic() - start < 20  # wall time on a loaded machine; CPU: see above

