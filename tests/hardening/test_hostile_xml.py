"""Hostile XML: external entities, DTDs, entity bombs, huge and deeply nested documents.

Every command is run on each document. Nothing from a file or URL the document points at
may reach stdout, stderr or a written file; entity declarations are refused (exit 2, or TX001
for ``validate``, TX002 when a xacro include has them); a DTD is never fetched.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
import time
import uuid
from collections.abc import Iterator
from http.server import BaseHTTPRequestHandler, HTTPServer
from pathlib import Path

import pytest

from tests.hardening.hostile_inputs import (
    billion_laughs,
    command_lines,
    invoke,
    one_line_error,
    quadratic_blowup,
    robot,
    run,
)
from txtool.io import xmlio
from txtool.io.xmlio import MAX_BYTES

ROOT = Path(__file__).resolve().parents[2]
SUFFIXES = (".urdf", ".urdf.xacro")
REFUSED = "the DOCTYPE declares entities"


def include_of(target: Path) -> str:
    """A clean xacro file whose only content is an include of ``target``."""
    return ('<?xml version="1.0"?>\n<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            f'  <xacro:include filename="{target}"/>\n</robot>\n')


def leaks(document: Path, scratch: Path, marker: str) -> list[str]:
    """Run every command on ``document``; what went wrong, one string per command."""
    problems = []
    for args, written in command_lines(document, scratch):
        outcome = invoke(*args)
        said = outcome.out + outcome.err
        if outcome.exception is not None:
            problems.append(f"{args}: raised {outcome.exception!r}")
        if outcome.code not in (0, 1, 2) or "Traceback" in said:
            problems.append(f"{args}: exit {outcome.code}: {said[-300:]}")
        if marker in said:
            problems.append(f"{args}: the marker is in the output")
        if written is not None and written.exists() and marker in written.read_text("latin-1"):
            problems.append(f"{args}: the marker is in {written.name}")
    return problems


@pytest.fixture
def secret(tmp_path: Path) -> tuple[Path, str]:
    marker = f"SECRET-{uuid.uuid4().hex}"
    path = tmp_path / "secret.txt"
    path.write_text(marker + "\n")
    return path, marker


@pytest.mark.parametrize("suffix", SUFFIXES)
@pytest.mark.parametrize("spot", ["transmission", "joint", "reduction", "comment"])
def test_external_entity_is_refused_and_never_read(tmp_path, secret, spot, suffix):
    secret_file, marker = secret
    doctype = f'<!DOCTYPE robot [<!ENTITY xxe SYSTEM "file://{secret_file}">]>'
    value = {"transmission": "elbow_trans&xxe;", "joint": "elbow&xxe;", "reduction": "&xxe;",
             "comment": "&xxe;"}[spot]
    document = tmp_path / f"robot{suffix}"
    document.write_text(robot(doctype=doctype, **{spot: value}))
    scratch = tmp_path / "out"
    scratch.mkdir()

    assert leaks(document, scratch, marker) == []

    code, out, err = run("show", str(document))
    assert code == 2 and out == ""
    assert one_line_error(err).startswith(f"txtool: {document}:")
    assert "entit" in err  # refused for what it is, by the declaration or the reference
    code, out, _ = run("validate", "--format", "json", str(document))
    assert code == 1
    assert [p["code"] for p in json.loads(out)["problems"]] == ["TX001"]


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_entity_declared_in_an_included_file_is_refused(tmp_path, secret, suffix):
    secret_file, marker = secret
    included = tmp_path / f"part{suffix}"
    included.write_text(robot(doctype=f'<!DOCTYPE robot [<!ENTITY xxe SYSTEM "file://{secret_file}">'
                                      '<!ENTITY name "elbow_trans">]>',
                              transmission="&name;", reduction="&xxe;"))
    top = tmp_path / "top.urdf.xacro"
    top.write_text(include_of(included))
    scratch = tmp_path / "out"
    scratch.mkdir()

    assert leaks(top, scratch, marker) == []

    code, out, err = run("show", str(top))
    assert code == 2 and out == ""
    assert one_line_error(err) == (f"txtool: {top}:1: xacro: {included}:2: {REFUSED}; txtool does "
                                   "not read entity declarations (they can pull in local files "
                                   "or expand without bound): remove them")
    code, out, _ = run("validate", "--format", "json", str(top))
    assert code == 1
    assert [p["code"] for p in json.loads(out)["problems"]] == ["TX002"]


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_parameter_entity_never_loads_its_dtd(tmp_path, secret, suffix):
    secret_file, marker = secret
    dtd = tmp_path / "evil.dtd"
    dtd.write_text(f'<!ENTITY leak "{marker}">\n<!ENTITY file SYSTEM "file://{secret_file}">\n')
    doctype = f'<!DOCTYPE robot [<!ENTITY % ext SYSTEM "file://{dtd}"> %ext;]>'
    document = tmp_path / f"robot{suffix}"
    document.write_text(robot(doctype=doctype, comment="&leak;&file;"))
    scratch = tmp_path / "out"
    scratch.mkdir()

    assert leaks(document, scratch, marker) == []
    code, _, err = run("convert", "--to", "ros2-p2", str(document))
    assert code == 2 and REFUSED in one_line_error(err)


class CountingServer:
    """An HTTP server on an ephemeral port that serves a DTD and counts the requests."""

    def __init__(self, body: str) -> None:
        self.requests: list[str] = []
        server = self

        class Handler(BaseHTTPRequestHandler):
            def do_GET(self) -> None:  # noqa: N802 (the http.server name)
                server.requests.append(self.path)
                payload = body.encode()
                self.send_response(200)
                self.send_header("Content-Type", "application/xml-dtd")
                self.send_header("Content-Length", str(len(payload)))
                self.end_headers()
                self.wfile.write(payload)

            def log_message(self, *args: object) -> None:
                pass

        self.httpd = HTTPServer(("127.0.0.1", 0), Handler)
        self.url = f"http://127.0.0.1:{self.httpd.server_address[1]}/robot.dtd"
        self.thread = threading.Thread(target=self.httpd.serve_forever, kwargs={"poll_interval": 0.05},
                                       daemon=True)

    def __enter__(self) -> CountingServer:
        self.thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.httpd.shutdown()
        self.httpd.server_close()


@pytest.fixture
def dtd_server(secret) -> Iterator[CountingServer]:
    secret_file, marker = secret
    with CountingServer(f'<!ENTITY leak "{marker}">') as server:
        yield server


def test_counting_server_counts(dtd_server):
    """The server the next test relies on does see a request when one is made."""
    import urllib.request

    with urllib.request.urlopen(dtd_server.url, timeout=5) as response:
        assert b"<!ENTITY leak" in response.read()
    assert dtd_server.requests == ["/robot.dtd"]


def dtd_robot(tmp_path: Path, suffix: str, system: str, **spots: str) -> Path:
    document = tmp_path / f"robot{suffix}"
    document.write_text(robot(doctype=f'<!DOCTYPE robot SYSTEM "{system}">', **spots))
    (tmp_path / "out").mkdir()
    return document


@pytest.mark.parametrize("suffix", SUFFIXES)
@pytest.mark.parametrize("where", ["http", "file"])
def test_external_dtd_is_never_fetched(tmp_path, secret, dtd_server, where, suffix):
    _, marker = secret
    dtd = tmp_path / "robot.dtd"
    dtd.write_text(f'<!ENTITY leak "{marker}">\n')
    system = dtd_server.url if where == "http" else f"file://{dtd}"
    document = dtd_robot(tmp_path, suffix, system)

    assert leaks(document, tmp_path / "out", marker) == []
    assert dtd_server.requests == []
    # Referring to a DTD is harmless: the document is read as if it did not.
    code, out, err = run("show", "--format", "json", str(document))
    assert (code, err) == (0, "")
    assert [t["name"] for t in json.loads(out)["transmissions"]] == ["elbow_trans"]


@pytest.mark.parametrize("suffix", SUFFIXES)
@pytest.mark.parametrize("spot", ["transmission", "comment"])
def test_entity_of_an_external_dtd_is_refused_unfetched(tmp_path, secret, dtd_server, spot,
                                                        suffix):
    _, marker = secret
    value = {"transmission": "elbow_trans&leak;", "comment": "&leak;"}[spot]
    document = dtd_robot(tmp_path, suffix, dtd_server.url, **{spot: value})

    assert leaks(document, tmp_path / "out", marker) == []
    assert dtd_server.requests == []
    # An attribute would silently lose the reference: refused instead, like text.
    code, out, err = run("show", str(document))
    assert (code, out) == (2, "")
    assert one_line_error(err).startswith(f"txtool: {document}:")
    assert err.endswith(": Entity 'leak' not defined: txtool loads no DTD and expands no "
                        "entity; write the text itself\n")


@pytest.mark.parametrize("spot", ["transmission", "comment"])
def test_entity_of_an_external_dtd_in_an_include_is_refused(tmp_path, dtd_server, spot):
    value = {"transmission": "elbow_trans&leak;", "comment": "&leak;"}[spot]
    included = dtd_robot(tmp_path, ".urdf", dtd_server.url, **{spot: value})
    top = tmp_path / "top.urdf.xacro"
    top.write_text(include_of(included))

    code, out, err = run("show", str(top))
    assert (code, out) == (2, "")
    assert one_line_error(err).startswith(f"txtool: {top}:1: xacro: {included}:")
    assert "Entity 'leak' not defined" in err
    assert dtd_server.requests == []


PROBE = """
import json, resource, sys, time
from pathlib import Path
sys.path.insert(0, sys.argv[1])
from tests.hardening.hostile_inputs import command_lines, invoke

