"""What BB's URDF exporter dropped, for ``roundtrip A --against B`` where B came from BB.

BB's exporter (beam-bots/bb ``lib/bb/urdf/exporter.ex`` @330b7c6, ``build_transmission_elements/2``
and its comment) writes one ``<transmission>`` per actuator whose reduction is not 1.0, named
``<joint>_trans`` (``<joint>_<actuator>_trans`` once the transmission moved into the actuator),
with ``<type>transmission_interface/SimpleTransmission</type>``, a bare ``<joint name=...>`` and an
``<actuator>`` holding only ``<mechanicalReduction>``. It never writes ``offset`` or
``reversed?`` (URDF has no place for them, it says) nor a ``<hardwareInterface>``; the test
``test/bb/urdf/exporter_test.exs`` @330b7c6 checks that ``reversed? true`` alone exports no
``<transmission>``.
"""

from __future__ import annotations

from collections.abc import Sequence

from txtool.dialects.read import Found
from txtool.model.core import Transmission
from txtool.model.numbers import format_float
from txtool.model.semantics import NotLoadable, effective


def written_by_bb(found: Sequence[Found]) -> bool:
    """Whether every transmission of B has the shape BB's exporter writes (and there is one)."""
    return bool(found) and all(_bb_shaped(f) for f in found)


def _bb_shaped(found: Found) -> bool:
    t = found.transmission
    if t.dialect != "ros1" or t.type != "transmission_interface/SimpleTransmission":
        return False
    if len(t.joints) != 1 or len(t.actuators) != 1:
        return False
    joint, actuator = t.joints[0], t.actuators[0]
    bare = (not joint.interfaces and joint.offset is None and joint.mechanical_reduction is None
            and not actuator.interfaces and actuator.offset is None)
    return bare and t.name in (f"{joint.name}_trans", f"{joint.name}_{actuator.name}_trans")


def bb_drops(a: Sequence[Transmission], b: Sequence[Found]) -> list[str]:
    """What B lost of A's simple transmissions if B was written by BB's exporter, else ``[]``."""
    if not written_by_bb(b):
        return []
    by_joint = {f.transmission.joints[0].name: f.transmission for f in b}
    dropped = []
    for t in a:
        try:
            eff = effective(t)
        except NotLoadable:
            continue
        if eff.kind != "simple":
            continue
        dropped.extend(_drops(t, eff.joints[0], eff.actuator_reduction[0] * eff.joint_reduction[0],
                              eff.joint_offset[0], by_joint.get(eff.joints[0])))
    return dropped


def _drops(t: Transmission, joint: str, reduction: float, offset: float,
           written: Transmission | None) -> list[str]:
    where = f"joint '{joint}' ({t.name})"
    if written is None:
        if abs(reduction) != 1.0:
            return []  # BB writes every other reduction; a missing one is compare()'s to report
        kept = ("direction reversed, " if reduction < 0 else "") + (
            f"offset {format_float(offset)}" if offset else "")
        what = f" ({kept.rstrip(', ')} lost)" if kept else ""
        return [f"{where}: no <transmission>: BB's URDF exporter writes none for a reduction "
                f"of 1.0{what}"]
    lost = []
    written_reduction = written.actuators[0].mechanical_reduction
    if reduction < 0 and written_reduction is not None and (written_reduction.value or 0) > 0:
        lost.append(f"{where}: direction reversed lost: BB's URDF exporter drops 'reversed?' "
                    "(export with --bb-direction negative-reduction: a negative reduction "
                    "survives)")
    if offset != 0.0:
        lost.append(f"{where}: offset {format_float(offset)} lost: BB's URDF exporter writes "
                    "no offset")
    lost.append(f"{where}: no <hardwareInterface>: BB's URDF exporter writes none, and "
                "ros_control skips a joint without one (TX110)")
    return lost
