"""``txtool lsp``'s language server (pygls): diagnostics, quick fixes and hover for robot files.

Each opened, changed or saved buffer is checked as ``txtool validate`` checks the file
(:mod:`txtool.commands.lsp_document`) and its problems are published; for a robot or controller
file, so are the controller findings of its package family in the controller files and the
robots they are judged against (:mod:`txtool.commands.lsp_controllers`); a fixable problem gets
``txtool migrate``'s fix as a quick fix, and the document a "fix all"; a hover on a
``<transmission>`` shows what each loader reads of it (:mod:`txtool.commands.lsp_hover`).

Only documents the client opened are served: the server never reads a file for a document
(pygls would read one it was asked about from disk, special files included); the controller
files of a family are its one exception, published from their regular files on disk. Over TCP,
only files inside the workspace folders the client declared. Changes are checked once typing
pauses (:data:`PAUSE`), the newest version only; every edit names the version it applies to.
Only this module and :mod:`txtool.commands.lsp_transport` import pygls, and only
``txtool lsp`` imports them.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import threading
from collections.abc import Callable, Sequence
from urllib.parse import unquote

from lsprotocol import types as lsp
from pygls.exceptions import FeatureNotificationError
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path
from pygls.workspace import TextDocument
from pygls.workspace.position_codec import ServerTextPosition, ServerTextRange

from txtool import __version__
from txtool.commands.lsp_document import (
    Failure,
    Options,
    end_of,
    fixable_rules,
    fixed_text,
    is_robot_file,
    line_edits,
    problems_of,
    root_of,
    settings_for,
)
from txtool.lint.problem import Note, Problem
from txtool.reporters.sarif import RULE_DOCS

SOURCE = "txtool"
SEVERITY = {"error": lsp.DiagnosticSeverity.Error, "warning": lsp.DiagnosticSeverity.Warning,
            "info": lsp.DiagnosticSeverity.Information}
FIX_ALL = lsp.CodeActionKind.SourceFixAll + ".txtool"
PAUSE = 0.3  # seconds without a change before a changed buffer is checked


class TxtoolServer(LanguageServer):
    """The server and the options ``txtool lsp`` was started with."""

    def __init__(self, options: Options) -> None:
        # One thread reads standard input (no handler runs in a thread of its own).
        super().__init__("txtool", __version__, max_workers=1,
                         text_document_sync_kind=lsp.TextDocumentSyncKind.Incremental)
        self.options = options
        self.confined = False  # over TCP: only documents inside the declared folders
        self.pending: dict[str, asyncio.TimerHandle] = {}  # checks waiting for a pause
        # What was last published of each URI: its own findings (with the version checked),
        # and, by path, the controller findings (TX5xx) of the family it was found in.
        self.own: dict[str, tuple[int | None, list[lsp.Diagnostic]]] = {}
        self.controller_part: dict[str, list[Problem]] = {}

    def workspace_paths(self) -> list[str]:
        """The folders the editor opened (each like the folder ``txtool validate`` runs in)."""
        folders = [to_fs_path(f.uri) for f in self.workspace.folders.values()]
        root = self.workspace.root_path
        return [path for path in [*folders, root] if path]

    def opened(self, uri: str) -> TextDocument | None:
        """The buffer the client opened at ``uri``, if it is one this server serves."""
        document = self.workspace.text_documents.get(unquote(uri))
        if document is None or not self.confined:
            return document
        path = document.path
        inside = path is not None and any(
            os.path.realpath(path).startswith(os.path.join(os.path.realpath(top), ""))
            for top in self.workspace_paths())
        return document if inside else None

    def serves(self, path: str) -> bool:
        """Whether findings may be published for the file at ``path`` (over TCP: only inside
        the declared folders)."""
        return not self.confined or any(
            os.path.realpath(path).startswith(os.path.join(os.path.realpath(top), ""))
            for top in self.workspace_paths())

    def buffers(self) -> dict[str, str]:
        """The text of each file the client has open (and this server serves), by path."""
        opened = (self.opened(uri) for uri in list(self.workspace.text_documents))
        return {d.path: d.source for d in opened
                if d is not None and d.path and d.uri.startswith("file:")}

    def start_io(self, stdin, stdout) -> None:  # type: ignore[no-untyped-def, override]
        """Serve standard input and output with the bounded loop."""
        from pygls.io_ import StdoutWriter

        from txtool.commands.lsp_transport import StdinReader, serve

        self._stop_event = threading.Event()
        self.protocol.set_writer(StdoutWriter(stdout))
        try:
            asyncio.run(serve(StdinReader(stdin, self.thread_pool), self.protocol,
                              self._stop_event, self.report_server_error))
        except BrokenPipeError:  # the editor is gone
            pass
        finally:
            self.shutdown()

    def start_tcp(self, host: str, port: int, token: str,  # type: ignore[override]
                  listening: Callable[[], None] = lambda: None) -> None:
        """Serve one client at a time on ``host:port``: the first that sends ``initialize``
        with ``token``; then only documents inside the folders it declares. ``listening`` is
        called once the address is bound."""
        from txtool.commands.lsp_transport import (
            MAX_LINE,
            StreamReader,
            authentic,
            first_message,
            frame,
            serve,
        )

        self._stop_event = stop = threading.Event()
        self.confined = True
        taken = False

        async def connection(reader: asyncio.StreamReader,
                             writer: asyncio.StreamWriter) -> None:
            nonlocal taken
            try:
                body = await first_message(reader)
            except asyncio.CancelledError:  # the server ends while this one says nothing
                writer.close()
                return
            if taken or body is None or not authentic(body, token):
                writer.close()
                return
            taken = True
            self.protocol.set_writer(writer)  # type: ignore[arg-type]
            await serve(StreamReader(reader, replay=frame(body)), self.protocol, stop,
                        self.report_server_error)
            self.shutdown()

        async def listen() -> None:
            self._server = await asyncio.start_server(connection, host, port, limit=MAX_LINE)
            listening()
            async with self._server:
                await self._server.serve_forever()

        with contextlib.suppress(asyncio.CancelledError):  # shut down
            asyncio.run(listen())


def build(options: Options) -> TxtoolServer:
    """A server with its handlers."""
    server = TxtoolServer(options)

    @server.feature(lsp.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: TxtoolServer, params: lsp.DidOpenTextDocumentParams) -> None:
        publish(ls, params.text_document.uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: TxtoolServer, params: lsp.DidChangeTextDocumentParams) -> None:
        after_a_pause(ls, params.text_document.uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls: TxtoolServer, params: lsp.DidSaveTextDocumentParams) -> None:
        publish(ls, params.text_document.uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: TxtoolServer, params: lsp.DidCloseTextDocumentParams) -> None:
        uri = params.text_document.uri
        waiting = ls.pending.pop(uri, None)
        if waiting is not None:
            waiting.cancel()
        ls.own.pop(uri, None)
        path = to_fs_path(uri)
        if path is not None:
            ls.controller_part.pop(path, None)
        ls.text_document_publish_diagnostics(
            lsp.PublishDiagnosticsParams(uri=uri, diagnostics=[]))

    @server.feature(lsp.TEXT_DOCUMENT_CODE_ACTION, lsp.CodeActionOptions(
        code_action_kinds=[lsp.CodeActionKind.QuickFix, FIX_ALL]))
    def code_action(ls: TxtoolServer, params: lsp.CodeActionParams) -> list[lsp.CodeAction]:
        document = ls.opened(params.text_document.uri)
        if document is None:  # never opened: nothing is read for it
            return []
        return code_actions(document, params.context, ls.workspace_paths(), ls.options)

    @server.feature(lsp.TEXT_DOCUMENT_HOVER)
    def hover(ls: TxtoolServer, params: lsp.HoverParams) -> lsp.Hover | None:
        document = ls.opened(params.text_document.uri)
        if document is None:
            return None
        return hover_of(document, params.position, ls.workspace_paths(), ls.options)

    return server


def after_a_pause(ls: TxtoolServer, uri: str) -> None:
    """Check ``uri`` once no change has come for :data:`PAUSE` seconds: a burst of keystrokes
    is one check, of the newest version (each version checked in turn fell seconds behind)."""
    waiting = ls.pending.pop(uri, None)
    if waiting is not None:
        waiting.cancel()

    def check() -> None:
        ls.pending.pop(uri, None)
        try:
            publish(ls, uri)
        except Exception as exc:  # as a handler's error: reported, the server goes on
            ls.report_server_error(exc, FeatureNotificationError)

    ls.pending[uri] = asyncio.get_running_loop().call_later(PAUSE, check)


def publish(ls: TxtoolServer, uri: str) -> None:
    """Check the buffer at ``uri`` and publish its findings; for a robot or controller file,
    also check its family's controller files and publish what changed in each of them."""
    document = ls.opened(uri)
    if document is None:  # never opened (or outside the folders): nothing is read for it
        return
    ls.own[uri] = (document.version, diagnostics_of(document, ls.workspace_paths(), ls.options))
    changed = _controller_findings(ls, document)
    _publish_own(ls, document)
    for path in changed:
        _publish_paired(ls, path)


