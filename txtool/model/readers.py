"""The programs that read a robot description's transmissions: *readers*, and which ones read
a given file.

A verdict is only as good as its loader: a top-level ROS 1 ``<transmission>`` in a robot that
only ros2_control reads is read by nothing, and its missing reduction refuses nothing. Each
:class:`Reader` says which ``<transmission>`` elements it reads (top-level ones, or those inside
``<ros2_control>``), how it reads numbers (:func:`~txtool.model.distro.numbers_of` of its
distribution), which types it loads, and what it does with what it cannot read.
:func:`assume` picks a file's readers, each with the reason, in this order:

1. ``readers = [...]`` in the configuration: exactly those;
2. ``--ros-distro`` (or ``ros-distro`` in the configuration): that ROS generation's readers;
3. the document's ``<gazebo>`` plugins (``libgazebo_ros_control.so``, ``libgazebo_ros2_control.so``,
   ``gz_ros2_control-system`` / ``ign_ros2_control-system``), else those another description
   file of its package names (a fragment is read by what loads its robot); in a package only
   ROS 2 builds (ament, no catkin), ``libgazebo_ros_control.so`` decides nothing: no ROS 2
   build has it (``unloaded_plugin``, TX306);
4. the enclosing package's ``package.xml`` (catkin: ROS 1; ament_cmake / ament_python: ROS 2);
5. ``<ros2_control>`` blocks (ros2_control reads them; its ``<hardware><plugin>`` may name a
   simulator such as mujoco_ros2_control): this alone does not rule ROS 1 out;
6. nothing: every transmission is judged by the loader of its dialect (``decided`` False).

Steps 1-4 *decide*: a reader not chosen does not read the file. Any step leaves the
transmission types exported with pluginlib known (:mod:`txtool.io.package_xml`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field, replace
from enum import Enum

from lxml import etree

from txtool.io.xmlio import local
from txtool.model.distro import ROS2, Distro, NumberReading, numbers_of
from txtool.model.robot import ancestor


class Placement(str, Enum):
    """Which ``<transmission>`` elements a reader reads."""

    TOP_LEVEL = "top-level"  # children of the root <robot> (ros_control's TransmissionParser)
    IN_COMPONENT = "in-component"  # children of <ros2_control> (ros2_control's parser)


STANDARD = (
    "transmission_interface/SimpleTransmission",
    "transmission_interface/DifferentialTransmission",
    "transmission_interface/FourBarLinkageTransmission",
)


@dataclass(frozen=True)
class Reader:
    """A program that reads part of a robot description.

    ``key`` is the name users write (``readers = [...]``); ``reads`` the transmissions it reads;
    ``distro`` None for every distribution of its generation; ``unread`` what it does with a
    transmission it cannot load.
    """

    key: str
    title: str
    reads: Placement
    ros2: bool
    loads_types: bool  # loads the transmission type as a plugin (not its own fixed handling)
    unread: str
    source: str
    distro: Distro | None = None

    @property
    def distros(self) -> tuple[Distro, ...]:
        if self.distro is not None:
            return (self.distro,)
        return ROS2 if self.ros2 else (Distro.NOETIC,)

    @property
    def numbers(self) -> tuple[NumberReading, ...]:
        return tuple(dict.fromkeys(numbers_of(d) for d in self.distros))

    def named(self) -> str:
        if self.ros2 and self.distro is not None:
            return f"{self.key} ({self.distro.value})"
        return self.key

    def at(self, distro: Distro | None) -> Reader:
        if not self.ros2 or distro is None or not distro.ros2:
            return self
        return Reader(self.key, self.title, self.reads, self.ros2, self.loads_types,
                      self.unread, self.source, distro)


ROS_CONTROL = Reader(
    "ros_control", "ros_control's transmission loaders (Noetic)", Placement.TOP_LEVEL, False,
    True, "refuses the transmission and stops loading the ones after it",
    "ros-controls/ros_control transmission_interface/src/transmission_parser.cpp "
    "TransmissionParser::parse (root->FirstChildElement(\"transmission\"))",
)
GAZEBO_ROS_CONTROL = Reader(
    "gazebo_ros_control", "gazebo_ros_control's DefaultRobotHWSim (Gazebo Classic, Noetic)",
    Placement.TOP_LEVEL, False, False,
    "reads the first joint's first interface, never reductions; refuses an unknown interface",
    "ros-simulation/gazebo_ros_pkgs gazebo_ros_control/src/default_robot_hw_sim.cpp initSim",
)
FRANKA_GAZEBO = Reader(
    "franka_gazebo", "franka_gazebo's FrankaHWSim (Noetic)", Placement.TOP_LEVEL, False, False,
    "reads SimpleTransmission joints and their prefixed interfaces, never reductions",
    "frankaemika/franka_ros franka_gazebo/src/franka_hw_sim.cpp initSim",
)
ROS2_CONTROL = Reader(
    "ros2_control", "ros2_control's component parser and transmission loaders",
    Placement.IN_COMPONENT, True, True,
    "throws on a malformed <ros2_control> block; a type no loader has is never loaded",
    "ros-controls/ros2_control hardware_interface/src/component_parser.cpp "
    "parse_control_resources_from_urdf",
)
_NO_COMPONENT = "refuses a robot without <ros2_control> (\"plugin not active\")"
GAZEBO_ROS2_CONTROL = Reader(
    "gazebo_ros2_control", "gazebo_ros2_control (Gazebo Classic)", Placement.IN_COMPONENT, True,
    False, _NO_COMPONENT,
    "ros-controls/gazebo_ros2_control gazebo_ros2_control/src/gazebo_ros2_control_plugin.cpp "
    "GazeboRosControlPlugin::Load",
)
GZ_ROS2_CONTROL = Reader(
    "gz_ros2_control", "gz_ros2_control (Gazebo; ign_ros2_control before Jazzy)",
    Placement.IN_COMPONENT, True, False, _NO_COMPONENT,
    "ros-controls/gz_ros2_control gz_ros2_control/src/gz_ros2_control_plugin.cpp "
    "(ign_ros2_control/src/ign_ros2_control_plugin.cpp on Humble)",
)
MUJOCO_ROS2_CONTROL = Reader(
    "mujoco_ros2_control", "mujoco_ros2_control (MuJoCo)", Placement.IN_COMPONENT, True, False,
    "parses the robot with ros2_control's component parser",
    "ros-controls/mujoco_ros2_control (a ros2_control hardware plugin)",
)
READERS: dict[str, Reader] = {r.key: r for r in (
    ROS_CONTROL, GAZEBO_ROS_CONTROL, FRANKA_GAZEBO, ROS2_CONTROL, GAZEBO_ROS2_CONTROL,
    GZ_ROS2_CONTROL, MUJOCO_ROS2_CONTROL,
)}
READER_KEYS = tuple(READERS)


def parse_readers(names: Iterable[str]) -> tuple[Reader, ...]:
    """Readers by key; ``ValueError`` naming the choices for an unknown one."""
    found = []
    for name in names:
        reader = READERS.get(name.strip().lower())
        if reader is None:
            raise ValueError(f"unknown reader {name!r} (choose from {', '.join(READER_KEYS)})")
        found.append(reader)
    return tuple(found)


# -- gazebo_ros_control: the RobotHWSim plugins whose rules are known ---------------------------

DEFAULT_SIM = "gazebo_ros_control/DefaultRobotHWSim"
FRANKA_SIM = "franka_gazebo/FrankaHWSim"
# RobotHWSim plugins whose source says how they read transmissions (see Sim).
KNOWN_SIMS = (DEFAULT_SIM, FRANKA_SIM)
ACCEPTED = frozenset(
    prefix + kind + "JointInterface"
    for prefix in ("", "hardware_interface/")
    for kind in ("Effort", "Position", "Velocity")
)


class Sim:
    """The ``<gazebo>`` plugin that loads a ROS 1 robot, and the RobotHWSim type it runs.

    A ``<gazebo><plugin filename="libgazebo_ros_control.so">`` hands the robot's transmissions
    to the ``RobotHWSim`` named by ``<robotSimType>``, by default DefaultRobotHWSim
    (ros-simulation/gazebo_ros_pkgs gazebo_ros_control/src/gazebo_ros_control_plugin.cpp,
    ``Load``); plugins built on it, such as baxter_gazebo's
    ``libbaxter_gazebo_ros_control.so`` (RethinkRobotics/baxter_simulator
    baxter_gazebo/src/baxter_gazebo_ros_control_plugin.cpp @1224c44), behave the same.
    DefaultRobotHWSim does not use ros_control's TransmissionInterfaceLoader
    (default_robot_hw_sim.cpp ``initSim`` @01c3a2c): it reads each transmission's first joint
    and its first ``<hardwareInterface>``, accepts Effort/Position/VelocityJointInterface with
    or without the ``hardware_interface/`` prefix, takes the actuator's interface when the
    joint names none, never reads ``<mechanicalReduction>``, and refuses the robot ("No
    matching hardware interface found") for any other name. franka_gazebo's FrankaHWSim
    (frankaemika/franka_ros franka_gazebo/src/franka_hw_sim.cpp ``initSim`` @005ff25) reads
    no reductions either but takes only prefixed interface names.
    """

    def __init__(self, plugin: etree._Element, sim_type: str) -> None:
        self.plugin = plugin
        self.sim_type = sim_type

    @property
    def default(self) -> bool:
        return self.sim_type == DEFAULT_SIM

    @property
    def reader(self) -> Reader:
        return GAZEBO_ROS_CONTROL if self.default else FRANKA_GAZEBO

    def describe(self) -> str:
        filename = (self.plugin.get("filename") or "").strip()
        loader = "gazebo_ros_control" if self.default else self.sim_type
        return f"{loader} (run by this robot's <gazebo> plugin {filename})"


def accepts(interface: str) -> bool:
    """Whether DefaultRobotHWSim drives a joint through this ``<hardwareInterface>`` text."""
    return interface.strip() in ACCEPTED


# -- what the document says --------------------------------------------------------------------

# <gazebo> plugin file names (without "lib" and ".so") by their ending: vendors ship renamed
# builds of these plugins (franka_ros2's franka_ign_ros2_control-system).
ROS2_SIM_FILES = {
    "gazebo_ros2_control": GAZEBO_ROS2_CONTROL,
    "gz_ros2_control-system": GZ_ROS2_CONTROL,
    "ign_ros2_control-system": GZ_ROS2_CONTROL,
}


def _ros2_sim(filename: str) -> Reader | None:
    base = filename.rsplit("/", 1)[-1].removeprefix("lib").removesuffix(".so")
    return next((r for end, r in ROS2_SIM_FILES.items() if base.endswith(end)), None)
# <ros2_control><hardware><plugin> prefixes of the simulators' system plugins.
HARDWARE_SIMS = {
    "gazebo_ros2_control/": GAZEBO_ROS2_CONTROL,
    "gz_ros2_control/": GZ_ROS2_CONTROL,
    "ign_ros2_control/": GZ_ROS2_CONTROL,
    "mujoco_ros2_control/": MUJOCO_ROS2_CONTROL,
}


@dataclass(frozen=True)
class Seen:
    """What the document itself says about its readers."""

    sim: Sim | None = None  # a ROS 1 RobotHWSim whose rules are known
    ros1_plugin: etree._Element | None = None  # any gazebo_ros_control plugin
    ros2_plugins: tuple[tuple[etree._Element, Reader], ...] = ()
    components: int = 0  # <ros2_control> elements
    hardware: tuple[tuple[str, Reader], ...] = ()  # simulator hardware plugins named
    where: str = ""  # another file of the package, when the plugins were seen there

    @property
    def plugins(self) -> bool:
        return self.ros1_plugin is not None or bool(self.ros2_plugins)


def _kids(element: etree._Element, name: str) -> list[etree._Element]:
    return [c for c in element if isinstance(c.tag, str) and local(c) == name]


def seen_in(root: etree._Element) -> Seen:
    """The ``<gazebo>`` plugins and ``<ros2_control>`` blocks of a document."""
    sim = ros1 = None
    ros2: list[tuple[etree._Element, Reader]] = []
    for plugin in root.iter("{*}plugin", "plugin"):
        parent = plugin.getparent()
        if parent is None or not isinstance(parent.tag, str) or local(parent) != "gazebo":
            continue
        filename = (plugin.get("filename") or "").strip()
        base = filename.rsplit("/", 1)[-1]
        if base.endswith("gazebo_ros_control.so"):
            ros1 = ros1 if ros1 is not None else plugin
            named = _kids(plugin, "robotSimType")
            sim_type = (named[0].text or "").strip() if named else DEFAULT_SIM
            if sim is None and sim_type in KNOWN_SIMS:
                sim = Sim(plugin, sim_type)
        elif (reader := _ros2_sim(base)) is not None:
            ros2.append((plugin, reader))
    blocks = list(root.iter("{*}ros2_control", "ros2_control"))
    hardware = []
    for block in blocks:
        for element in _kids(block, "hardware"):
            for plugin in _kids(element, "plugin"):
                text = (plugin.text or "").strip()
                for prefix, reader in HARDWARE_SIMS.items():
                    if text.startswith(prefix):
                        hardware.append((text, reader))
    return Seen(sim, ros1, tuple(ros2), len(blocks), tuple(hardware))


# -- the choice ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class Stated:
    """What the user said: ``readers = [...]`` and ``--ros-distro`` / ``ros-distro``."""

    readers: tuple[Reader, ...] = ()
    distro: Distro | None = None
    origin: str = "configuration"  # where ``readers`` was said
    distro_said: str | None = None  # "--ros-distro jazzy", "ros-distro jazzy in FILE"


@dataclass(frozen=True)
class Package:
    """The enclosing package as the model needs it (see :mod:`txtool.io.package_xml`)."""

    name: str
    build_type: str | None
    both: bool = False  # the manifest builds under ROS 1 and ROS 2 ($ROS_VERSION conditions)

    @property
    def ros1(self) -> bool:
        return self.build_type == "catkin"

    @property
    def ros2(self) -> bool:
        return self.build_type in ("ament_cmake", "ament_python")

    @property
    def ros2_only(self) -> bool:
        return self.ros2 and not self.both


@dataclass(frozen=True)
class Assumption:
    """The readers assumed for one file, each with why, in the order found.

    ``decided``: a reader not listed does not read the file; otherwise each transmission is
    judged by the loader of its dialect, as when nothing is known. ``sim`` is the ROS 1
    RobotHWSim loading the robot (its findings name it). ``missing_components``: a ROS 2
    simulator plugin that refuses this robot, which has no ``<ros2_control>``.
    ``unloaded_plugin``: the document's ROS 1 gazebo_ros_control plugin when only ROS 2
    programs read it (no ROS 2 build has that plugin).
    """

    readers: tuple[Reader, ...] = ()
    because: tuple[str, ...] = ()
    decided: bool = False
    sim: Sim | None = None
    missing_components: etree._Element | None = None
    unloaded_plugin: etree._Element | None = None
    types: Callable[[], Mapping[str, str]] | None = field(default=None, compare=False)

    def reads(self, placement: Placement) -> bool:
        """Whether some reader of this file reads transmissions placed so."""
        if not self.decided:
            return True
        return any(r.reads is placement for r in self.readers)

    @property
    def distros(self) -> tuple[Distro, ...]:
        """The distributions whose loaders read the file (every one when nothing says)."""
        found = tuple(dict.fromkeys(d for r in self.readers for d in r.distros))
        return found or (Distro.NOETIC, *ROS2)

    @property
    def ros1(self) -> bool:
        return any(not r.ros2 for r in self.readers)

    @property
    def ros2(self) -> bool:
        return any(r.ros2 for r in self.readers)

    def known_type(self, name: str) -> str | None:
        """Where a non-standard transmission type is registered with pluginlib, or None."""
        return None if self.types is None else self.types().get(name)

    def names(self) -> tuple[str, ...]:
        return tuple(r.named() for r in self.readers)

    def explain(self) -> str:
        """``gz_ros2_control, ros2_control (<gazebo> plugin gz_ros2_control-system)``."""
        if not self.readers:
            return "no reader known"
        reasons = "; ".join(dict.fromkeys(self.because))
        return f"{', '.join(self.names())} ({reasons})"

    def summary(self) -> str:
        """``ros2_control (jazzy) [--ros-distro jazzy]; ...`` for the show command."""
        if not self.readers:
            return "not known (each transmission is judged by the loader of its dialect)"
        return "; ".join(f"{n} [{why}]" for n, why in zip(self.names(), self.because,
                                                           strict=True))


class _Choice:
    def __init__(self, distro: Distro | None) -> None:
        self.readers: list[Reader] = []
        self.because: list[str] = []
        self.distro = distro

    def add(self, reader: Reader, why: str) -> None:
        reader = reader.at(self.distro)
        if reader not in self.readers:
            self.readers.append(reader)
            self.because.append(why)


def _plugin_reason(plugin: etree._Element, where: str = "") -> str:
    said = f"<gazebo> plugin {(plugin.get('filename') or '').strip()}"
    return f"{said} in {where}" if where else said


def assume(root: etree._Element, package: Package | None = None, stated: Stated | None = None,
           types: Callable[[], Mapping[str, str]] | None = None,
           elsewhere: Callable[[], Seen | None] | None = None) -> Assumption:
    """The readers of a document (see the module documentation for the order).

    ``elsewhere`` gives the plugins another description file of the document's package names
    (asked only when the document names none): a fragment is read by what loads its robot.
    """
    stated = stated or Stated()
    own = seen = seen_in(root)
    # A ROS 2 package decides without them (and its plugins make no verdict milder): the
    # package's other files are read only for a ROS 1 package or a file outside any package.
    ros2_package = package is not None and package.ros2
    if (package is not None and package.ros2_only and seen.ros1_plugin is not None
            and not stated.readers and stated.distro is None):
        # A package only ROS 2 builds: no ROS 2 build has gazebo_ros_control, so its plugin
        # decides nothing (TX306 says so) and the package does.
        seen = replace(seen, sim=None, ros1_plugin=None)
    if not seen.plugins and elsewhere is not None and not ros2_package and not stated.readers:
        other = elsewhere()
        if other is not None and other.plugins:
            seen = replace(seen, sim=other.sim, ros1_plugin=other.ros1_plugin,
                           ros2_plugins=other.ros2_plugins, where=other.where)
    choice = _Choice(stated.distro)
    decided = True
    if stated.readers:
        for reader in stated.readers:
            choice.add(reader, f"readers in the {stated.origin}")
    elif stated.distro is not None:
        said = stated.distro_said or f"--ros-distro {stated.distro.value}"
        _by_generation(choice, seen, stated.distro.ros2, said)
    elif seen.ros1_plugin is not None or seen.ros2_plugins:
        if seen.ros1_plugin is not None:
            _by_generation(choice, seen, False, _plugin_reason(seen.ros1_plugin, seen.where))
        if seen.ros2_plugins:
            _by_generation(choice, seen, True,
                           _plugin_reason(seen.ros2_plugins[0][0], seen.where))
    elif package is not None and (package.ros1 or package.ros2):
        _by_generation(choice, seen, package.ros2, f"package.xml: {package.build_type}")
    else:
        decided = False
        if seen.components:
            choice.add(ROS2_CONTROL, "<ros2_control> blocks")
            for text, reader in seen.hardware:
                choice.add(reader, f"<ros2_control> hardware plugin {text}")
    sim = seen.sim if any(not r.ros2 for r in choice.readers) or not decided else None
    missing = None
    if not own.components:  # only the document's own plugins refuse it
        keys = {r.key for r in choice.readers}
        missing = next((p for p, r in own.ros2_plugins if r.key in keys), None)
    unloaded = None
    if decided and choice.readers and all(r.ros2 for r in choice.readers):
        unloaded = own.ros1_plugin
    return Assumption(tuple(choice.readers), tuple(choice.because), decided, sim, missing,
                      unloaded, types)


def _by_generation(choice: _Choice, seen: Seen, ros2: bool, why: str) -> None:
    """The readers of one ROS generation that the document's plugins and blocks name."""
    if not ros2:
        if seen.ros1_plugin is not None:
            sim = seen.sim
            reason = _plugin_reason(seen.ros1_plugin, seen.where)
            if sim is not None:
                choice.add(sim.reader, reason)
            # DefaultRobotHWSim does not use ros_control's loaders; the real robot's RobotHW does
            choice.add(ROS_CONTROL, f"a ROS 1 robot's own hardware: {why}")
        else:
            choice.add(ROS_CONTROL, why)
        return
    for plugin, reader in seen.ros2_plugins:
        choice.add(reader, _plugin_reason(plugin, seen.where))
    for text, reader in seen.hardware:
        choice.add(reader, f"<ros2_control> hardware plugin {text}")
    choice.add(ROS2_CONTROL, why)


def placement_of(element: etree._Element) -> Placement:
    """Where a ``<transmission>`` stands: inside a ``<ros2_control>`` block or not."""
    return Placement.IN_COMPONENT if ancestor(element, "ros2_control") is not None \
        else Placement.TOP_LEVEL
