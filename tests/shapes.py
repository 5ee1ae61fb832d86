"""Robots of any size in the shapes people write them, for the scaling test and bench/.

Each shape holds ``n`` ROS 1 simple transmissions (the demo robot's have two each: ``n`` of them
are made from ``n // 2`` copies), each driving a revolute joint of a chain:

- ``after``: the links and joints, then the transmissions, one element a line;
- ``interleaved``: each link, joint and transmission together (a xacro macro per joint);
- ``one_line``: ``after`` on a single line;
- ``crlf``: ``after`` with CR LF line endings; ``utf16``: ``after`` in UTF-16 with a BOM;
- ``comments``: a comment and a blank line before each transmission;
- ``pretty``: every element on a line of its own, indented;
- ``ros2_control``: a ``<ros2_control>`` block that declares every joint, the transmissions after
  it (a conversion to ROS 2 moves each into the block);
- ``xacro``: ``interleaved`` as a xacro file writes it, each joint's parts in an
  ``xacro:if`` with ``${...}`` names, read as written;
- ``robot``: the demo robot (fixtures/demo_robot.urdf: comments, a differential, an offset)
  repeated under other names.
"""

from __future__ import annotations

import re
from pathlib import Path

SHAPES = ("after", "interleaved", "one_line", "crlf", "utf16", "comments", "pretty",
          "ros2_control", "xacro", "robot")
DEMO = Path(__file__).resolve().parent.parent / "fixtures" / "demo_robot.urdf"

LINK = '<link name="{p}l{i}"/>'
JOINT = ('<joint name="{p}j{i}" type="revolute"><parent link="{p}l{k}"/><child link="{p}l{i}"/>'
         '<limit lower="-1" upper="1" effort="10" velocity="2"/></joint>')
TRANSMISSION = (
    '<transmission name="{p}t{i}"><type>transmission_interface/SimpleTransmission</type>'
    '<joint name="{p}j{i}"><hardwareInterface>hardware_interface/EffortJointInterface'
    '</hardwareInterface></joint><actuator name="{p}m{i}"><mechanicalReduction>{n}'
    "</mechanicalReduction></actuator></transmission>")
DECLARATION = ('<joint name="j{i}"><command_interface name="effort"/>'
               '<state_interface name="position"/></joint>')


def _parts(i: int, prefix: str = "") -> tuple[str, str, str]:
    return (LINK.format(p=prefix, i=i), JOINT.format(p=prefix, i=i, k=i - 1),
            TRANSMISSION.format(p=prefix, i=i, n=10 + i % 90))


def robot(shape: str, n: int) -> bytes:
    """The document of ``shape`` (one of :data:`SHAPES`) with ``n`` transmissions."""
    if shape == "robot":
        return _demo(n)
    if shape == "xacro":
        return _xacro(n)
    parts = [_parts(i) for i in range(1, n + 1)]
    links = [f"  {link}\n  {joint}" for link, joint, _ in parts]
    drives = [f"  {t}" for _, _, t in parts]
    head = '<?xml version="1.0"?>\n<robot name="chain">\n  <link name="l0"/>\n'
    if shape == "interleaved":
        body = [f"{a}\n{b}" for a, b in zip(links, drives, strict=True)]
    elif shape == "comments":
        body = links + [f"\n  <!-- drive {i} -->\n{t}" for i, t in enumerate(drives, 1)]
    elif shape == "ros2_control":
        block = ('  <ros2_control name="hw" type="system">\n    <hardware><plugin>'
                 "mock_components/GenericSystem</plugin></hardware>\n" + "".join(
                     f"    {DECLARATION.format(i=i)}\n" for i in range(1, n + 1))
                 + "  </ros2_control>")
        body = [*links, block, *drives]
    else:
        body = links + drives
    text = head + "\n".join(body) + "\n</robot>\n"
    if shape == "one_line":
        return re.sub(r">\s+<", "><", text).encode()
    if shape == "crlf":
        return text.replace("\n", "\r\n").encode()
    if shape == "utf16":
        return text.replace('<?xml version="1.0"?>', '<?xml version="1.0" encoding="UTF-16"?>'
                            ).encode("utf-16")
    if shape == "pretty":
        return _pretty(text).encode()
    return text.encode()


def _pretty(text: str) -> str:
    """Every element on a line of its own, indented by its depth."""
    out, depth = [], 0
    for token in re.findall(r"<[^>]+>|[^<]+", text):
        if not token.strip():
            continue
        if token.startswith("</"):
            depth -= 1
            out.append("  " * depth + token)
        elif token.startswith("<") and not token.startswith(("<?", "<!")) and not (
                token.endswith("/>")):
            out.append("  " * depth + token)
            depth += 1
        elif token.startswith("<"):
            out.append("  " * depth + token)
        else:
            out[-1] += token.strip()  # a text stays beside its start tag
    joined = "\n".join(out)
    return re.sub(r"(<[^/!?][^>]*[^/]>)\n\s*([^<\s][^<]*)\n\s*(</)", r"\1\2\3", joined) + "\n"


def _xacro(n: int) -> bytes:
    parts = []
    for i in range(1, n + 1):
        link, joint, transmission = (part.replace(f"t{i}\"", f"t{i}_${{suffix}}\"")
                                     for part in _parts(i, "${prefix}"))
        parts.append(f'  <xacro:if value="${{use_{i}}}">\n    {link}\n    {joint}\n'
                     f"    {transmission}\n  </xacro:if>")
    return ('<?xml version="1.0"?>\n<robot name="chain" '
            'xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <link name="${prefix}l0"/>\n'
            + "\n".join(parts) + "\n</robot>\n").encode()


def _demo(n: int) -> bytes:
    """The demo robot's body ``n // 2`` times (each copy's names suffixed), in one robot."""
    text = DEMO.read_text()
    start, end = text.index(">", text.index("<robot")) + 1, text.rindex("</robot>")
    body = text[start:end]
    copies = [re.sub(r'(name|link)="([^"]+)"', rf'\1="\2_{k}"', body)
              for k in range(max(1, n // 2))]
    return (text[:start] + "".join(copies) + text[end:]).encode()
