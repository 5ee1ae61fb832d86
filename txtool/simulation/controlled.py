"""``simulate --controllers``: the joints a controller configuration commands, through which
command interface, and with which gains.

The configuration is read as ``validate --controllers`` reads it
(:func:`txtool.io.controller_yaml.read_controller_file`, the claims of
:mod:`txtool.model.controllers`) and checked against the config the controller side of the run
reads (the candidate, else ROBOT) with the TX5xx rules and their configured severities: a
controller its manager refuses is a failure found without a run.

- A joint is driven by the first controller of the files that claims a command interface of it
  (a file of alternatives gives a note; the manager refuses the second one activated).
- A joint no controller commands gets no command from ros2_control or ros_control: its drive
  keeps it where it is (a brake, or the last command held). simulate holds it at the start of
  its reference and still checks that it stays there.
- Gains: those the driving controller carries (:func:`txtool.simulation.yaml_gains.
  controller_gains`), used where its PID's output is the joint effort. A position or velocity
  command interface hands the set-point to the drive's own servo loop, which simulate does not
  model: its computed-torque law stands in for that loop, at the default gains or those of
  ``--params``, and a note says so.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from txtool.io.controller_yaml import read_controller_file
from txtool.io.xmlio import InputError, Source
from txtool.lint.config import Overrides, SettingsCache
from txtool.lint.controller_files import (
    ControllerContext,
    controllers_of,
    exported_controllers,
    judged,
    package_root,
    provision_of,
)
from txtool.lint.problem import Problem
from txtool.model.controllers import (
    EFFORT,
    POS_VEL,
    POS_VEL_ACC,
    POSITION,
    STATE,
    VELOCITY,
    Claim,
    Controller,
)
from txtool.simulation.params import Params, merge, read_text
from txtool.simulation.yaml_gains import controller_gains

# ROS 1 hardware interface classes as the command interfaces they carry.
_ROS1_COMMANDS = {
    POSITION: ("position",), VELOCITY: ("velocity",), EFFORT: ("effort",),
    POS_VEL: ("position", "velocity"), POS_VEL_ACC: ("position", "velocity", "acceleration"),
}


@dataclass(frozen=True)
class Driver:
    """The controller that commands a joint: its name, type, command interfaces and where it
    is written (``file:line``)."""

    controller: str
    type: str
    interfaces: tuple[str, ...]
    file: str
    line: int

    @property
    def effort(self) -> bool:
        """Whether the actuator receives the controller's effort (the only command simulate's
        actuators take as they are)."""
        return self.interfaces == ("effort",)


@dataclass(frozen=True)
class Controlled:
    """What the controller configuration makes of a run."""

    files: tuple[str, ...]
    drivers: dict[str, Driver]  # joint -> the controller commanding it
    held: tuple[str, ...]  # joints of the model no controller commands
    refused: tuple[Problem, ...] = ()  # TX5xx errors: the manager refuses these controllers
    params: Params = field(default_factory=Params)  # the driving controllers' gains
    notes: tuple[str, ...] = ()

    def report(self, joints: tuple[str, ...]) -> dict[str, Driver | None]:
        """Per joint of the model: its controller, or None (held)."""
        return {joint: self.drivers.get(joint) for joint in joints}


def read(paths: tuple[str, ...], config: Source, joints: tuple[str, ...],
         followers: frozenset[str]) -> Controlled:
    """The controllers of ``paths`` with the config ``config`` whose moving ``joints`` they
    drive (mimic ``followers`` follow their leader, commanded or not)."""
    drivers: dict[str, Driver] = {}
    refused: list[Problem] = []
    notes: list[str] = []
    gains: list[Params] = []
    provision = provision_of(config.root)
    settings = SettingsCache(Overrides())
    for path in paths:
        file = read_controller_file(path)
        if file is None:
            raise InputError(f"{path}: no controller in it (a controller is a name holding a "
                             "'type', under a ROS 2 node's ros__parameters or a ROS 1 namespace)")
        controllers = controllers_of(file, exported_controllers(package_root(path)))
        if provision.has(file.generation):
            ctx = ControllerContext(path, config.path, file.generation, controllers, provision)
            found = judged(ctx, settings.for_file(path))
            refused += [p for p in found if p.severity == "error"]
            notes += [str(p) for p in found if p.severity != "error"]
        else:
            notes.append(f"{path}: its {_GENERATION[file.generation]} controllers' interfaces "
                         f"are not checked: {config.path} provides none for them")
        text = read_text(path)
        for controller in controllers:
            mine = _drive(controller, file.generation, path, joints, drivers, notes)
            if mine:
                gains.append(_gains_of(text, path, controller.name, mine, notes))
    held = tuple(j for j in joints if j not in drivers and j not in followers)
    return Controlled(paths, drivers, held, tuple(refused), merge(gains) if gains else Params(),
                      tuple(notes) + _interface_notes(drivers))


def _drive(controller: Controller, generation: str, path: str, joints: tuple[str, ...],
           drivers: dict[str, Driver], notes: list[str]) -> list[str]:
    """The joints ``controller`` drives, entered in ``drivers``: those it commands that no
    earlier controller does (a note for the others)."""
    commanded = _commanded(controller, generation)
    if not commanded and _names_joints(controller):
        notes.append(f"{path}:{controller.line}: which joints '{controller.name}' "
                     f"({controller.type}) commands is not known (txtool does not work out the "
                     "interfaces of its type): they are not counted as driven (--params FILE "
                     "takes its gains)")
    mine = [j for j in commanded if j in joints and j not in drivers]
    for joint in commanded:
        first = drivers.get(joint)
        if first is not None and first.controller != controller.name:
            notes.append(f"{path}:{controller.line}: '{controller.name}' also commands joint "
                         f"'{joint}': simulated as '{first.controller}' ({first.file}:"
                         f"{first.line}) drives it (the manager refuses the second of them "
                         "activated)")
    for joint in mine:
        drivers[joint] = Driver(controller.name, controller.type, commanded[joint], path,
                                controller.line)
    return mine


_GENERATION = {"ros1": "ROS 1", "ros2": "ROS 2"}


def _commanded(controller: Controller, generation: str) -> dict[str, tuple[str, ...]]:
    """Joint -> the command interfaces the controller takes of it, as names (position, ...)."""
    commanded: dict[str, tuple[str, ...]] = {}
    for claim in controller.claims or _pid_claims(controller):
        if not claim.command or claim.interface == STATE:
            continue
        names = _ROS1_COMMANDS.get(claim.interface, (claim.interface,)) \
            if generation == "ros1" else (claim.interface,)
        commanded[claim.joint] = commanded.get(claim.joint, ()) + names
    return commanded


def _names_joints(controller: Controller) -> bool:
    """Whether the parameters of a controller that claims nothing name joints (a type whose
    interfaces txtool does not work out; a state broadcaster's joints are only read)."""
    if "broadcaster" in controller.type or "state_controller" in controller.type:
        return False
    return any(controller.params.get(key) for key in ("joints", "joint", "dof_names"))


def _pid_claims(controller: Controller) -> tuple[Claim, ...]:
    """pid_controller's command interfaces, ``dof_names`` x ``command_interface``
    (pid_controller.cpp:308-320, ros2_controllers @94e74de), which validate does not check; a
    name with a ``/`` is a chained controller's reference, not a joint."""
    if controller.type != "pid_controller/PidController":
        return ()
    interface = controller.params.get("command_interface")
    names = controller.params.get("dof_names")
    if not isinstance(interface, str) or not interface or not isinstance(names, list):
        return ()
    return tuple(Claim(name, interface, True) for name in names
                 if isinstance(name, str) and name and "/" not in name and "$(" not in name)


def _gains_of(text: str, path: str, name: str, joints: list[str], notes: list[str]) -> Params:
    """The gains ``name`` carries for the ``joints`` it drives; those for other joints get a
    note, not a use."""
    found = controller_gains(text, path, name)
    notes += found.notes
    other = [j for j in found.joints if j not in joints]
    if other:
        notes.append(f"{path}: gains of '{name}' for " + ", ".join(f"'{j}'" for j in other)
                     + " not used: it does not drive them in this run")
    kept = {j: g for j, g in found.joints.items() if j in joints}
    where = {k: v for k, v in found.where.items() if k.split(".", 1)[1].strip('"') in kept}
    return Params(joints=kept, path=path, text=text, where=where)


def _interface_notes(drivers: dict[str, Driver]) -> tuple[str, ...]:
    """Per controller that does not command efforts: what simulate runs in its place."""
    by: dict[tuple[str, tuple[str, ...]], list[str]] = {}
    for joint, driver in drivers.items():
        if not driver.effort:
            by.setdefault((driver.controller, driver.interfaces), []).append(joint)
    return tuple(
        f"{_joints(joints)} {'/'.join(interfaces)} commands from '{name}': the drive's own "
        "servo loop tracks them, which simulate does not model; its computed-torque law "
        "stands in for that loop"
        for (name, interfaces), joints in by.items())


def _joints(names: list[str]) -> str:
    quoted = ", ".join(f"'{j}'" for j in names)
    return f"joint {quoted} takes" if len(names) == 1 else f"joints {quoted} take"
