"""Why a candidate config fails: its maps compared with the robot's, by linear algebra.

Both drives are bound to the robot's joints, and the candidate's actuators to the robot's by name
(``S``), so the whole difference between them is three small matrices:

* ``G`` (joint space): the controller's position estimate is ``G x + g`` for the true position
  ``x``, ``G = ctrl.pos_a2j S plant.pos_j2a`` (velocities use the same ``G``). Agreement is
  ``G = I``.
* ``T`` (actuator space): for the pose at which the robot's actuators read ``y``, the candidate
  expects them to read ``T y``, ``T = S^T ctrl.pos_j2a plant.pos_a2j``. It is the same mismatch
  seen from the motors (``T = R G^-1 R^-1`` with ``R`` the robot's map).
* ``K`` (joint torque): the robot's transmissions apply ``K tau`` when the controller commands
  ``tau``, ``K = plant.eff_a2j S^T ctrl.eff_j2a``. When both effort maps are the transposes of
  their velocity maps (power conserved), ``K = G^T``; any other ``K`` is a different effort
  convention, such as ros_control's four-bar map.

Per group of coupled joints: a diagonal ``G`` names reversed joints and joint-side reduction
factors, a diagonal ``T`` the same for actuators, a permutation in ``G`` or ``T`` swapped joints
or actuators; offsets are compared after that. Where a ROS 1 config gives a coupled
transmission's roles to other members than the robot's, the roles are the cause and the shape
is what they do. Each finding is a :class:`~txtool.simulation.result.Cause` with its kind.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from txtool.mechanics.maps import TransmissionMap
from txtool.simulation.drive import Drive
from txtool.simulation.result import Cause

TOLERANCE = 1e-9  # relative: entries this small compared with the largest are zero
OFFSET_TOLERANCE = 1e-12  # rad or m


@dataclass(frozen=True)
class Comparison:
    """The candidate against the robot, in the robot's joint and actuator order."""

    G: np.ndarray
    T: np.ndarray
    K: np.ndarray
    offset: np.ndarray  # the candidate's joint offsets (constant of its actuator -> joint map)
    robot_offset: np.ndarray


def compare(plant: Drive, ctrl: Drive, S: np.ndarray) -> Comparison:
    """``S`` (candidate actuators x robot actuators) binds the actuators by name."""
    return Comparison(
        G=ctrl.pos_a2j @ S @ plant.pos_j2a,
        T=S.T @ ctrl.pos_j2a @ plant.pos_a2j,
        K=plant.eff_a2j @ S.T @ ctrl.eff_j2a,
        offset=ctrl.pos_a2j_c,
        robot_offset=plant.pos_a2j_c,
    )


def causes(plant: Drive, ctrl: Drive, S: np.ndarray, units: tuple[str, ...]) -> list[str]:
    """What differs between the candidate's maps and the robot's, one line per finding.

    Empty when the maps agree. ``units`` are the joints' position units (rad or m).
    """
    return [cause.text for cause in find(plant, ctrl, S, units)]


def find(plant: Drive, ctrl: Drive, S: np.ndarray, units: tuple[str, ...]) -> list[Cause]:
    """:func:`causes` with the kind of each."""
    c = compare(plant, ctrl, S)
    found: list[Cause] = []
    for joints in _groups(c, plant, ctrl):
        actuators = sorted({int(i) for i in np.nonzero(plant.vel_j2a[:, joints])[0]})
        found += _group_causes(c, plant, ctrl, joints, actuators, units)
    return found


def _groups(c: Comparison, plant: Drive, ctrl: Drive) -> list[list[int]]:
    """Joints that any of the maps couple, as connected components (in DoF order)."""
    n = len(plant.joints)
    link = (np.abs(c.G) + np.abs(c.G.T) + np.abs(c.K) + np.abs(c.K.T)) > 0
    for drive in (plant, ctrl):
        pattern = np.abs(drive.vel_j2a) > 0
        link |= (pattern.T.astype(int) @ pattern.astype(int)) > 0
    seen = np.zeros(n, dtype=bool)
    groups = []
    for start in range(n):
        if seen[start]:
            continue
        stack, group = [start], []
        seen[start] = True
        while stack:
            v = stack.pop()
            group.append(v)
            for w in np.nonzero(link[v] & ~seen)[0]:
                seen[w] = True
                stack.append(int(w))
        groups.append(sorted(group))
    return groups


