"""What else decides who reads a robot converted to ROS 2, said as the next step.

The transmissions are half of it: the programs that load them are chosen by the robot's
``<gazebo>`` plugin and by its package's build type (:mod:`txtool.model.readers`). A robot
converted to ROS 2 that keeps ROS 1's gazebo_ros_control plugin is still run by ROS 1's
Gazebo (nothing under ROS 2 loads ``libgazebo_ros_control.so``), and a package whose
``package.xml`` still builds with catkin is not built by colcon's ament build types. Neither
has a faithful rewrite txtool could make alone: the ROS 2 plugins take a controllers file
(``<parameters>``) that ROS 1 kept on the parameter server, and a catkin CMakeLists.txt must
be ported with the manifest. So each is named, with what to change.
"""

from __future__ import annotations

import os
from collections.abc import Iterable

from lxml import etree

from txtool.io.package_xml import package_of, plugin_files, read_description
from txtool.model.readers import seen_in

# gazebo_ros2_control (Gazebo Classic: ros-controls/gazebo_ros2_control
# gazebo_ros2_control/src/gazebo_ros2_control_plugin.cpp) and gz_ros2_control (Gazebo Sim:
# ros-controls/gz_ros2_control gz_ros2_control/src/gz_ros2_control_plugin.cpp) load the
# hardware named in each <ros2_control> block: their own GazeboSystem / GazeboSimSystem.
GAZEBO_NEXT = (
    "the robot's <gazebo> plugin {filename} is ROS 1's gazebo_ros_control: nothing under ROS 2 "
    "loads it, and the converted transmissions are read only where it is replaced: by "
    "gazebo_ros2_control (Gazebo Classic: <plugin filename=\"libgazebo_ros2_control.so\" "
    "name=\"gazebo_ros2_control\"> with <parameters> naming the controllers file, and "
    "<plugin>gazebo_ros2_control/GazeboSystem</plugin> as the block's hardware) or gz_ros2_control "
    "(Gazebo Sim: filename \"gz_ros2_control-system\", name \"gz_ros2_control::"
    "GazeboSimROS2ControlPlugin\", hardware gz_ros2_control/GazeboSimSystem){namespace}")


def gazebo_plugin(root: etree._Element) -> list[str]:
    """The next step for a robot converted to ROS 2 that keeps gazebo_ros_control."""
    plugin = seen_in(root).ros1_plugin
    if plugin is None:
        return []
    line = f" (line {plugin.sourceline})" if plugin.sourceline else ""
    namespace = next((c for c in plugin if isinstance(c.tag, str)
                      and c.tag.rpartition("}")[2] == "robotNamespace"), None)
    said = (f"; its <robotNamespace>{(namespace.text or '').strip()}</robotNamespace> becomes "
            f"<ros><namespace>{(namespace.text or '').strip()}</namespace></ros>"
            if namespace is not None and (namespace.text or "").strip() else "")
    return [GAZEBO_NEXT.format(filename=f"'{(plugin.get('filename') or '').strip()}'{line}",
                               namespace=said)]


def package_gazebo_plugins(converted: Iterable[str]) -> list[str]:
    """The next step for each other description file (a ``.gazebo`` file a robot includes)
    that holds gazebo_ros_control in a package of which ``converted`` were converted to
    ROS 2 (each converted file says its own)."""
    done = {os.path.abspath(path) for path in converted}
    folders = {os.path.dirname(package.manifest) for path in converted
               if (package := package_of(path)) is not None}
    steps = []
    for folder in sorted(folders):
        for candidate in plugin_files(folder):
            if os.path.abspath(candidate) in done:
                continue
            root = read_description(candidate)
            if root is not None:
                steps.extend(f"{_shown(candidate)}: {step}" for step in gazebo_plugin(root))
    return steps


def package_build_types(paths: Iterable[str]) -> list[str]:
    """The next step for each catkin package that holds one of ``paths`` (files converted
    to ROS 2), once per package."""
    said: dict[str, str] = {}
    for path in paths:
        package = package_of(path)
        if package is None or not package.ros1 or package.manifest in said:
            continue
        said[package.manifest] = (
            f"{_shown(package.manifest)}: package '{package.name}' builds with "
            f"{package.build_type}: ROS 2 (colcon, and txtool's readers) takes it for a ROS 1 "
            "package, whose converted transmissions nothing reads; make it an ament package: "
            "<buildtool_depend>ament_cmake</buildtool_depend> for catkin's, "
            "<export><build_type>ament_cmake</build_type></export>, and CMakeLists.txt "
            "ported (find_package(ament_cmake), install(DIRECTORY ...), ament_package())")
    return list(said.values())


def _shown(path: str) -> str:
    """``path`` relative to the working folder when it lies below it."""
    relative = os.path.relpath(path)
    return path if relative.startswith("..") else relative
