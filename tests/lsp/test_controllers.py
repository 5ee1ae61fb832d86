"""``txtool lsp`` and controller configurations: a robot's package and the controller package
beside it (``arm_description``, ``arm_control``), checked as ``txtool validate`` checks them,
with the findings (TX5xx) shown in both files, over JSON-RPC as an editor speaks it.

One session: open the robot (the controller file, not opened, gets its finding too), open the
controller file, type the fix in it (both files clear), type a robot the controllers no longer
fit (both files show it again, from the buffers, not the disk), close.
"""

from __future__ import annotations

import asyncio
import sys
from collections.abc import Awaitable, Callable
from pathlib import Path

import pytest
from lsprotocol import types as lsp

from tests.lsp.robots import ARM
from tests.lsp.test_client import ROOT, WAIT, Editor, codes, full_change

# The language-server tests' arm, driven through effort handles with a reduction of 50.
ROBOT = (ARM.replace("PositionJointInterface", "hardware_interface/EffortJointInterface")
         .replace(">0</mechanicalReduction>", ">50</mechanicalReduction>"))
TRANSMISSION_JOINT = 11  # 0-based line of the transmission's <joint name="shoulder">
CONTROLLERS = """\
arm:
  joint_state_controller:
    type: joint_state_controller/JointStateController
  shoulder_controller:
    type: position_controllers/JointPositionController
    joint: shoulder
"""
PACKAGE = """<?xml version="1.0"?>
<package format="2"><name>{}</name><version>0.0.0</version><description>d</description>
<maintainer email="m@example.com">m</maintainer><license>BSD</license>
<buildtool_depend>catkin</buildtool_depend></package>
"""
REFUSED = ("controller 'shoulder_controller' (position_controllers/JointPositionController): "
           "joint 'shoulder' has no hardware interface 'hardware_interface::"
           "PositionJointInterface'")


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    (tmp_path / ".git").mkdir()
    for package, folder, name, text in (("arm_description", "urdf", "arm.urdf", ROBOT),
                                        ("arm_control", "config", "controllers.yaml",
                                         CONTROLLERS)):
        (tmp_path / "src" / package / folder).mkdir(parents=True)
        (tmp_path / "src" / package / "package.xml").write_text(PACKAGE.format(package))
        (tmp_path / "src" / package / folder / name).write_text(text)
    return tmp_path


def test_controller_findings_in_both_files(workspace: Path) -> None:
    asyncio.run(asyncio.wait_for(_session(workspace, _edits), 90))


async def _session(folder: Path, body: Callable[[Editor, Path], Awaitable[None]]) -> None:
    """``body`` in a session of the server whose workspace is ``folder``, which then shuts
    down and exits cleanly."""
    editor = Editor()
    await editor.start_io(sys.executable, "-m", "txtool", "lsp", cwd=str(ROOT))
    server = editor._server
    assert server is not None
    try:
        await asyncio.wait_for(editor.initialize_async(lsp.InitializeParams(
            capabilities=lsp.ClientCapabilities(),
            workspace_folders=[lsp.WorkspaceFolder(uri=folder.as_uri(), name="ws")])), WAIT)
        editor.initialized(lsp.InitializedParams())
        await body(editor, folder)
        await asyncio.wait_for(editor.shutdown_async(None), WAIT)
        editor.exit(None)
        await asyncio.wait_for(server.wait(), WAIT)
    finally:
        if server.returncode is None:
            server.kill()
        await editor.stop()
    assert server.stderr is not None
    assert (server.returncode, await server.stderr.read()) == (0, b"")


def _open(editor: Editor, uri: str, text: str) -> None:
    editor.text_document_did_open(lsp.DidOpenTextDocumentParams(text_document=lsp.TextDocumentItem(
        uri=uri, language_id="xml", version=1, text=text)))


def _at(diagnostic: lsp.Diagnostic) -> tuple[int, int, str]:
    return diagnostic.range.start.line, diagnostic.range.start.character, str(diagnostic.code)