def _group_causes(c: Comparison, plant: Drive, ctrl: Drive, joints: list[int],
                  actuators: list[int], units: tuple[str, ...]) -> list[Cause]:
    names = [plant.joints[v] for v in joints]
    kinds = _kinds(plant, ctrl, names)
    G = c.G[np.ix_(joints, joints)]
    if kinds or np.any(np.all(G == 0, axis=1)):
        return kinds  # a joint the candidate cannot measure: the binding reasons say why
    T = c.T[np.ix_(actuators, actuators)]
    K = c.K[np.ix_(joints, joints)]
    # Offsets that travel with swapped joints are not a difference of their own.
    by_joint = None if _diagonal(G) else _permutation(G)
    swapped = by_joint is not None and _unit(G, by_joint)
    plain = c.offset[joints] - c.robot_offset[joints]
    if swapped and _diagonal(T):
        # A reversed actuator of a differential reads as swapped joints too; with offsets that
        # do not travel with the swap, the actuator factor is the reading with fewer changes.
        residual = c.offset[joints] - _pattern(G).astype(float) @ c.robot_offset[joints]
        if np.abs(residual).max() > OFFSET_TOLERANCE >= np.abs(plain).max():
            swapped = False
    out = _position(plant, ctrl, joints, G, T, [plant.actuators[i] for i in actuators],
                    prefer_swap=swapped or not _diagonal(T))
    roles = _roles(plant, ctrl, names)
    if roles and out:
        # The position reading is what the swapped roles do, not a change of its own.
        reading = "; ".join(cause.text for cause in out)
        out = [Cause("roles_swapped", f"{roles[0].text}; the loader then reads: {reading}")]
        out += roles[1:]
    carried = _pattern(G).astype(float) if swapped else np.eye(len(joints))
    offset = c.offset[joints] - carried @ c.robot_offset[joints]
    for k, v in enumerate(joints):
        if abs(offset[k]) > OFFSET_TOLERANCE:
            out.append(Cause("offset", f"joint '{plant.joints[v]}': offset off by "
                             f"{offset[k]:+.4g} {units[v]} in {_in(ctrl, plant.joints[v])} "
                             f"({c.offset[v]:.6g}, the robot's {c.robot_offset[v]:.6g})"))
    if not np.allclose(K, G.T, rtol=0.0, atol=TOLERANCE * np.abs(G).max()):
        out.append(_effort(ctrl, names, K))
    if out:
        out += _xml_order(plant, ctrl, names)
    return out


def _position(plant: Drive, ctrl: Drive, joints: list[int], G: np.ndarray, T: np.ndarray,
              motors: list[str], prefer_swap: bool = True) -> list[Cause]:
    """The simplest reading that fits: joint factors, a plain joint swap (unless
    ``prefer_swap`` is off), actuator factors, a scaled joint swap, an actuator swap; else the
    matrix."""
    names = [plant.joints[v] for v in joints]
    if _diagonal(G):
        return [_joint_factor(plant, ctrl, v, G[k, k]) for k, v in enumerate(joints)
                if not _close(G[k, k], 1.0)]
    by_joint = _permutation(G)
    if prefer_swap and by_joint is not None and _unit(G, by_joint):
        return [Cause("joints_swapped", _swapped("joints", names, G, by_joint, ctrl, names[0])
                      + _same_as(T, motors))]
    if _diagonal(T):
        return [_actuator_factor(plant, ctrl, motors[k], T[k, k]) for k in range(len(motors))
                if not _close(T[k, k], 1.0)]
    if by_joint is not None:
        return [Cause("joints_swapped", _swapped("joints", names, G, by_joint, ctrl, names[0]))]
    if (by_actuator := _permutation(T)) is not None:
        return [Cause("actuators_swapped",
                      _swapped("actuators", motors, T, by_actuator, ctrl, names[0]))]
    return [Cause("coupling", f"{_in(ctrl, names[0])}: joints {_list(names)} are coupled "
                  f"differently from the robot's (its position estimates are {_matrix(G)} "
                  "times the true positions)")]