def _controller_findings(ls: TxtoolServer, document: TextDocument) -> list[str]:
    """Check the family of the document's file (:mod:`txtool.commands.lsp_controllers`) and
    keep its findings; the other paths whose findings changed (or were cleared)."""
    from txtool.commands.lsp_controllers import family_findings, inside, is_controller_candidate

    path = document.path
    if not document.uri.startswith("file:") or not path or not (
            is_controller_candidate(path) or _checked_path(document)):
        return []
    family = family_findings(path, ls.buffers(), root_of(path, ls.workspace_paths()),
                             ls.options, ls.serves)
    before = ls.controller_part
    gone = [p for p in before if inside(p, family.folders) and p not in family.findings]
    changed = [p for p in gone if before.pop(p)]
    for each, found in family.findings.items():
        if each not in before or _shown(before[each]) != _shown(found):
            changed.append(each)
        before[each] = found
    return [p for p in dict.fromkeys(changed) if p != path and ls.serves(p)]


def _shown(problems: list[Problem]) -> list[tuple]:
    return [(p.line, p.column, p.code, p.severity, p.message, p.related) for p in problems]


def _publish_own(ls: TxtoolServer, document: TextDocument) -> None:
    version, own = ls.own.get(document.uri, (document.version, []))
    paired = ls.controller_part.get(document.path or "", [])
    ls.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(
        uri=document.uri, version=version,
        diagnostics=[*own, *(diagnostic(document, p) for p in paired)]))


