"""``txtool lsp`` with a real client: pygls's ``LanguageClient`` starts ``python -m txtool lsp``
and speaks JSON-RPC with it over its standard input and output, as an editor does.

One session walks a user's edits: open a robot with known findings, take the quick fix, type
the fix of another finding, suppress one with a comment, hover over the transmission, open an
unsaved xacro file; the repository's configuration counts throughout; shutdown and exit leave
the server with exit status 0.
"""

from __future__ import annotations

import asyncio
import sys
from pathlib import Path

import pytest
from lsprotocol import types as lsp
from pygls.lsp.client import LanguageClient

from tests.lsp.robots import ARM, ARM_XACRO, REDUCTION, REDUCTION_LINE

ROOT = Path(__file__).resolve().parents[2]
WAIT = 15.0  # seconds for one answer; the whole session takes about two


class Editor(LanguageClient):
    """A client that keeps what the server publishes."""

    def __init__(self) -> None:
        super().__init__("test-editor", "1")
        self.published: asyncio.Queue[lsp.PublishDiagnosticsParams] = asyncio.Queue()

        @self.feature(lsp.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        def on_diagnostics(params: lsp.PublishDiagnosticsParams) -> None:
            self.published.put_nowait(params)

    async def diagnostics(self, uri: str, version: int | None) -> list[lsp.Diagnostic]:
        """The diagnostics published for ``version`` of ``uri`` (None: of no version)."""
        while True:
            params = await asyncio.wait_for(self.published.get(), WAIT)
            if params.uri == uri and params.version == version:
                return list(params.diagnostics)


def applied(text: str, edits: list[lsp.TextEdit]) -> str:
    """``text`` with ``edits`` applied, as an editor applies them (last first)."""
    lines = text.splitlines(keepends=True)

    def offset(position: lsp.Position) -> int:
        return sum(len(line) for line in lines[:position.line]) + position.character

    for edit in sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character),
                       reverse=True):
        text = text[:offset(edit.range.start)] + edit.new_text + text[offset(edit.range.end):]
    return text


def edits_of(action: lsp.CodeAction, version: int | None = None) -> list[lsp.TextEdit]:
    """The edits of ``action``: one document's, naming the version they were made for."""
    assert action.edit is not None and action.edit.changes is None
    [change] = action.edit.document_changes or []
    assert isinstance(change, lsp.TextDocumentEdit)
    assert change.text_document.version is not None
    assert version is None or change.text_document.version == version
    return [edit for edit in change.edits if isinstance(edit, lsp.TextEdit)]


def full_change(uri: str, version: int, text: str) -> lsp.DidChangeTextDocumentParams:
    return lsp.DidChangeTextDocumentParams(
        text_document=lsp.VersionedTextDocumentIdentifier(uri=uri, version=version),
        content_changes=[lsp.TextDocumentContentChangeWholeDocument(text=text)])


def codes(diagnostics: list[lsp.Diagnostic]) -> list[str]:
    return sorted(str(d.code) for d in diagnostics)


@pytest.fixture
def repository(tmp_path: Path) -> Path:
    """A repository whose configuration lowers TX300 to an info."""
    (tmp_path / ".git").mkdir()
    (tmp_path / ".txtool.toml").write_text('[severity]\nTX300 = "info"\n')
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "arm.urdf").write_text(ARM)
    # On disk the xacro file's ratio is 50: only the editor's unsaved text has 0.
    (tmp_path / "urdf" / "arm.urdf.xacro").write_text(ARM_XACRO.replace('value="0"', 'value="50"'))
    return tmp_path


def test_an_editing_session(repository: Path) -> None:
    asyncio.run(asyncio.wait_for(_session(repository), 60))


async def _session(repository: Path) -> None:
    editor = Editor()
    # Started elsewhere than the repository, as editors do: the workspace decides.
    await editor.start_io(sys.executable, "-m", "txtool", "lsp", cwd=str(ROOT))
    server = editor._server
    assert server is not None
    try:
        await _edits(editor, repository)
        await asyncio.wait_for(server.wait(), WAIT)  # it leaves on "exit", by itself
    finally:
        if server.returncode is None:
            server.kill()
        await editor.stop()
    assert server.stderr is not None
    assert (server.returncode, await server.stderr.read()) == (0, b"")