def _roles(plant: Drive, ctrl: Drive, names: list[str]) -> list[Cause]:
    """ROS 1 roles of these joints' transmissions given to other members than the robot's
    (``Drive.roles`` lists the members in XML order).

    ros_control indexes a coupled transmission's parameters by ``<role>`` but fills the joint
    and actuator data in XML order (ros-controls/ros_control transmission_interface/src/
    four_bar_linkage_transmission_loader.cpp:49 @17b626a, likewise the differential loader;
    joint_state_interface_provider.cpp:132 @133d768; see :mod:`txtool.views.effective`), so
    roles exchanged between members that keep their places move the reductions and offsets
    to the other member.
    """
    out = []
    for tmap in ctrl.maps:
        mine, theirs = ctrl.roles.get(tmap.name), plant.roles.get(tmap.name)
        if mine is None or theirs is None or not set(tmap.joints) & set(names):
            continue
        # Members that kept their place in the XML but not their role (a member moved with
        # its role, such as two joints' names exchanged, reads as a swap of those members).
        place, robot_place = list(mine), list(theirs)
        moved = [(member, role, theirs[member]) for member, role in mine.items()
                 if member in theirs and theirs[member] != role
                 and place.index(member) == robot_place.index(member)]
        for side, members in (("joint", tmap.joints), ("actuator", tmap.actuators)):
            pairs = [f"'{m}' has {role}, the robot's {robot}" for m, role, robot in moved
                     if m in members]
            if pairs:
                out.append(Cause("roles_swapped", f"transmission '{tmap.name}': {side} roles "
                                 f"swapped in the config ({'; '.join(pairs)})"))
    return out


def _unit(M: np.ndarray, p: np.ndarray) -> bool:
    """The permutation ``p`` of ``M`` moves values without scaling them."""
    return all(_close(M[k, p[k]], 1.0) for k in range(len(p)))


def _kinds(plant: Drive, ctrl: Drive, names: list[str]) -> list[Cause]:
    """Joints whose transmission in the config is of another kind than the robot's."""
    out = []
    for joint in names:
        mine, theirs = _transmission(ctrl, joint), _transmission(plant, joint)
        if (mine and mine.kind) != (theirs and theirs.kind):
            kind = "missing_transmission" if mine is None else "transmission_kind"
            out.append(Cause(kind, f"joint '{joint}': the config has {_kind(mine)} where the "
                             f"robot has {_kind(theirs)}"))
    return out


def _kind(tmap: TransmissionMap | None) -> str:
    if tmap is None:
        return "no transmission"
    article = {"simple": "a simple", "differential": "a differential", "four_bar": "a four-bar"}
    return f"{article[tmap.kind]} transmission '{tmap.name}'"


def _close(a: float, b: float) -> bool:
    return abs(a - b) <= TOLERANCE * max(abs(a), abs(b))


def _diagonal(M: np.ndarray) -> bool:
    return not np.any(_pattern(M) & ~np.eye(len(M), dtype=bool))


def _pattern(M: np.ndarray) -> np.ndarray:
    """Where ``M`` is nonzero, ignoring round-off."""
    return np.abs(M) > TOLERANCE * np.abs(M).max()


def _permutation(M: np.ndarray) -> np.ndarray | None:
    """``p`` with one entry per row at column ``p[i]`` and per column, else None."""
    big = _pattern(M)
    if not (np.all(big.sum(axis=0) == 1) and np.all(big.sum(axis=1) == 1)):
        return None
    return np.argmax(big, axis=1)