def _publish_paired(ls: TxtoolServer, path: str) -> None:
    """Publish the file at ``path`` again with its family's new controller findings: an
    opened one with its own findings of its last check (unless a newer check is waiting), one
    not opened with those findings alone, placed in its text on disk."""
    uri = from_fs_path(path) or path
    document = ls.opened(uri)
    if document is not None:
        if uri not in ls.pending and ls.own.get(uri, (document.version,))[0] == document.version:
            _publish_own(ls, document)
        return
    from txtool.io.xmlio import InputError, read_regular

    found = ls.controller_part.get(path, [])
    try:
        text = read_regular(path).decode("utf-8", errors="replace") if found else ""
    except InputError:
        return
    on_disk = TextDocument(uri, text)
    ls.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(
        uri=uri, diagnostics=[diagnostic(on_disk, p) for p in found]))


def _checked_path(document: TextDocument) -> str | None:
    """The file the buffer is of, when it is a robot file on disk's side (``file:`` URI)."""
    path = document.path
    if not document.uri.startswith("file:") or not path:
        return None
    return path if is_robot_file(path, document.source) else None


def diagnostics_of(document: TextDocument, workspace: Sequence[str],
                   options: Options) -> list[lsp.Diagnostic]:
    """The buffer's problems as diagnostics (none for a file txtool does not check)."""
    path = _checked_path(document)
    if path is None:
        return []
    found = problems_of(path, document.source, root_of(path, workspace), options)
    if isinstance(found, Failure):
        return [_failure(document, found)]
    return [diagnostic(document, problem) for problem in found]


def diagnostic(document: TextDocument, problem: Problem) -> lsp.Diagnostic:
    start = ServerTextPosition(problem.line - 1, problem.column - 1)
    end = ServerTextPosition((problem.end_line or problem.line) - 1,
                             (problem.end_column or problem.column + 1) - 1)
    return lsp.Diagnostic(
        range=document.range_to_client_units(ServerTextRange(start, end)),
        message=f"{problem.message} ({problem.name})" if problem.name else problem.message,
        severity=SEVERITY[problem.severity],
        code=problem.code,
        code_description=lsp.CodeDescription(href=RULE_DOCS.format(code=problem.code)),
        source=SOURCE,
        data={"fixable": bool(problem.fixable)},
        related_information=[_related(note) for note in problem.related] or None,
    )


