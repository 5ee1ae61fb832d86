"""The check of a conversion pairs each transmission as read with the one written by name and
says what did not survive in the order of the transmissions as read, however the written
document orders them."""

from __future__ import annotations

from txtool.dialects.read import read_source
from txtool.io.xmlio import Source, parse_bytes
from txtool.transform.check import round_trip

TX = ('<transmission name="{name}"><type>transmission_interface/SimpleTransmission</type>'
      '<joint name="j{name}"><hardwareInterface>hardware_interface/EffortJointInterface'
      '</hardwareInterface></joint><actuator name="m{name}"><mechanicalReduction>{n}'
      "</mechanicalReduction></actuator></transmission>")


def _robot(*transmissions: tuple[str, int]) -> bytes:
    return ('<robot name="r">' + "".join(TX.format(name=name, n=n) for name, n in transmissions)
            + "</robot>").encode()


def test_what_did_not_survive_is_said_in_the_order_read() -> None:
    read = _robot(("a", 5), ("b", 7), ("c", 9))
    originals = [found.transmission for found in read_source(
        Source("r.urdf", read, parse_bytes(read, "r.urdf")), locate=False)]
    written = parse_bytes(_robot(("c", 90), ("b", 7), ("a", 50)), "r.urdf").getroot()

    verdict = round_trip(originals, written)

    assert [loss.split("'")[1] for loss in verdict.losses] == ["a", "c"]
    assert all("did not survive the round trip" in loss for loss in verdict.losses)


def test_a_transmission_the_written_document_no_longer_holds_is_not_judged() -> None:
    read = _robot(("a", 5), ("b", 7))
    originals = [found.transmission for found in read_source(
        Source("r.urdf", read, parse_bytes(read, "r.urdf")), locate=False)]
    written = parse_bytes(_robot(("b", 70)), "r.urdf").getroot()

    assert [loss.split("'")[1] for loss in round_trip(originals, written).losses] == ["b"]


def test_same_named_transmissions_are_paired_in_document_order() -> None:
    # The first "a" read with the first "a" written, the second with the second.
    read = _robot(("a", 5), ("b", 7), ("a", 9))
    originals = [found.transmission for found in read_source(
        Source("r.urdf", read, parse_bytes(read, "r.urdf")), locate=False)]
    kept = parse_bytes(_robot(("a", 5), ("a", 9), ("b", 7)), "r.urdf").getroot()
    swapped = parse_bytes(_robot(("a", 9), ("b", 7), ("a", 5)), "r.urdf").getroot()

    assert round_trip(originals, kept).losses == []
    assert [loss.split(": ", 1)[1] for loss in round_trip(originals, swapped).losses] == [
        "reduction: {*: 5.0} -> {*: 9.0}", "reduction: {*: 9.0} -> {*: 5.0}"]