def _joint_factor(plant: Drive, ctrl: Drive, v: int, gain: float) -> Cause:
    """Joint ``v`` is read as ``gain * x``: the candidate's reduction is ``1/gain`` times."""
    joint = plant.joints[v]
    values = _values(plant, ctrl, joint, "joint", 1.0 / gain)
    return Cause(_factor_kind(gain),
                 f"joint '{joint}': {_factor(1.0 / gain)} in {_in(ctrl, joint)}{values}")


def _actuator_factor(plant: Drive, ctrl: Drive, actuator: str, gain: float) -> Cause:
    """The candidate expects actuator readings ``gain`` times the robot's: so is its reduction."""
    values = _values(plant, ctrl, actuator, "actuator", gain)
    owner = _owner(ctrl, actuator)
    where = f"the config's transmission '{owner}'" if owner else "the config"
    return Cause(_factor_kind(gain), f"actuator '{actuator}': {_factor(gain)} in {where}{values}")


def _factor_kind(k: float) -> str:
    return "direction" if _close(k, -1.0) else "reduction"


def _factor(k: float) -> str:
    if _close(k, -1.0):
        return "direction reversed"
    size = f"reduction off by a factor {abs(k):.4g}"
    return f"direction reversed and {size}" if k < 0 else size


def _swapped(what: str, names: list[str], M: np.ndarray, p: np.ndarray, ctrl: Drive,
             joint: str) -> str:
    """``names[i]`` is read as ``M[i, p[i]]`` times ``names[p[i]]``."""
    pairs = [f"'{names[i]}' reads '{names[int(p[i])]}'"
             + ("" if _close(M[i, p[i]], 1.0) else f" x{M[i, p[i]]:.4g}")
             for i in range(len(names)) if p[i] != i or not _close(M[i, p[i]], 1.0)]
    moved = [names[i] for i in range(len(names)) if p[i] != i]
    return f"{what} {_list(moved)} swapped in {_in(ctrl, joint)} ({'; '.join(pairs)})"


def _same_as(T: np.ndarray, motors: list[str]) -> str:
    """The actuator-space reading of a joint swap, when it is as simple (symmetric maps)."""
    if _diagonal(T):
        changed = [f"{_factor(T[k, k])} on actuator '{motors[k]}'" for k in range(len(motors))
                   if not _close(T[k, k], 1.0)]
        return f"; the same as {' and '.join(changed)}" if changed else ""
    p = _permutation(T)
    if p is not None and np.any(p != np.arange(len(p))) and _unit(T, p):
        moved = [m for k, m in enumerate(motors) if p[k] != k]
        return f"; the same as swapping actuators {_list(moved)}"
    return ""


def _effort(ctrl: Drive, names: list[str], K: np.ndarray) -> Cause:
    """An effort map that is not the transpose of the velocity map, e.g. ROS 1's four-bar.

    ros_control computes ``tau_j1 = nj1 na1 tau_a1``, ``tau_j2 = nj2 (na2 tau_a2 - nj1 na1
    tau_a1)`` (ros-controls/ros_control transmission_interface/include/transmission_interface/
    four_bar_linkage_transmission.h:241-242 actuatorToJointEffort, :309-310 the inverse, at
    133d768c). ros2_control's four_bar_linkage_transmission.hpp had the same lines (:298-300
    and :340-341 at 057d3673) until PR #1837 made them ``A^T``: ``tau_j1 = nj1 na1 tau_a1 + na2
    tau_a2``, ``tau_j2 = nj2 na2 tau_a2`` (its test/four_bar_linkage_transmission_test.cpp
    WhiteBoxTest.MoveBothJoints expects (-160, -400) from tau_a (3, 5), ar (10, -20), jr
    (-2, 4) at 15c1af27; ROS 1 gives (-60, -160)). :mod:`txtool.mechanics.maps` has both.
    """
    ros1 = [m.name for m in ctrl.maps if m.kind == "four_bar" and m.convention == "ros1"
            and set(m.joints) & set(names)]
    applied = f"the applied torques of {_list(names)} are {_matrix(K)} times the commanded ones"
    if ros1:
        return Cause("effort_convention", f"transmission '{ros1[0]}': the config's effort map "
                     "is ros_control's (ROS 1) four-bar map, which does not conserve power "
                     "(ros_control#523), while the robot's is the power-conserving one of "
                     f"ros2_control (PR #1837): {applied}")
    return Cause("effort_convention", f"{_in(ctrl, names[0])}: a different effort convention, "
                 "the effort map is not the transpose of the velocity map as the robot's is "
                 f"({applied})")