async def _edits(editor: Editor, workspace: Path) -> None:
    robot = (workspace / "src" / "arm_description" / "urdf" / "arm.urdf").as_uri()
    yaml = (workspace / "src" / "arm_control" / "config" / "controllers.yaml").as_uri()

    # The robot opened: its transmission joint shows the refusal, pointing at the controller;
    # the controller file, not opened, gets it at the controller's name (as validate has it).
    _open(editor, robot, ROBOT)
    [in_robot] = await editor.diagnostics(robot, 1)
    assert _at(in_robot) == (TRANSMISSION_JOINT, 4, "TX501")
    assert in_robot.severity == lsp.DiagnosticSeverity.Error
    assert in_robot.message.startswith(f"controllers.yaml:4: {REFUSED}")
    assert in_robot.message.endswith("(controller-command-interface)")
    [related] = in_robot.related_information or []
    assert related.location.uri == yaml and related.location.range.start == lsp.Position(
        line=3, character=2)
    [in_yaml] = await editor.diagnostics(yaml, None)
    assert _at(in_yaml) == (3, 2, "TX501") and in_yaml.message.startswith(REFUSED)
    assert in_yaml.range.end == lsp.Position(line=3, character=2 + len("shoulder_controller"))

    # Opened, the controller file's buffer is what is checked.
    _open(editor, yaml, CONTROLLERS)
    assert [_at(d) for d in await editor.diagnostics(yaml, 1)] == [(3, 2, "TX501")]
    # Typing the fix there clears both files.
    fixed = CONTROLLERS.replace("position_controllers/", "effort_controllers/")
    editor.text_document_did_change(full_change(yaml, 2, fixed))
    assert await editor.diagnostics(yaml, 2) == []
    assert await editor.diagnostics(robot, 1) == []

    # A robot whose transmission now gives position handles: the edited controllers (effort,
    # in the buffer only; position on disk) no longer fit it.
    position = ROBOT.replace("EffortJointInterface", "PositionJointInterface")
    editor.text_document_did_change(full_change(robot, 2, position))
    assert [_at(d) for d in await editor.diagnostics(robot, 2)] == [
        (TRANSMISSION_JOINT, 4, "TX501")]
    [in_yaml] = await editor.diagnostics(yaml, 2)
    assert _at(in_yaml) == (3, 2, "TX501") and "effort_controllers/" in in_yaml.message

    # Closing the controller file clears what it showed; the robot's check publishes it again
    # from the disk, where its controllers are the position ones the robot now fits.
    editor.text_document_did_close(lsp.DidCloseTextDocumentParams(
        text_document=lsp.TextDocumentIdentifier(uri=yaml)))
    assert await editor.diagnostics(yaml, None) == []
    editor.text_document_did_change(full_change(robot, 3, position + "\n"))
    assert codes(await editor.diagnostics(robot, 3)) == []


def test_a_robot_in_no_package_is_paired_with_nothing(tmp_path: Path) -> None:
    """Without a package.xml above it, a robot's folder may be any folder (a home folder):
    no walk for controller files starts there."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "arm.urdf").write_text(ROBOT)
    (tmp_path / "controllers.yaml").write_text(CONTROLLERS)
    asyncio.run(asyncio.wait_for(_session(tmp_path, _lone), 90))


async def _lone(editor: Editor, folder: Path) -> None:
    robot, yaml = (folder / "arm.urdf").as_uri(), (folder / "controllers.yaml").as_uri()
    _open(editor, robot, ROBOT)
    _open(editor, yaml, CONTROLLERS)
    # Each publishes itself, with nothing, and nothing else is published between.
    published = [await asyncio.wait_for(editor.published.get(), WAIT) for _ in range(2)]
    assert [(p.uri, p.version, list(p.diagnostics)) for p in published] == [
        (robot, 1, []), (yaml, 1, [])]


@pytest.mark.parametrize("one, other, family", [
    ("rrbot_description", "rrbot_control", True),
    ("rrbot_control", "rrbot_gazebo", True),
    ("ur_description", "ur_robot_driver", True),  # its config/ur_controllers.yaml
    ("ur_robot_driver", "ur_description", True),
    ("my_robot_description", "my_robot_bringup", True),
    ("my_robot_description", "my_other_control", False),
    ("rrbot_description", "rrbot2_control", False),
    ("arm", "arm_control", True),
    ("arm", "leg", False),
])
def test_the_packages_of_a_family(one: str, other: str, family: bool) -> None:
    from txtool.commands.lsp_controllers import related

    assert related(one, other) is family
