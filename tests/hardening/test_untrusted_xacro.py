"""A xacro file from a pull request is expanded without running its code.

By default txtool evaluates ``${...}`` and ``$(eval ...)`` with its own restricted evaluator,
passes ``$(env)`` only names the user allows, reads only files inside the repository and the
packages found, and expands in a child process with bounded time, memory, nodes and output
(``txtool/io/xacro_sandbox.py``). Each attack below ends in one line and exit 2, with nothing
executed (a marker file a successful attack would create stays absent) and nothing leaked.
``--trust-xacro`` is upstream xacro: the same attacks work there, which shows the tests can
fail.
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from lxml import etree

from tests.corpus import CORPUS, WORKSPACE
from txtool.cli import cli
from txtool.io.xacro import expand_text
from txtool.io.xacro_eval import EvalRefused, evaluate, make_globals
from txtool.io.xacro_guard import MAX_NODES
from txtool.io.xacro_sandbox import MAX_OUTPUT, expand_in_sandbox
from txtool.io.xmlio import XacroOptions

SECRET = "s3cr3t-value-9f8e7d"
SECONDS = 20.0  # every refusal below comes well within this (the default time limit is 30 s)


def robot(body: str) -> str:
    return ('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            f"  <link name=\"base\"/>\n{body}\n</robot>\n")


@pytest.fixture
def repo(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A repository (``.git``) with a file outside it, a secret in the environment."""
    root = tmp_path / "repo"
    (root / ".git").mkdir(parents=True)
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.yaml").write_text(f"token: {SECRET}\n")
    (outside / "secret.xacro").write_text(robot(f'<link name="{SECRET}"/>'))
    monkeypatch.chdir(root)
    monkeypatch.delenv("TXTOOL_NO_XACRO", raising=False)
    monkeypatch.setenv("FAKE_GITHUB_TOKEN", SECRET)
    monkeypatch.setenv("DEPLOY_NOTE", SECRET)
    return root