def peak_kb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss

warm_up, scratch, *documents = sys.argv[2:]
for args, _ in command_lines(Path(warm_up), Path(scratch)):  # imports, first-call costs
    invoke(*args)
baseline = peak_kb()
report = []
for document in documents:
    for args, _ in command_lines(Path(document), Path(scratch)):
        start = time.perf_counter()
        outcome = invoke(*args)
        report.append({"args": args, "code": outcome.code, "out": outcome.out,
                       "err": outcome.err,
                       "seconds": time.perf_counter() - start,
                       "grew_mb": (peak_kb() - baseline) / 1024})
print(json.dumps(report))
"""


def test_entity_bombs_are_refused_fast_and_small(tmp_path):
    """Billion laughs and quadratic blowup, plain, xacro and included: < 1 s, < 100 MB each."""
    bombs = {"laughs": billion_laughs(), "quadratic": quadratic_blowup()}
    documents = []
    for name, text in bombs.items():
        for suffix in SUFFIXES:
            documents.append(tmp_path / f"{name}{suffix}")
            documents[-1].write_text(text)
        documents.append(tmp_path / f"includes_{name}.urdf.xacro")
        documents[-1].write_text(include_of(tmp_path / f"{name}.urdf"))
    warm_up = tmp_path / "plain.urdf"
    warm_up.write_text(robot())
    scratch = tmp_path / "out"
    scratch.mkdir()

    probe = subprocess.run(
        [sys.executable, "-c", PROBE, str(ROOT), str(warm_up), str(scratch), *map(str, documents)],
        capture_output=True, text=True, timeout=300, cwd=tmp_path,
    )
    assert probe.returncode == 0, probe.stderr[-2000:]
    report = json.loads(probe.stdout.splitlines()[-1])

    assert len(report) == len(documents) * 17
    slow = [(r["args"], round(r["seconds"], 2)) for r in report if r["seconds"] >= 1.0]
    big = [(r["args"], round(r["grew_mb"])) for r in report if r["grew_mb"] >= 100]
    assert slow == [] and big == []
    for line in report:
        command, path = line["args"][0], line["args"][-1]
        if command == "validate":
            assert line["code"] == 1 and REFUSED in line["out"], line
        elif command == "migrate" and "includes_" in path:  # migrate never expands xacro
            assert (line["code"], line["err"]) == (0, "nothing to do (1 file(s) checked)\n")
        else:
            assert line["code"] == 2 and REFUSED in line["err"], line


def test_validate_names_the_bomb_as_tx001(tmp_path):
    bomb = tmp_path / "laughs.urdf"
    bomb.write_text(billion_laughs())
    code, out, err = run("validate", str(bomb))
    assert (code, err) == (1, "")
    assert out.startswith(f"{bomb}:3:1: error TX001 xml-syntax: {REFUSED}")


def big_robot(transmissions: int, filler_per_link: int) -> str:
    """A robot of ``transmissions`` joints, each link carrying a bulky <gazebo> block."""
    filler = "Gazebo/Grey " * (filler_per_link // 12)
    parts = ['<?xml version="1.0"?>\n<robot name="big">\n<link name="l0"/>\n']
    for n in range(1, transmissions + 1):
        parts.append(
            f'<link name="l{n}"><visual><geometry><box size="1 1 1"/></geometry></visual></link>\n'
            f'<joint name="j{n}" type="revolute"><parent link="l{n - 1}"/><child link="l{n}"/>'
            '<limit lower="-1" upper="1" effort="10" velocity="2"/></joint>\n'
            f'<transmission name="t{n}"><type>transmission_interface/SimpleTransmission</type>'
            f'<joint name="j{n}"><hardwareInterface>hardware_interface/EffortJointInterface'
            f'</hardwareInterface></joint><actuator name="m{n}"><mechanicalReduction>50'
            '</mechanicalReduction></actuator></transmission>\n'
            f'<gazebo reference="l{n}"><material>{filler}</material></gazebo>\n')
    parts.append("</robot>\n")
    return "".join(parts)


def test_a_50_mb_robot_is_processed(tmp_path):
    document = tmp_path / "big.urdf"
    document.write_text(big_robot(1000, 53_000))
    assert document.stat().st_size > 50 * 1024 * 1024

    start = time.perf_counter()
    code, out, err = run("validate", str(document))
    assert (code, out, err) == (0, "No problems in 1 file.\n", "")
    code, out, err = run("show", "--format", "json", str(document))
    assert (code, err) == (0, "")
    assert len(json.loads(out)["transmissions"]) == 1000
    assert time.perf_counter() - start < 15


def test_a_file_over_the_size_limit_is_refused_unread(tmp_path, monkeypatch):
    document = tmp_path / "huge.urdf"
    with document.open("wb") as handle:
        handle.truncate(MAX_BYTES + 1)  # sparse: nothing is written, nothing could be read
    read = []
    real_open = open

    class Unread:  # the size is asked of the open file; its content must not be read
        def __init__(self, handle):
            self.handle = handle

        def __enter__(self):
            return self

        def __exit__(self, *exc_info):
            self.handle.close()

        def fileno(self):
            return self.handle.fileno()

        def read(self, *args):
            read.append(self.handle.name)
            return self.handle.read(*args)

    monkeypatch.setattr(xmlio, "open", lambda *a, **k: Unread(real_open(*a, **k)), raising=False)
    reason = f"txtool: {document}: file is {MAX_BYTES + 1} bytes, larger than the {MAX_BYTES} limit"
    for args in (["show"], ["convert", "--to", "ros1"]):
        code, out, err = run(*args, str(document))
        assert (code, out, one_line_error(err)) == (2, "", reason), args
    code, out, err = run("validate", str(document))
    assert (code, one_line_error(err)) == (2, reason)
    assert out == "1 file could not be read; nothing was checked.\n"
    assert read == []


def nested(depth: int) -> str:
    return '<robot name="deep">' + "<a>" * depth + "</a>" * depth + "</robot>\n"


def test_deep_nesting_is_one_line_not_a_recursion_error(tmp_path):
    document = tmp_path / "deep.urdf"
    document.write_text(nested(10_000))
    reason = "elements nested more than 256 levels deep (a safety limit)"

    code, out, err = run("show", str(document))
    assert (code, out) == (2, "")
    line = one_line_error(err)
    assert line.startswith(f"txtool: {document}:1:") and line.endswith(f": {reason}")
    code, out, err = run("validate", str(document))
    assert (code, err) == (1, "")
    assert out.startswith(f"{document}:1:") and f"error TX001 xml-syntax: {reason}\n" in out

    top = tmp_path / "top.urdf.xacro"
    top.write_text(include_of(document))
    code, out, err = run("show", str(top))
    assert (code, out) == (2, "")
    assert one_line_error(err) == f"txtool: {top}:1: xacro: {document}:1: {reason}"
    code, out, err = run("validate", "--format", "json", str(top))
    assert code == 1 and "RecursionError" not in out + err
    assert [p["code"] for p in json.loads(out)["problems"]] == ["TX002"]


def test_nesting_within_the_limit_is_read(tmp_path):
    for name in ("nested.urdf", "nested.urdf.xacro"):
        (tmp_path / name).write_text(nested(200))
        code, out, err = run("show", "--format", "json", str(tmp_path / name))
        assert (code, json.loads(out), err) == (0, {"transmissions": []}, ""), name


def deep_transmission(groups: int) -> str:
    """A robot whose one transmission stands inside ``groups`` nested elements."""
    transmission = (
        '<transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
        '<joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface'
        '</hardwareInterface></joint><actuator name="m"><mechanicalReduction>2'
        "</mechanicalReduction></actuator></transmission>"
    )
    return ('<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
            '<parent link="a"/><child link="b"/>'
            '<limit effort="1" velocity="1" lower="-1" upper="1"/></joint>'
            + "<group>" * groups + transmission + "</group>" * groups + "</robot>\n")


@pytest.mark.parametrize("target", ["ros2-p1", "ros2-p2"])
def test_a_conversion_that_would_nest_too_deep_is_refused_not_written(tmp_path, target):
    """The <ros2_control> block written in the place of a transmission 253 levels down nests
    its <mechanical_reduction> 257 deep: nothing (txtool included) could read the result."""
    document = tmp_path / "deep.urdf"
    document.write_text(deep_transmission(252))
    reason = "elements nested more than 256 levels deep (a safety limit)"
    assert run("validate", str(document))[0] == 0  # the input itself reads

    code, out, err = run("convert", "--to", target, str(document))
    assert (code, out) == (2, "")
    line = one_line_error(err)
    assert line.startswith(f"txtool: {document}: cannot convert: the result could not be read "
                           "back; its line ") and line.endswith(f": {reason}")
    before = document.read_bytes()
    code, out, err = run("migrate", "--write", "--to", target, str(document))
    assert code == 2 and line in err and document.read_bytes() == before

    document.write_text(deep_transmission(249))  # three levels up: converted as usual
    code, out, err = run("convert", "--to", target, "--hardware-plugin", "deep/Hardware",
                         str(document))
    p1 = "warning: ros2-p1 is not what ros2_control reads"  # (its <role> elements)
    assert (code, err.startswith(p1)) == (0, target == "ros2-p1") and "<ros2_control" in out
    assert err.count("\n") == (target == "ros2-p1")


def test_a_file_that_grew_after_its_size_was_taken_is_read_whole_or_refused(tmp_path,
                                                                             monkeypatch):
    """The read asks for the size fstat gave, plus one byte to see growth; a file that grew
    between the two is read on up to the limit, and refused past it."""
    document = tmp_path / "robot.urdf"
    document.write_bytes(b"<robot name='r'>" + b" " * 4000 + b"</robot>\n")
    real_fstat = xmlio.os.fstat

    def shrunk(handle):  # the size the file had before it grew
        status = real_fstat(handle)
        return os.stat_result((*status[:6], 10, *status[7:]))

    monkeypatch.setattr(xmlio.os, "fstat", shrunk)
    assert xmlio.read_regular(str(document)) == document.read_bytes()
    with pytest.raises(xmlio.TooLarge, match="file is larger than the 100 limit"):
        xmlio.read_regular(str(document), limit=100)
