"""package.xml as the readers read it: the build type, and the transmission types exported.

REP 140 (package format 2/3): ``<export><build_type>`` says the build system (colcon reads it);
without it ``<buildtool_depend>catkin`` is a ROS 1 package. A pluginlib export is
``<export><transmission_interface plugin="${prefix}/file.xml"/>`` and the file lists
``<class ... base_class_type="transmission_interface::...">``.
"""

from __future__ import annotations

import os

import pytest

from txtool.io.package_xml import exports_of, read_package

MANIFEST = """<?xml version="1.0"?>
<package{format}>
  <name>{name}</name>
  {body}
</package>
"""


def manifest(tmp_path, body: str = "", *, name: str = "arm", format: str = ' format="3"'):
    path = tmp_path / name / "package.xml"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(MANIFEST.format(format=format, name=name, body=body))
    return str(path)


@pytest.mark.parametrize(("body", "build_type", "ros1", "ros2"), [
    ("<buildtool_depend>catkin</buildtool_depend>", "catkin", True, False),
    ("<buildtool_depend>ament_cmake</buildtool_depend>", "ament_cmake", False, True),
    # REP 140: the export wins over the build tool
    ("<buildtool_depend>catkin</buildtool_depend><export><build_type>ament_python"
     "</build_type></export>", "ament_python", False, True),
    ("<export><build_type>  </build_type></export>"
     "<buildtool_depend>cmake</buildtool_depend>", None, False, False),
    ("", None, False, False),
])
def test_the_build_type(tmp_path, body, build_type, ros1, ros2):
    info = read_package(manifest(tmp_path, body))
    assert info is not None and info.name == "arm" and info.format == 3
    assert (info.build_type, info.ros1, info.ros2) == (build_type, ros1, ros2)


def test_a_bad_format_attribute_reads_as_format_1(tmp_path):
    info = read_package(manifest(tmp_path, format=' format="three"'))
    assert info is not None and info.format == 1
    assert read_package(manifest(tmp_path, format="", name="old")).format == 1


def test_what_is_no_manifest_reads_as_none(tmp_path):
    other = tmp_path / "robot.xml"
    other.write_text("<robot name='r'/>")
    broken = tmp_path / "broken.xml"
    broken.write_text("<package><name>x</name>")
    fifo = tmp_path / "fifo.xml"
    os.mkfifo(fifo)
    for path in (other, broken, fifo, tmp_path / "missing.xml"):
        assert read_package(str(path)) is None


PLUGINS = """<{root}>
  <library path="lib/libvendor">
    <class name="vendor/Half" type="vendor::HalfLoader"
           base_class_type="transmission_interface::TransmissionLoader"/>
    <class type="vendor::Other" base_class_type="hardware_interface::SystemInterface"/>
  </library>
  <library path="lib/libmore">
    <class type="vendor::Unnamed" base_class_type="transmission_interface::TransmissionLoader"/>
  </library>
</{root}>
"""


@pytest.mark.parametrize("root", ["class_libraries", "library"])
def test_the_exported_transmission_types(tmp_path, root):
    body = ('<export><transmission_interface plugin="${prefix}/plugins.xml"/>'
            '<transmission_interface plugin="${prefix}/missing.xml"/></export>')
    path = manifest(tmp_path, body, name=f"vendor_{root}")
    text = PLUGINS.format(root=root)
    if root == "library":  # a file of one library, as pluginlib also takes it
        text = ('<library path="lib/libvendor"><class name="vendor/Half" type="vendor::Half" '
                'base_class_type="transmission_interface::TransmissionLoader"/>'
                '<class type="vendor::Other" base_class_type="hardware_interface::X"/></library>')
    (tmp_path / f"vendor_{root}" / "plugins.xml").write_text(text)
    names = [t.name for t in exports_of(path)]
    assert "vendor/Half" in names
    assert "vendor::Other" not in names  # another base class
    exported = exports_of(path)[0]
    assert exported.package == f"vendor_{root}" and "plugins.xml" in exported.describe()


def test_a_package_exporting_nothing_is_not_parsed(tmp_path):
    path = manifest(tmp_path, "<export><build_type>ament_cmake</build_type></export>")
    assert exports_of(path) == ()
    assert exports_of(str(tmp_path / "nowhere" / "package.xml")) == ()
