"""Big documents cost the same per transmission as small ones.

Timing is unreliable on a shared machine, so the work is counted as well: every Python and
builtin call a command makes (``sys.setprofile``), held to a tight bound. A step whose cost
grows with the document for every transmission (a list searched per element) makes the count
per transmission grow with the size; a linear command keeps it flat. Loops that make no calls
(difflib's inner search) show only in the time, held to a loose bound (a quadratic step
costs four times as much per transmission at four times the size).
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli

TRANSMISSION = (
    '<transmission name="t{i}"><type>transmission_interface/SimpleTransmission</type>'
    '<joint name="j{i}"><hardwareInterface>hardware_interface/EffortJointInterface'
    '</hardwareInterface></joint><actuator name="m{i}"><mechanicalReduction>{n}'
    "</mechanicalReduction></actuator></transmission>"
)


def chain(joints: int, *, pretty: bool = False) -> str:
    """A chain of ``joints`` revolute joints, each driven by a ROS 1 simple transmission
    (what ``bench/bench_scale.py`` measures); ``pretty``: every element on its own line."""
    parts = ['<robot name="chain">', '<link name="l0"/>']
    parts += [f'<link name="l{i}"/><joint name="j{i}" type="revolute"><parent link="l{i - 1}"/>'
              f'<child link="l{i}"/><limit lower="-1" upper="1" effort="10" velocity="2"/>'
              "</joint>" for i in range(1, joints + 1)]
    parts += [TRANSMISSION.format(i=i, n=10 + i % 90) for i in range(1, joints + 1)]
    text = "\n".join(parts) + "\n</robot>\n"
    return text.replace("><", ">\n<") if pretty else text


def calls(run: Callable[[], object]) -> int:
    count = 0

    def counter(frame, event, arg) -> None:
        nonlocal count
        if event in ("call", "c_call"):
            count += 1

    sys.setprofile(counter)
    try:
        run()
    finally:
        sys.setprofile(None)
    return count


def per_transmission(path: Path, args: list[str], size: int) -> tuple[float, float]:
    """Calls and CPU seconds per transmission of ``txtool ARGS PATH``: the best of three timed
    runs (the first one's imports and first-call caches do not count; the third takes out a
    run slowed by other work on a shared machine), then a counted one."""
    runner = CliRunner()
    seconds = []
    for _ in range(3):
        start = time.process_time()
        result = runner.invoke(cli, [*args, str(path)])
        seconds.append(time.process_time() - start)
        assert result.exit_code in (0, 1), result.output
        assert "internal error" not in result.output
    count = calls(lambda: runner.invoke(cli, [*args, str(path)]))
    return count / size, min(seconds) / size


@pytest.mark.parametrize(("args", "small", "start"), [
    (["convert", "--to", "ros2-p2"], 250, "ros1"),
    (["convert", "--to", "ros1"], 250, "ros2"),  # a generated block taken apart
    (["migrate", "--diff", "--to", "ros2-p2"], 250, "ros1"),
    (["migrate", "--diff", "--to", "ros2-p2"], 300, "pretty"),  # repeated lines to align
    (["roundtrip", "--format", "json"], 40, "ros1"),
    (["roundtrip", "--format", "json"], 40, "ros2"),  # followers inside a generated block
    (["validate", "--format", "json"], 250, "ros2"),  # each member's block declaration
], ids=["convert", "convert-back", "migrate", "migrate-pretty", "roundtrip", "roundtrip-ros2",
        "validate-ros2"])
def test_work_per_transmission_does_not_grow_with_the_document(tmp_path, args, small, start):
    counts = []
    for size in (small, 4 * small):
        path = tmp_path / f"chain_{size}.urdf"
        path.write_text(chain(size, pretty=start == "pretty"))
        if start == "ros2":
            converted = CliRunner().invoke(cli, ["convert", "--to", "ros2-p2", str(path)])
            path.write_bytes(converted.stdout_bytes)
        counts.append(per_transmission(path, args, size))
    (small_calls, small_time), (large_calls, large_time) = counts
    # A fixed cost per document makes the small one dearer per transmission; a cost per
    # transmission that grows with the document makes the large one dearer.
    assert large_calls <= 1.1 * small_calls, counts
    assert large_time <= 2 * small_time, counts


def test_an_input_within_the_size_limit_converts_though_the_result_exceeds_it(tmp_path,
                                                                              monkeypatch):
    """The size cap is on inputs: a robot just under it converts to ROS 2 (its declarations
    make the result larger), and the result is read back for the check, not refused."""
    from txtool.io import xmlio

    path = tmp_path / "robot.urdf"
    path.write_text(chain(20))
    limit = path.stat().st_size + 10
    monkeypatch.setattr(xmlio.parse_bytes, "__kwdefaults__", {"limit": limit})
    monkeypatch.setattr(xmlio.read_regular, "__defaults__", (limit,))
    runner = CliRunner()
    converted = runner.invoke(cli, ["convert", "--to", "ros2-p2", str(path)])
    assert converted.exit_code == 0, converted.output
    assert len(converted.stdout_bytes) > limit
    assert converted.stdout_bytes.count(b"<transmission ") == 20
    diff = runner.invoke(cli, ["migrate", "--diff", "--to", "ros2-p2", str(path)])
    assert diff.exit_code == 1, diff.output
    assert "+    <joint name=\"j20\" role=\"joint1\">" in diff.stdout
    cycles = runner.invoke(cli, ["roundtrip", "--format", "json", str(path)])
    assert cycles.exit_code == 0, cycles.output
    bigger = tmp_path / "bigger.urdf"
    bigger.write_bytes(converted.stdout_bytes)
    refused = runner.invoke(cli, ["convert", "--to", "ros1", str(bigger)])
    assert refused.exit_code == 2
    assert "larger than the" in refused.output


def test_a_generated_block_taken_apart_leaves_each_replaced_transmission_on_its_own():
    """lxml frees an element whose subtree was detached by scanning that whole subtree for
    other live elements: had the replaced transmissions stayed together in the removed
    ``<ros2_control>`` block, freeing them would cost N squared (converting 5,000 back to ROS 1
    took 25 s instead of 3 s; at 250 it does not show in the timings above)."""
    from lxml import etree

    from txtool.dialects.read import read_transmission, transmission_elements
    from txtool.dialects.translate import translate
    from txtool.transform.placement.placer import Placer

    ros2 = CliRunner().invoke(cli, ["convert", "--to", "ros2-p2", "-"], input=chain(3))
    root = etree.fromstring(ros2.stdout_bytes)
    elements = transmission_elements(root)
    placer = Placer(root, "mock_components/GenericSystem")
    for element in elements:
        t = translate(read_transmission(element, None), "ros1").transmission
        placer.place(element, t)
    placer.finish()
    assert "is what txtool generates" in placer.notes[0]
    assert [e.getparent() for e in elements] == [None, None, None]
    assert [e.get("name") for e in root.iter("transmission")] == ["t1", "t2", "t3"]
    assert not [*root.iter("ros2_control")]


def test_a_large_diff_names_a_path_outside_ascii(tmp_path):
    """The diff of a large ASCII document, written from its bytes, under a folder and a file
    name outside ASCII: the header names them as the lines' diff would (this once stopped
    with an internal error)."""
    from txtool.transform.linediff import unified_text
    from txtool.transform.migrate import diff_of

    folder = tmp_path / "n\u00e9"
    folder.mkdir()
    path = folder / "r\u00f6bot arm.urdf"
    path.write_text(chain(2_500))
    result = CliRunner().invoke(cli, ["migrate", "--diff", "--to", "ros2-p2", str(path)])
    assert result.exit_code == 1, result.output
    name = str(path).lstrip("/")
    assert result.stdout.startswith(f"--- a/{name}\n+++ b/{name}\n@@ ")
    converted = CliRunner().invoke(cli, ["convert", "--to", "ros2-p2", str(path)]).stdout_bytes
    before, after = path.read_bytes(), converted
    assert isinstance(diff_of(str(path), before, after), str)  # the header is not ASCII
    assert isinstance(diff_of("robot.urdf", before, after), bytes)  # written as it is
    assert result.stdout == unified_text(before.decode().splitlines(keepends=True),
                                         after.decode().splitlines(keepends=True),
                                         f"a/{name}", f"b/{name}")


def test_a_conversion_leaves_no_reference_cycles():
    """Every object a large conversion makes is freed as soon as it is let go (a cycle, such
    as a written transmission referring to its follower and back, waits for the collector,
    whose pass then walks every object the command still holds)."""
    import gc

    from txtool.io.xmlio import Source, parse_bytes
    from txtool.transform.convert import convert_source

    data = chain(300).encode()
    enabled = gc.isenabled()
    gc.disable()
    try:
        gc.collect()
        for target in ("ros2-p2", "ros2-p1", "ros1"):
            converted = convert_source(Source("r.urdf", data, parse_bytes(data, "r.urdf")),
                                       target)  # type: ignore[arg-type]
            assert converted.converted in (0, 300)
            del converted
            assert gc.collect() == 0, target
    finally:
        if enabled:
            gc.enable()


def _robots_alive(before: frozenset[int] = frozenset()) -> list[int]:
    """How many children each ``<robot>`` element alive in this process has, and -1 for each
    ROS 1 ``<transmission>`` alive (one read; the conversion's own templates are ROS 2), of
    those not among ``before`` (ids of elements alive before)."""
    import gc

    from lxml import etree

    return [len(node) if node.tag == "robot" else -1 for node in gc.get_objects()
            if isinstance(node, etree._Element) and id(node) not in before and (
                node.tag == "robot" or node.tag == "transmission"
                and node.find("type") is not None)]


def _transmissions_first(text: str) -> str:
    """``text`` (a :func:`chain`) with its transmissions before its links and joints."""
    head, _, rest = text.partition("\n")
    body, _, end = rest.rpartition("\n</robot>")
    lines = body.split("\n")
    first = next(i for i, line in enumerate(lines) if line.startswith("<transmission"))
    return "\n".join([head, *lines[first:], *lines[:first]]) + "\n</robot>" + end


@pytest.mark.parametrize("order", ["links first", "transmissions first"])
@pytest.mark.parametrize("args", [["migrate", "--diff", "--to", "ros2-p2"],
                                  ["convert", "--to", "ros2-p2"]])
def test_the_document_read_is_freed_before_the_written_bytes_are_parsed(tmp_path, monkeypatch,
                                                                          args, order):
    """A large robot needs one tree at a time. The check reads what the edits wrote from
    the root's first child recorded on (:class:`.conversion_edits.Window`: its links and
    joints before it are compared as bytes), beside the converted tree: a parse of a few
    children and the block's marker. Where it reads the whole document (the transmissions
    first), it does so once the converted tree is gone (its memory then takes the new tree).
    The transmissions a conversion replaced are gone before the document is written."""
    import gc

    from lxml import etree

    import txtool.transform.convert as convert
    import txtool.transform.edits.conversion_edits as conversion_edits

    gc.collect()
    before = frozenset(id(node) for node in gc.get_objects() if isinstance(node, etree._Element))
    path = tmp_path / "chain.urdf"
    text = chain(200) if order == "links first" else _transmissions_first(chain(200))
    path.write_text(text)
    alive: dict[str, list[int]] = {}
    parsed: list[int] = []
    real_parse, real_edits = conversion_edits.parse_bytes, convert.ConversionEdits.edits

    def parse_for_the_check(data: bytes, *args, **kwargs):  # type: ignore[no-untyped-def]
        alive["check"] = _robots_alive(before)
        parsed.append(len(data))
        return real_parse(data, *args, **kwargs)

    def edits(self, *args, **kwargs):  # type: ignore[no-untyped-def]
        alive["write"] = _robots_alive(before)
        return real_edits(self, *args, **kwargs)

    monkeypatch.setattr(conversion_edits, "parse_bytes", parse_for_the_check)
    monkeypatch.setattr(convert.ConversionEdits, "edits", edits)
    result = CliRunner().invoke(cli, [*args, str(path)])
    assert result.exit_code in (0, 1), result.output
    if order == "links first":  # the converted robot alive, and a parse of a few children
        assert alive["check"] == [401 + 1] and parsed[0] < 2_000 < len(text) // 20
    else:
        assert alive["check"] == [] and parsed[0] > len(text) // 4
    # The converted robot: its 400 links and joints and the generated block, no transmission.
    assert alive["write"] == [401 + 1]