def _related(note: Note) -> lsp.DiagnosticRelatedInformation:
    """A place of the finding's xacro call chain ("in expansion of macro ..."), in any file."""
    at = lsp.Position(line=note.line - 1, character=note.column - 1)
    return lsp.DiagnosticRelatedInformation(
        location=lsp.Location(uri=from_fs_path(os.path.abspath(note.path)) or note.path,
                              range=lsp.Range(start=at, end=at)),
        message=note.message)


def _failure(document: TextDocument, failure: Failure) -> lsp.Diagnostic:
    line = min(failure.line, max(len(document.lines) - 1, 0))
    start, end = ServerTextPosition(line, 0), ServerTextPosition(line + 1, 0)
    return lsp.Diagnostic(range=document.range_to_client_units(ServerTextRange(start, end)),
                          message=failure.message, severity=lsp.DiagnosticSeverity.Error,
                          source=SOURCE)


def code_actions(document: TextDocument, context: lsp.CodeActionContext,
                 workspace: Sequence[str], options: Options) -> list[lsp.CodeAction]:
    """A quick fix per fixable code among the diagnostics asked about, each applying that
    rule's fix to the buffer; and, when anything is fixable, the fix of every fixable rule."""
    path = _checked_path(document)
    if path is None:
        return []
    root = root_of(path, workspace)
    only = context.only
    actions = []
    ours = [d for d in context.diagnostics
            if d.source == SOURCE and isinstance(d.data, dict) and d.data.get("fixable")]
    if only is None or any(lsp.CodeActionKind.QuickFix.startswith(kind) for kind in only):
        for code in sorted({str(d.code) for d in ours}):
            rules = fixable_rules(path, root, options, [code])
            fixed, counts = fixed_text(path, document.source, rules,
                                       settings_for(path, root, options))
            if not counts:
                continue
            many = f" ({counts[code]} in this file)" if counts.get(code, 0) > 1 else ""
            actions.append(_action(document, f"Fix {code} {rules[0].name}{many}",
                                   lsp.CodeActionKind.QuickFix, fixed,
                                   [d for d in ours if d.code == code]))
    if only is None or any(FIX_ALL.startswith(kind) for kind in only):
        # Only the rules of the findings the buffer shows: migrate would also fix
        # transmissions no reader of the file reads, which lint only notes (TX305).
        found = problems_of(path, document.source, root, options)
        codes = sorted({p.code for p in found if p.fixable}) if isinstance(found, list) else []
        rules = fixable_rules(path, root, options, codes) if codes else []
        fixed, counts = fixed_text(path, document.source, rules,
                                   settings_for(path, root, options)) if rules else ("", {})
        if counts:
            what = ", ".join(f"{code} x{n}" for code, n in sorted(counts.items()))
            actions.append(_action(document, f"Fix all txtool fixable problems ({what})",
                                   FIX_ALL, fixed, []))
    return actions


def _action(document: TextDocument, title: str, kind: str, fixed: str,
            diagnostics: list[lsp.Diagnostic]) -> lsp.CodeAction:
    return lsp.CodeAction(
        title=title, kind=kind, diagnostics=diagnostics or None,
        is_preferred=kind == lsp.CodeActionKind.QuickFix,
        # The version the edits were made for: an editor whose buffer moved on refuses them.
        edit=lsp.WorkspaceEdit(document_changes=[lsp.TextDocumentEdit(
            text_document=lsp.OptionalVersionedTextDocumentIdentifier(
                uri=document.uri, version=document.version),
            edits=list(text_edits(document, fixed)))]),
    )


def text_edits(document: TextDocument, fixed: str) -> list[lsp.TextEdit]:
    """Whole-line edits turning the buffer into ``fixed``, in the client's units."""
    before = document.source
    edits = []
    for edit in line_edits(before, fixed):
        start = ServerTextPosition(*end_of(before, edit.start))
        end = ServerTextPosition(*end_of(before, edit.end))
        edits.append(lsp.TextEdit(range=document.range_to_client_units(
            ServerTextRange(start, end)), new_text=edit.text))
    return edits


def hover_of(document: TextDocument, position: lsp.Position, workspace: Sequence[str],
             options: Options) -> lsp.Hover | None:
    from txtool.commands.lsp_hover import hover_markdown

    path = _checked_path(document)
    if path is None:
        return None
    here = document.position_from_client_units(position)
    shown = hover_markdown(path, document.source, here.line, here.character, list(workspace),
                           options)
    if shown is None:
        return None
    return lsp.Hover(contents=lsp.MarkupContent(kind=lsp.MarkupKind.Markdown, value=shown))