def run(*args: str) -> tuple[int, str, str, float]:
    start = time.monotonic()
    result = CliRunner().invoke(cli, list(args), catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr, time.monotonic() - start


def refused(repo: Path, body: str, *options: str) -> str:
    """Run ``show`` on a robot with ``body``: one line, exit 2, within the bound; the line."""
    path = repo / "robot.urdf.xacro"
    path.write_text(robot(body))
    code, out, err, elapsed = run("show", *options, str(path))
    assert (code, out) == (2, "")
    assert err.count("\n") == 1 and err.startswith(f"txtool: {path}"), err
    assert elapsed < SECONDS
    assert SECRET not in err
    return err


MARKER = "pwned.marker"
# Format templates hold braces, which cannot stand inside ${...}: xacro's own way is a property.
TEMPLATES = ('<xacro:property name="reach" value="{0.__globals__[os].system}"/>\n'
             '<xacro:property name="index" value="{0[0]}"/>\n'
             '<xacro:property name="wide" value="{:>999999999}"/>\n')
# Every spelling below would create MARKER (or reach code that could) if it ran.
CODE_EXECUTION = {
    "dunder chain": "${''.__class__.__mro__[1].__subclasses__()}",
    "__import__": "${__import__('os').system('touch " + MARKER + "')}",
    "open": "${open('" + MARKER + "', 'w').write('x')}",
    "exec": "${exec(\"open('" + MARKER + "', 'w')\")}",
    "getattr": "${getattr(str, 'mro')}",
    "format string": "${reach.format(xacro.message)}",
    "format index": "${index.format(python.list)}",
    "lambda": "${(lambda: 1)()}",
    "comprehension": "${[c for c in python.list((1, 2))]}",
    "generator": "${python.list(c for c in 'ab')}",
    "walrus": "${(x := 1)}",
    "function internals": "${xacro.load_yaml.function}",
    "namespace internals": "${math.sin.__call__}",
    "type": "${python.type(1)}",
    "vars": "${python.vars(xacro)}",
    "eval substitution": "$(eval open('" + MARKER + "', 'w'${close}",
    "eval builtins": "$(eval exec('x'${close}",
}


@pytest.mark.parametrize("expression", CODE_EXECUTION.values(), ids=CODE_EXECUTION.keys())
def test_code_execution_is_refused_and_nothing_runs(repo, expression):
    body = TEMPLATES + '<xacro:property name="close" value=")"/>\n' \
        f'<link name="{expression.replace(chr(34), "&quot;")})"/>'
    err = refused(repo, body)
    assert "xacro: " in err and ("is not allowed" in err or "is not defined" in err), err
    assert not (repo / MARKER).exists()


def test_upstream_xacro_runs_the_same_file_under_trust(repo):
    """The check above can fail: upstream ``$(eval)`` has Python's builtins."""
    body = '<xacro:property name="close" value=")"/>\n' \
           f"<link name=\"$(eval open('{MARKER}', 'w'${{close}}.close(${{close}})\"/>"
    refused(repo, body)
    assert not (repo / MARKER).exists()
    path = repo / "robot.urdf.xacro"
    run("show", "--trust-xacro", str(path))
    assert (repo / MARKER).exists()


LEAKS = {
    "env": '<link name="$(env DEPLOY_NOTE)"/>',
    "env of a secret name": '<link name="$(env FAKE_GITHUB_TOKEN)"/>',
    "format string": '<xacro:property name="fmt" value="{0.__globals__[os].environ}"/>'
                     '<link name="${fmt.format(xacro.message)}"/>',
    "include outside": '<xacro:include filename="../outside/secret.xacro"/>',
    "load_yaml outside": '<link name="${xacro.load_yaml(\'../outside/secret.yaml\').token}"/>',
}


@pytest.mark.parametrize("body", LEAKS.values(), ids=LEAKS.keys())
@pytest.mark.parametrize("output_format", ["text", "json", "github", "sarif"])
def test_no_secret_reaches_any_output(repo, body, output_format):
    path = repo / "robot.urdf.xacro"
    path.write_text(robot(body))
    code, out, err, _ = run("validate", "--format", output_format, str(path))
    assert code == 2
    assert SECRET not in out + err
    assert f"{path}:" in err and "xacro:" in err


def test_the_format_string_leak_is_real_under_trust(repo):
    path = repo / "robot.urdf.xacro"
    path.write_text(robot(LEAKS["format string"]))
    _, out, _, _ = run("show", "--format", "json", "--trust-xacro", str(path))
    assert SECRET not in out  # the link name holds it, show prints transmissions only
    text = expand_text(str(path), str(path), XacroOptions(trust=True))
    assert SECRET in text


def test_env_names_a_line_and_the_way_out(repo):
    err = refused(repo, '<link name="a"/>\n<link name="$(env DEPLOY_NOTE)"/>')
    assert err == (f"txtool: {repo / 'robot.urdf.xacro'}:5: xacro: $(env DEPLOY_NOTE) is not "
                   "allowed (only names given with --xacro-env are read; see --trust-xacro)\n")


def test_optenv_takes_its_default_unless_allowed(repo):
    path = repo / "robot.urdf.xacro"
    path.write_text(robot('<link name="$(optenv DEPLOY_NOTE fallback)"/>'))
    text = expand_in_sandbox(str(path), str(path), XacroOptions())
    assert 'name="fallback"' in text and SECRET not in text
    text = expand_in_sandbox(str(path), str(path), XacroOptions(env=("DEPLOY_NOTE",)))
    assert f'name="{SECRET}"' in text


def test_allowed_env_from_the_command_line_never_from_the_configuration(repo, monkeypatch):
    monkeypatch.setenv("ROBOT_MODEL", "ur5e")
    path = repo / "robot.urdf.xacro"
    path.write_text(robot(TRANSMISSION.replace("JOINT", "$(env ROBOT_MODEL)_joint")))
    code, out, _, _ = run("show", "--format", "json", "--xacro-env", "ROBOT_MODEL", str(path))
    assert code == 0 and '"ur5e_joint"' in out
    code, out, err, _ = run("show", str(path))
    assert code == 2 and "$(env ROBOT_MODEL) is not allowed" in err
    # a pull request's configuration cannot name what leaves the machine: one line, exit 2
    (repo / ".txtool.toml").write_text('xacro-env = ["ROBOT_MODEL", "FAKE_GITHUB_TOKEN"]\n')
    path.write_text(robot('<link name="$(env FAKE_GITHUB_TOKEN)"/>'))
    for command in ("validate", "show"):
        code, out, err, _ = run(command, str(path))
        assert (code, out) == (2, "") and err == (
            f"txtool: {repo / '.txtool.toml'}: key 'xacro-env': the environment variables "
            "$(env) may read are named on the command line (--xacro-env NAME), never in a "
            "file of the repository\n")


TRANSMISSION = """<transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="JOINT"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>10</mechanicalReduction></actuator>
  </transmission>"""


def test_files_outside_the_repository_are_refused(repo, tmp_path):
    (repo / "inside.xacro").write_text(robot('<link name="inside"/>'))
    (repo / "inside.yaml").write_text("a: {b: 3}\n")
    (repo / "link.xacro").symlink_to(tmp_path / "outside" / "secret.xacro")
    path = repo / "robot.urdf.xacro"
    path.write_text(robot('<xacro:include filename="inside.xacro"/>\n'
                          '<link name="${xacro.load_yaml(\'inside.yaml\').a.b}"/>'))
    text = expand_in_sandbox(str(path), str(path), XacroOptions())
    assert 'name="inside"' in text and 'name="3"' in text
    for body in ('<xacro:include filename="/etc/passwd"/>',
                 '<xacro:include filename="../../outside/../outside/secret.xacro"/>',
                 '<xacro:include filename="link.xacro"/>',
                 '<link name="${xacro.load_yaml(\'/etc/hostname\')}"/>'):
        err = refused(repo, body)
        assert "is outside the repository and the packages found" in err


DENIAL_OF_SERVICE = {
    "exponent": ('<link name="${9**9**9}"/>', "a number over 4096 bits (a safety limit)"),
    "eval exponent": ('<link name="$(eval 9**9**9)"/>', ":4: xacro: a number over 4096 bits"),
    "pow()": ('<link name="${python.pow(10, 10**8)}"/>', "a number over 4096 bits"),
    "shift": ('<link name="${1 &lt;&lt; 10**9}"/>', "a number over 4096 bits"),
    "string repetition": ('<link name="${\'a\' * 10**10}"/>', "more than 1000000 items"),
    "list repetition": ('<link name="${[[0] * 1000] * 10**6}"/>', "more than 1000000 items"),
    "percent width": ('<link name="${\'%999999999d\' % 1}"/>', "wider than 1000"),
    "format width": (TEMPLATES + '<link name="${wide.format(1)}"/>', "wider than 1000"),
    "replace": ('<link name="${(\'a\' * 999999).replace(\'a\', \'aa\')}"/>', "more than 1000000"),
    "range": ('<link name="${python.list(python.range(10**12))}"/>', "more than 1000000"),
    "factorial": ('<link name="${math.factorial(10**7)}"/>', "factorial() of a number over"),
    "doubling": ("".join(f'<xacro:property name="p{i + 1}" value="${{[p{i}, p{i}]}}"/>'
                         for i in range(30)).replace("p0", "'x'")
                 + '<link name="${p30}"/>', "more than 1000000 items"),
}


@pytest.mark.parametrize(("body", "reason"), DENIAL_OF_SERVICE.values(),
                         ids=DENIAL_OF_SERVICE.keys())
def test_oversized_values_are_refused_before_they_are_built(repo, body, reason):
    assert reason in refused(repo, body)


def fan_out(levels: int, width: int, leaf: str) -> str:
    macros = [f'<xacro:macro name="m0" params="">{leaf}</xacro:macro>']
    for level in range(1, levels + 1):
        macros.append(f'<xacro:macro name="m{level}" params="">'
                      + f"<xacro:m{level - 1}/>" * width + "</xacro:macro>")
    return "\n".join(macros) + f"\n<xacro:m{levels}/>"


def test_a_macro_fan_out_stops_at_the_node_limit(repo):
    err = refused(repo, fan_out(3, 10, "<group>" + "<g/>" * 1000 + "</group>"))
    assert err.endswith(f"xacro: expansion exceeded {MAX_NODES} XML nodes (a safety limit)\n")


def test_recursion_stops(repo):
    err = refused(repo, '<xacro:macro name="loop" params=""><xacro:loop/></xacro:macro>'
                        "<xacro:loop/>")
    assert "recursion" in err


def test_a_huge_output_stops_at_the_output_limit(repo):
    # text written in the file, copied by macros: no evaluation, only clones to pay for
    leaf = "<group>" + "_" * 800_000 + "</group>"
    err = refused(repo, fan_out(2, 10, leaf))
    assert err.endswith(f"xacro: expansion exceeded {MAX_OUTPUT} bytes of output (a safety "
                        "limit)\n")


def test_a_slow_expansion_stops_at_the_time_limit(repo, monkeypatch):
    monkeypatch.setenv("TXTOOL_XACRO_TIMEOUT", "0.05")  # the work below takes some 0.5 s
    err = refused(repo, fan_out(15, 2, '<link name="x"/>'))
    assert err.endswith("xacro: expansion exceeded 0.05 seconds (a safety limit)\n")
    monkeypatch.delenv("TXTOOL_XACRO_TIMEOUT")
    path = repo / "robot.urdf.xacro"  # the next file gets a fresh worker
    path.write_text(robot('<link name="${1 + 1}"/>'))
    assert 'name="2"' in expand_in_sandbox(str(path), str(path), XacroOptions())


def test_memory_stops_at_the_memory_limit(repo, monkeypatch):
    monkeypatch.setenv("TXTOOL_XACRO_MEMORY_MB", "64")
    # a megabyte of text written once, copied by fifty macro calls (each evaluated anew, so
    # each a string of its own): memory at little work
    body = ('<xacro:macro name="m" params=""><t>' + "_" * 1_000_000 + "</t></xacro:macro>"
            + "<xacro:m/>" * 50)
    err = refused(repo, body)
    assert "expansion exceeded 64 MiB of memory" in err


def test_a_yaml_alias_bomb_is_refused(repo):
    lines = ["a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    lines += [f"a{i}: &a{i} [*a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, "
              f"*a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}]" for i in range(1, 10)]
    (repo / "bomb.yaml").write_text("\n".join(lines) + "\n")
    err = refused(repo, '<link name="${xacro.load_yaml(\'bomb.yaml\')}"/>')
    assert "once its aliases are expanded (a safety limit)" in err


def test_a_limit_from_the_environment_must_be_a_number(repo, monkeypatch):
    monkeypatch.setenv("TXTOOL_XACRO_TIMEOUT", "soon")
    path = repo / "robot.urdf.xacro"
    path.write_text(robot('<link name="x"/>'))
    assert run("show", str(path))[:3] == (
        2, "", "txtool: TXTOOL_XACRO_TIMEOUT='soon': expected a number of seconds above 0 to "
        "3600\n")


# -- the restricted grammar: what real robots write evaluates as Python would ----------------

class Table(dict):
    pass


ACCEPTED = [
    "pi/2", "-pi + 0.5", "radians(92)", "degrees(pi)", "math.cos(0) * sqrt(2)", "1./12 * 3",
    "(2 - 1)/2*pi", "3 * 2**2", "7 // 2 + 7 % 3", "python.abs(-2) + max(1, 2) + min([3, 4])",
    "floor(2.5) + ceil(2.5)", "pow(2, 10)", "'revolute' == 'fixed'", "'y' in 'xyz'",
    "1 < 2 <= 2", "not True or False and True", "pi/2.0 if 'y' in 'xy' else 0",
    "'0 1 2'.split(' ')[2]", "'ab'.upper() + 'x'.join(['1', '2'])", "[1, 2, 3][1:]",
    "{'a': 1}['a']", "(1, 2)[0]", "len('abc')", "str(1) + '_joint'", "int('3') + float('1.5')",
    "python.sorted([3, 1, 2])", "python.list(python.range(3))", "'{}_{}'.format('l', 2)",
    "'%s_%d' % ('a', 3)", "f'{2:.2f}'", "round(2.567, 2)", "bool(0)", "True", "None",
    "python.sum([1, 2.5])", "e", "tau", "inf > 1", "isnan(nan)", "1 if 1 in [1, 2] else 0",
    "f'{\"a\"!r}'", "f'{1!s}'", "f'{\"é\"!a}'", "len({1, 2, 2})", "'ab'.rjust(5)",
    "'ab'.ljust(4) + 'x'.center(3)", "'a-b'.replace('-', '_')", "0 or 'x'", "1 and 0",
    "(1, 2) + (3,)", "[1] * 3", "2 << 3", "'x'.join(['a', 'b'])", "[1, 2, 3].index(2)",
    "{'a': 1}.get('b', 2)", "python.list({'a': 1}.keys())",
]


@pytest.mark.parametrize("expression", ACCEPTED)
def test_the_grammar_real_robots_use_evaluates_as_python_does(expression):
    names = make_globals({})
    python = {**vars(math), "abs": abs, "max": max, "min": min, "len": len, "str": str,
              "int": int, "float": float, "round": round, "bool": bool, "pow": pow,
              "math": math, "python": _Python()}
    assert evaluate(expression, Table(names)) == eval(expression, {"__builtins__": {}}, python)


class _Python:
    abs, sorted, list, range, sum = abs, sorted, list, range, sum


@pytest.mark.parametrize("expression", ["x.__class__", "().__class__", "python.sum(['a'], '')",
                                        "{**{}}", "[*'ab']", "print(1)", "1j", "b'x'",
                                        "max(*[1, 2])", "python.dict(**{'a': 1})",
                                        "'{0.real}'.format(1)", "'{:{}}'.format(1, 5)",
                                        "'a'.rjust(10**7)", "(1).real", "len[0]",
                                        "'a' * 10**7", "[0] * 10**7 + [1]",
                                        "'ab' + 'c' * 999999"])
def test_outside_the_grammar_is_refused_or_undefined(expression):
    with pytest.raises((EvalRefused, NameError)):
        evaluate(expression, Table(make_globals({}), x=1))


# -- real robots expand the same way in both modes -------------------------------------------

def _xacro_files() -> list[Path]:
    found = sorted(CORPUS.glob("*.xacro")) + sorted(WORKSPACE.rglob("*.xacro"))
    return found or [Path("<corpus missing>")]


def canonical(text: str) -> bytes:
    parser = etree.XMLParser(remove_comments=True, remove_blank_text=True)
    return etree.tostring(etree.fromstring(text.encode("utf-8"), parser), method="c14n")


@pytest.mark.parametrize("path", _xacro_files(), ids=lambda p: p.name)
def test_corpus_xacro_expands_identically_in_safe_mode(path):
    if not path.is_file():
        pytest.skip("corpus not found")
    outcomes = []
    for expand in (expand_text, expand_in_sandbox):
        try:
            outcomes.append(canonical(expand(str(path), str(path), XacroOptions())))
        except Exception as exc:  # noqa: BLE001 (a missing package fails both the same way)
            outcomes.append(str(exc).encode())
    assert outcomes[0] == outcomes[1]


def test_corpus_validate_reports_the_same_in_both_modes():
    if not CORPUS.is_dir():
        pytest.skip("corpus not found")
    paths = [str(p) for p in _xacro_files()]
    safe = run("validate", "--format", "json", *paths)
    trusted = run("validate", "--format", "json", "--trust-xacro", *paths)
    assert json.loads(safe[1]) == json.loads(trusted[1])
    assert safe[0] == trusted[0]


def test_a_package_path_is_a_root_only_when_it_is_a_package(repo):
    err = refused(repo, '<xacro:include filename="$(find fake)/passwd"/>',
                  "--pkg-path", "fake:=/etc")
    assert "include of '/etc/passwd' is outside the repository" in err


def test_no_configuration_file_can_trust_xacro(repo):
    (repo / ".txtool.toml").write_text("trust-xacro = true\n")
    path = repo / "robot.urdf.xacro"
    path.write_text(robot('<link name="${python.type(1)}"/>'))
    code, out, err, _ = run("validate", str(path))
    assert code == 2 and "trust-xacro" in err and "python" not in out


@pytest.mark.parametrize("command", ["validate", "show", "convert", "migrate", "map",
                                     "roundtrip", "simulate"])
def test_every_command_that_reads_xacro_takes_trust_xacro(command):
    result = CliRunner().invoke(cli, [command, "--help"])
    assert "--trust-xacro" in result.stdout


# The guard itself, in this process: the same attacks with its hooks installed in upstream
# xacro but without the child process and its limits around it. Whatever the process boundary
# adds, the guard alone must refuse each of them (and run none).
def guarded(repo: Path, body: str, env: dict[str, str] | None = None) -> str:
    from txtool.io.xacro_guard import XacroGuard

    path = repo / "robot.urdf.xacro"
    path.write_text(robot(body))
    options = XacroOptions(env=tuple(env or ()))
    return expand_text(str(path), str(path), options, XacroGuard(str(path), options, env or {}))


@pytest.mark.parametrize("expression", CODE_EXECUTION.values(), ids=CODE_EXECUTION.keys())
def test_the_guard_alone_refuses_code_execution(repo, expression):
    from txtool.io.xacro import XacroError
    from txtool.io.xacro_guard import Refusal

    body = (TEMPLATES + f'<link name="{expression}"/>').replace("${close}", ")")
    with pytest.raises((Refusal, XacroError)):
        guarded(repo, body)
    assert not (repo / MARKER).exists()


@pytest.mark.parametrize("body", LEAKS.values(), ids=LEAKS.keys())
def test_the_guard_alone_reads_no_secret(repo, body, monkeypatch):
    from txtool.io.xacro import XacroError
    from txtool.io.xacro_guard import Refusal

    monkeypatch.setenv("DEPLOY_NOTE", SECRET)
    monkeypatch.setenv("FAKE_GITHUB_TOKEN", SECRET)
    try:
        text = guarded(repo, body)
    except (Refusal, XacroError) as exc:
        text = str(exc)
    assert SECRET not in text


@pytest.mark.parametrize(("body", "reason"), DENIAL_OF_SERVICE.values(),
                         ids=DENIAL_OF_SERVICE.keys())
def test_the_guard_alone_refuses_oversized_values(repo, body, reason):
    from txtool.io.xacro import XacroError
    from txtool.io.xacro_guard import Refusal

    with pytest.raises((Refusal, XacroError)) as raised:
        guarded(repo, body)
    shown = getattr(raised.value, "reason", str(raised.value))
    assert reason.split(": xacro: ")[-1] in shown


def test_the_guard_alone_reads_an_allowed_variable(repo):
    text = guarded(repo, '<link name="$(env ROBOT_MODEL)_base"/>', {"ROBOT_MODEL": "ur5e"})
    assert 'name="ur5e_base"' in text


@pytest.mark.parametrize("path", _xacro_files(), ids=lambda p: p.name)
def test_corpus_xacro_expands_identically_under_the_guard_alone(path):
    from txtool.io.xacro_guard import XacroGuard

    if not path.is_file():
        pytest.skip("corpus not found")
    outcomes = []
    for guard in (None, XacroGuard(str(path), XacroOptions(), {})):
        try:
            outcomes.append(canonical(expand_text(str(path), str(path), XacroOptions(), guard)))
        except Exception as exc:  # noqa: BLE001 (a missing package fails both the same way)
            outcomes.append(str(exc).encode())
    assert outcomes[0] == outcomes[1]


@pytest.fixture
def child_here(monkeypatch):
    """The child's request handling run in this process: without its process limits (a
    request would set them on the test run itself), minidom as it was afterwards."""
    import xml.dom.minidom as minidom

    from txtool.io import xacro_child as child

    monkeypatch.setattr(child, "_set_limits", lambda seconds, memory: None)
    monkeypatch.setattr(minidom, "_clone_node", minidom._clone_node)
    for name in child.PACKAGE_VARIABLES:  # the request's package paths replace them
        monkeypatch.setenv(name, "")
        monkeypatch.delenv(name)
    return child


def request_for(path: Path, **changes):
    from txtool.io import xacro as xacro_support

    request = {"path": str(path), "display": path.name, "args": [], "pkg_dirs": [],
               "pkg_paths": [], "env_names": [], "env": {}, "seconds": 30, "memory": 512,
               "readable": [],
               "max_read": xacro_support.MAX_READ, "package_paths": {}}
    return {**request, **changes}


def test_the_childs_answers_to_each_kind_of_request(repo, child_here):
    path = repo / "robot.urdf.xacro"
    path.write_text(robot('<link name="${2 * 3}"/>'))
    header, text = child_here._expand(request_for(path))
    assert header["ok"] and 'name="6"' in text and header["inputs"]
    path.write_text(robot("\n<link name=\"${''.__class__}\"/>"))
    header, text = child_here._expand(request_for(path))
    assert (set(header), header["line"], text) == ({"refused", "line"}, 5, "")
    path.write_text(robot('<link name="$(arg missing)"/>'))
    header, _ = child_here._expand(request_for(path))
    assert header["missing"] == "argument" and "missing" in header["error"]
    path.write_text(robot(fan_out(3, 10, "<group>" + "<g/>" * 1000 + "</group>")))
    header, _ = child_here._expand(request_for(path))
    assert header == {"limit": f"{child_here.MAX_NODES} XML nodes", "retire": True}


def test_the_child_answers_one_line_and_the_text(repo, child_here, monkeypatch):
    import io
    import sys

    path = repo / "robot.urdf.xacro"
    path.write_text(robot('<link name="${1 + 1}"/>'))

    class Stream(io.BytesIO):
        @property
        def buffer(self):
            return self

    stdin = Stream((json.dumps(request_for(path)) + "\n").encode())
    stdout = Stream()
    monkeypatch.setattr(sys, "stdin", stdin)
    monkeypatch.setattr(sys, "stdout", stdout)
    monkeypatch.setattr(sys, "stderr", sys.stderr)
    child_here.main()
    head, _, body = stdout.getvalue().partition(b"\n")
    header = json.loads(head)
    assert header["ok"] and header["size"] == len(body) and b'name="2"' in body


def test_the_guard_alone_expands_what_real_robots_write(repo):
    """$(eval) with arguments, load_yaml of a file in the repository (units, dotted keys,
    methods of a dict), $(find) of a package, optenv's default: all as upstream."""
    (repo / "config").mkdir()
    (repo / "config" / "limits.yaml").write_text(
        "shoulder:\n  upper: !degrees 90\n  lower: -1.5\nnames: [a, b]\n")
    (repo / "arm_description").mkdir()
    (repo / "arm_description" / "package.xml").write_text(
        "<package format='3'><name>arm_description</name></package>")
    body = ('<xacro:arg name="scale" default="2"/>'
            '<xacro:property name="limits" value="${xacro.load_yaml(\'config/limits.yaml\')}"/>'
            '<link name="$(eval 3 * scale)"/>'
            '<link name="$(eval scale + 1)"/>'
            '<link name="${limits.shoulder.upper}"/>'
            '<link name="${limits[\'shoulder\'][\'lower\']}"/>'
            '<link name="${\'-\'.join(limits.names)}"/>'
            '<link name="${python.sorted(limits.shoulder.keys())[0]}"/>'
            '<link name="${limits.get(\'missing\', 7)}"/>'
            '<link name="$(find arm_description)"/>'
            '<link name="$(optenv NOT_ALLOWED fallback)"/>')
    text = guarded(repo, body)
    for shown in ('name="6"', 'name="3"', f'name="{math.pi / 2}"', 'name="-1.5"', 'name="a-b"',
                  'name="lower"', 'name="7"', f'name="{repo / "arm_description"}"',
                  'name="fallback"'):
        assert shown in text, shown


def test_the_guard_alone_refuses_a_yaml_alias_bomb_and_eval_attributes(repo):
    from txtool.io.xacro_guard import Refusal

    lines = ["a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    lines += [f"a{i}: &a{i} [*a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, "
              f"*a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}]" for i in range(1, 8)]
    (repo / "bomb.yaml").write_text("\n".join(lines) + "\n")
    with pytest.raises(Refusal, match="once its aliases are expanded"):
        guarded(repo, '<link name="${xacro.load_yaml(\'bomb.yaml\')}"/>')
    with pytest.raises(Refusal, match="__class__"):
        guarded(repo, '<link name="$(eval arg.__class__)"/>')


@pytest.mark.parametrize(("body", "said"), [
    ('<link name="$(env ROBOT_MODEL)"/>', "environment variable 'ROBOT_MODEL' is not set"),
    ('<xacro:property name="y" value="${xacro.load_yaml(\'l.yaml\')}"/><link name="${y.nope}"/>',
     "nope"),
    ('<link name="${math.nope}"/>', "name 'nope' is not defined"),
    ('<link name="${xacro.load_yaml(\'fifo.yaml\')}"/>', "not a regular file"),
])
def test_the_guard_alone_fails_as_xacro_fails_where_nothing_is_refused(repo, body, said):
    """An allowed variable that is unset, a key or name that does not exist, a YAML file that
    is no regular file: ordinary xacro errors (TX002), not refusals."""
    from txtool.io.xacro import XacroError

    (repo / "l.yaml").write_text("a: 1\n")
    os.mkfifo(repo / "fifo.yaml")
    from txtool.io.xacro_guard import XacroGuard

    path = repo / "robot.urdf.xacro"
    path.write_text(robot(body))
    options = XacroOptions(env=("ROBOT_MODEL",))  # allowed, and not set
    with pytest.raises(XacroError, match=said):
        expand_text(str(path), str(path), options, XacroGuard(str(path), options, {}))
