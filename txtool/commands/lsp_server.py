"""``txtool lsp``'s language server (pygls): diagnostics, quick fixes and hover for robot files.

Each opened, changed or saved buffer is checked as ``txtool validate`` checks the file
(:mod:`txtool.commands.lsp_document`) and its problems are published; a fixable problem gets
``txtool migrate``'s fix as a quick fix, and the document a "fix all"; a hover on a
``<transmission>`` shows what each loader reads of it (:mod:`txtool.commands.lsp_hover`).
Only this module imports pygls, and only ``txtool lsp`` imports it.
"""

from __future__ import annotations

import os
from collections.abc import Sequence

from lsprotocol import types as lsp
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
)
from txtool.lint.problem import Note, Problem
from txtool.reporters.sarif import RULE_DOCS

SOURCE = "txtool"
SEVERITY = {"error": lsp.DiagnosticSeverity.Error, "warning": lsp.DiagnosticSeverity.Warning,
            "info": lsp.DiagnosticSeverity.Information}
FIX_ALL = lsp.CodeActionKind.SourceFixAll + ".txtool"


class TxtoolServer(LanguageServer):
    """The server and the options ``txtool lsp`` was started with."""

    def __init__(self, options: Options) -> None:
        # One thread reads standard input (no handler runs in a thread of its own).
        super().__init__("txtool", __version__, max_workers=1,
                         text_document_sync_kind=lsp.TextDocumentSyncKind.Incremental)
        self.options = options

    def workspace_paths(self) -> list[str]:
        """The folders the editor opened (each like the folder ``txtool validate`` runs in)."""
        folders = [to_fs_path(f.uri) for f in self.workspace.folders.values()]
        root = self.workspace.root_path
        return [path for path in [*folders, root] if path]


def build(options: Options) -> TxtoolServer:
    """A server with its handlers."""
    server = TxtoolServer(options)

    @server.feature(lsp.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: TxtoolServer, params: lsp.DidOpenTextDocumentParams) -> None:
        publish(ls, params.text_document.uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: TxtoolServer, params: lsp.DidChangeTextDocumentParams) -> None:
        publish(ls, params.text_document.uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls: TxtoolServer, params: lsp.DidSaveTextDocumentParams) -> None:
        publish(ls, params.text_document.uri)

    @server.feature(lsp.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: TxtoolServer, params: lsp.DidCloseTextDocumentParams) -> None:
        ls.text_document_publish_diagnostics(
            lsp.PublishDiagnosticsParams(uri=params.text_document.uri, diagnostics=[]))

    @server.feature(lsp.TEXT_DOCUMENT_CODE_ACTION, lsp.CodeActionOptions(
        code_action_kinds=[lsp.CodeActionKind.QuickFix, FIX_ALL]))
    def code_action(ls: TxtoolServer, params: lsp.CodeActionParams) -> list[lsp.CodeAction]:
        document = ls.workspace.get_text_document(params.text_document.uri)
        return code_actions(document, params.context, ls.workspace_paths(), ls.options)

    @server.feature(lsp.TEXT_DOCUMENT_HOVER)
    def hover(ls: TxtoolServer, params: lsp.HoverParams) -> lsp.Hover | None:
        document = ls.workspace.get_text_document(params.text_document.uri)
        return hover_of(document, params.position, ls.workspace_paths(), ls.options)

    return server


def publish(ls: TxtoolServer, uri: str) -> None:
    document = ls.workspace.get_text_document(uri)
    diagnostics = diagnostics_of(document, ls.workspace_paths(), ls.options)
    ls.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(
        uri=uri, diagnostics=diagnostics, version=document.version))


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
            fixed, counts = fixed_text(path, document.source, rules)
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
        fixed, counts = fixed_text(path, document.source, rules) if rules else ("", {})
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
        edit=lsp.WorkspaceEdit(changes={document.uri: text_edits(document, fixed)}),
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