async def _edits(editor: Editor, repository: Path) -> None:
    result = await asyncio.wait_for(editor.initialize_async(lsp.InitializeParams(
        capabilities=lsp.ClientCapabilities(),
        workspace_folders=[lsp.WorkspaceFolder(uri=repository.as_uri(), name="robot")],
    )), WAIT)
    assert result.server_info is not None and result.server_info.name == "txtool"
    assert result.capabilities.hover_provider
    editor.initialized(lsp.InitializedParams())

    uri = (repository / "urdf" / "arm.urdf").as_uri()
    editor.text_document_did_open(lsp.DidOpenTextDocumentParams(
        text_document=lsp.TextDocumentItem(uri=uri, language_id="xml", version=1, text=ARM)))
    found = await editor.diagnostics(uri, 1)
    assert codes(found) == ["TX106", "TX300"]
    zero = next(d for d in found if d.code == "TX106")
    start = REDUCTION.index("<")
    assert zero.range == lsp.Range(start=lsp.Position(line=REDUCTION_LINE, character=start),
                                   end=lsp.Position(line=REDUCTION_LINE,
                                                    character=start + len("<mechanicalReduction>")))
    assert zero.severity == lsp.DiagnosticSeverity.Error and zero.source == "txtool"
    assert zero.code_description is not None
    assert zero.code_description.href.endswith("/docs/rules/TX106.md")
    assert "reduction of actuator 'shoulder_motor'" in zero.message
    unprefixed = next(d for d in found if d.code == "TX300")
    assert unprefixed.severity == lsp.DiagnosticSeverity.Information  # the repository's

    # The quick fix of TX300, applied, removes it (and the refusal it caused).
    actions = await asyncio.wait_for(editor.text_document_code_action_async(lsp.CodeActionParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri), range=unprefixed.range,
        context=lsp.CodeActionContext(diagnostics=[unprefixed],
                                      only=[lsp.CodeActionKind.QuickFix]))), WAIT)
    assert [a.title for a in actions] == ["Fix TX300 unprefixed-interface"]
    fixed = applied(ARM, edits_of(actions[0]))
    assert fixed == ARM.replace(">PositionJointInterface<",
                                ">hardware_interface/PositionJointInterface<")
    editor.text_document_did_change(full_change(uri, 2, fixed))
    assert codes(await editor.diagnostics(uri, 2)) == ["TX106"]

    # The hover on the transmission shows what ros_control reads: it refuses the zero.
    hover = await asyncio.wait_for(editor.text_document_hover_async(lsp.HoverParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri),
        position=lsp.Position(line=REDUCTION_LINE - 1, character=8))), WAIT)
    assert hover is not None and isinstance(hover.contents, lsp.MarkupContent)
    assert "shoulder_trans (line 10): SimpleTransmission" in hover.contents.value
    assert "read by ros_control; not loaded: reduction ratio cannot be zero" in (
        hover.contents.value)

    # Typing the fix clears the diagnostics: "5" before the zero, sent as an editor sends it.
    where = lsp.Position(line=REDUCTION_LINE, character=REDUCTION.index(">0<") + 1)
    editor.text_document_did_change(lsp.DidChangeTextDocumentParams(
        text_document=lsp.VersionedTextDocumentIdentifier(uri=uri, version=3),
        content_changes=[lsp.TextDocumentContentChangePartial(
            range=lsp.Range(start=where, end=where), text="5")]))
    assert await editor.diagnostics(uri, 3) == []
    hover = await asyncio.wait_for(editor.text_document_hover_async(lsp.HoverParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri),
        position=lsp.Position(line=10, character=3))), WAIT)
    assert hover is not None and "shoulder_motor" in hover.contents.value  # type: ignore[union-attr]

    # A suppression comment is honoured (and used: no TX003).
    silenced = fixed.replace(REDUCTION, "      <!-- txtool: disable-next-line TX106 -->\n"
                             + REDUCTION)
    editor.text_document_did_change(full_change(uri, 4, silenced))
    assert await editor.diagnostics(uri, 4) == []
    # Saving checks again; closing clears what was published.
    (repository / "urdf" / "arm.urdf").write_text(silenced)
    editor.text_document_did_save(lsp.DidSaveTextDocumentParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri)))
    assert await editor.diagnostics(uri, 4) == []
    editor.text_document_did_close(lsp.DidCloseTextDocumentParams(
        text_document=lsp.TextDocumentIdentifier(uri=uri)))
    assert await editor.diagnostics(uri, None) == []

    # An unsaved xacro buffer is expanded as typed, not as saved (ratio 50 on disk).
    xacro_uri = (repository / "urdf" / "arm.urdf.xacro").as_uri()
    editor.text_document_did_open(lsp.DidOpenTextDocumentParams(text_document=lsp.TextDocumentItem(
        uri=xacro_uri, language_id="xml", version=1, text=ARM_XACRO)))
    assert codes(await editor.diagnostics(xacro_uri, 1)) == ["TX106"]

    await asyncio.wait_for(editor.shutdown_async(None), WAIT)
    editor.exit(None)