def _xml_order(plant: Drive, ctrl: Drive, names: list[str]) -> list[Cause]:
    """ros2_control binds coupled parameters in XML order to the joints sorted by name."""
    hints = []
    for tmap in ctrl.maps:
        order = ctrl.xml_order.get(tmap.name)
        if order is None or tmap.kind == "simple" or not set(tmap.joints) & set(names):
            continue
        robot_order = plant.xml_order.get(tmap.name)
        for listed, kind, params in (
            (order[0], "joints", (tmap.joint_reduction, tuple(tmap.offset))),
            (order[1], "actuators", (tmap.actuator_reduction,)),
        ):
            bound = tuple(sorted(set(listed)))
            if list(listed[:2]) == list(bound) or not any(p[0] != p[1] for p in params):
                continue
            if robot_order is not None and robot_order == order:
                continue
            hints.append(Cause("xml_order", f"transmission '{tmap.name}' lists its {kind} as "
                               f"{', '.join(listed)}: ros2_control takes their parameters in "
                               f"XML order but binds them to the {kind} sorted by name "
                               f"({', '.join(bound)}); roles are not used (ros2_control#3382)"))
    return hints


def _values(plant: Drive, ctrl: Drive, name: str, side: str, factor: float) -> str:
    """Both reductions, when they differ by ``factor`` (else the parameters do not say it)."""
    mine, theirs = _reduction(ctrl, name, side), _reduction(plant, name, side)
    if mine is None or theirs is None or not _close(mine, factor * theirs):
        return ""
    return f" (reduction {mine:.6g}, the robot's {theirs:.6g})"


def _reduction(drive: Drive, name: str, side: str) -> float | None:
    """The reduction that scales ``name``'s reading: a simple transmission's product, a coupled
    one's on ``side`` (the four-bar's first actuator and joint only act as ``ar1 jr1``)."""
    for tmap in drive.maps:
        members = tmap.joints if side == "joint" else tmap.actuators
        if name not in members:
            continue
        ar, jr = tmap.actuator_reduction, tmap.joint_reduction
        k = members.index(name)
        if tmap.kind == "simple" or (tmap.kind == "four_bar" and k == 0):
            return ar[0] * jr[0]
        return (jr if side == "joint" else ar)[k]
    return 1.0 if name in drive.direct else None


def _owner(drive: Drive, actuator: str) -> str:
    if actuator in drive.actuators:
        return drive.transmission_of[drive.actuators.index(actuator)]
    return ""


def _transmission(drive: Drive, joint: str) -> TransmissionMap | None:
    return next((m for m in drive.maps if joint in m.joints), None)


def _in(ctrl: Drive, joint: str) -> str:
    tmap = _transmission(ctrl, joint)
    if tmap is None:
        return "the config (no transmission: identity)"
    return f"the config's transmission '{tmap.name}'"


def _list(names: list[str]) -> str:
    quoted = [f"'{n}'" for n in names]
    return quoted[0] if len(quoted) == 1 else ", ".join(quoted[:-1]) + " and " + quoted[-1]


def _matrix(M: np.ndarray) -> str:
    M = np.where(_pattern(M), M, 0.0)
    return "[" + "; ".join(" ".join(f"{x:.4g}" for x in row) for row in M) + "]"
