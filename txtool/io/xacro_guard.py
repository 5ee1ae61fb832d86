"""Hooks that make upstream xacro safe for a file nobody vouches for, without forking it.

Installed for one expansion (:meth:`XacroGuard.installed`), they replace:

- ``xacro.safe_eval`` (every ``${...}``, and the ``!degrees``-style YAML units) and
  ``substitution_args._eval`` (``$(eval ...)``) by :mod:`txtool.io.xacro_eval`, charged to the
  file's :class:`~txtool.io.xacro_eval.Meter`;
- xacro's global symbols by :func:`txtool.io.xacro_eval.make_globals`, with
  ``xacro.tokenize`` splitting on the characters of its separator as text (upstream builds a
  regular expression of it);
- ``$(env NAME)``: the value only for a name the command line gives (``--xacro-env NAME``),
  else a refusal; ``$(optenv NAME DEFAULT)``: its default then. No file of the repository
  names a variable, so no name is judged by how it looks;
- ``$(find PKG)``: as before; the package found becomes a root files may be read from when it
  lies inside the repository (links resolved) or was given outside it (``--pkg-dir``,
  ``--pkg-path`` on the command line, the ROS environment), else a refusal;
- ``xacro.load_yaml`` and ``<xacro:include>`` (globs too): only regular files inside the roots
  (the repository of the top file, or its workspace's ``src``, its package, packages
  ``$(find)`` found), symbolic links resolved first, never below a hidden folder (``.git``
  holds a checkout's credentials) nor a hidden file; a glob whose folder is outside is refused
  before it is listed, so no outside name is printed; a YAML document expanding to more than
  :data:`MAX_YAML_NODES` nodes (an alias bomb) is refused, and a file that is no YAML is
  reported by line and column, never quoted;
- minidom's node creation and moves: each cloned node counts against :data:`MAX_NODES`, each
  child list an insertion or removal walks is charged to the file's meter (a macro fan-out
  grows one parent's children, and each move scans them).
"""

from __future__ import annotations

import contextlib
import os
import re
import xml.dom.minidom as minidom
from collections.abc import Iterator, Mapping
from typing import Any
from xml.parsers.expat import ExpatError
from xml.parsers.expat import errors as expat_errors

from txtool.io.install_layout import installed_source
from txtool.io.packages import enclosing_manifest, is_within, locate_package, workspace_roots
from txtool.io.xacro_eval import (
    EvalRefused,
    Meter,
    SafeFunction,
    WorkLimit,
    cost,
    evaluate,
    make_globals,
    metered,
    plain_attribute,
)
from txtool.io.xmlio import InputError, TooLarge, XacroOptions, read_regular

_EXPAT_NO_MEMORY = expat_errors.codes[expat_errors.XML_ERROR_NO_MEMORY]

MAX_YAML_NODES = 1_000_000
# XML nodes created by cloning (macro bodies, blocks) in one expansion: minidom takes some
# microseconds to clone one and as many to evaluate it, so this many cost about half a second.
MAX_NODES = 100_000
CLONE_STEPS = 10  # steps of work a cloned node is charged (its evaluation follows)
YAML_STEPS_PER_BYTE = 64  # PyYAML's pure-Python loader: some 6 microseconds a byte
LIST_SCAN_PER_STEP = 8  # items of a child list that minidom scans in C, per step of work
# xacro's lexer copies the rest of a text after each token it takes: bytes copied per step.
LEXER_COPY_PER_STEP = 1024
# xacro's own work for an element (its attributes, its dispatch) and for a macro call (a new
# scope, its parameters, its body evaluated and moved): tens of microseconds.
ELEMENT_STEPS = 20
MACRO_CALL_STEPS = 300
_MAGIC = re.compile(r"[*?[]")


class Refusal(Exception):
    """What the guard refused: a one-line reason, and a text to find the line by."""

    def __init__(self, reason: str, needle: str | None = None) -> None:
        super().__init__(reason)
        self.reason = reason
        self.needle = needle


class NodeLimit(Exception):
    """The expansion created more XML nodes than the sandbox allows."""


class XacroGuard:
    """The hooks of one expansion of ``path``."""

    def __init__(self, path: str, options: XacroOptions, environment: Mapping[str, str]) -> None:
        self.path = os.path.abspath(path)
        self.options = options
        self.environment = {k: v for k, v in environment.items() if k in options.env}
        self.roots = [os.path.realpath(root) for root in _roots(self.path)]
        self.meter = Meter()
        self.nodes = MAX_NODES
        self.yaml: dict[str, Any] = {}  # what load_yaml read, by file: read and paid once

    # -- files -------------------------------------------------------------------------------
    def check_readable(self, path: str, what: str) -> None:
        """Refuse a file outside the roots (after resolving symbolic links), or below a hidden
        folder of its root; the message names ``path`` as the file wrote it, never where a
        link leads."""
        real = os.path.realpath(path)
        root = next((r for r in self.roots if is_within(real, r)), None)
        if root is None:
            raise Refusal(f"{what} of '{path}' is outside the repository and the packages "
                          "found (txtool reads no other file for an untrusted xacro; "
                          "see --trust-xacro)", needle=os.path.basename(path))
        if any(part.startswith(".") for part in os.path.relpath(real, root).split(os.sep)):
            raise Refusal(f"{what} of '{path}' is or leads to a hidden file or folder (such "
                          "as .git, which holds a checkout's credentials; txtool reads none for "
                          "an untrusted xacro; see --trust-xacro)", needle=os.path.basename(path))

    def add_package_root(self, folder: str) -> None:
        if os.path.isfile(os.path.join(folder, "package.xml")):
            self.roots.append(os.path.realpath(folder))

    def glob(self, pattern: str) -> list[str]:
        """``glob.glob`` for an include: the folder before the first wildcard must be readable
        and the pattern must not climb out of it (``..``), so the names it lists are inside."""
        import glob

        parts = pattern.split(os.sep)
        first = next(i for i, part in enumerate(parts) if _MAGIC.search(part))
        folder = os.sep.join(parts[:first]) or os.sep
        real = os.path.realpath(folder)
        root = next((r for r in self.roots if is_within(real, r)), None)
        below = os.path.relpath(real, root).split(os.sep) if root else []
        hidden = [p for p in below + parts[first:] if p.startswith(".") and p != "."]
        if root is None or hidden:  # ('..' after a wildcard climbs out of the folder checked)
            raise Refusal(f"include of '{pattern}' is outside the repository and the packages "
                          "found (txtool lists no other folder for an untrusted xacro; see "
                          "--trust-xacro)", needle=os.path.basename(pattern))
        return glob.glob(pattern)

    # -- substitution args -------------------------------------------------------------------
    def env(self, name: str) -> str:
        if name not in self.options.env:
            raise Refusal(f"$(env {name}) is not allowed (only names given with --xacro-env "
                          "are read; see --trust-xacro)", needle=f"$(env {name}")
        try:
            return self.environment[name]
        except KeyError:
            from xacro.substitution_args import SubstitutionException

            raise SubstitutionException(f"environment variable '{name}' is not set") from None

    def optenv(self, name: str, default: str = "") -> str:
        return self.environment.get(name, default)

    def find(self, package: str) -> str:
        folder, given = locate_package(
            package, near=self.path, pkg_paths=self.options.pkg_paths,
            pkg_dirs=self.options.pkg_dirs, confine=self.options.readable)
        if given:
            self.add_package_root(folder)
        elif not any(is_within(os.path.realpath(folder), root) for root in self.roots):
            raise Refusal(f"$(find {package}) leads outside the repository (through a link or "
                          "a folder of the configuration; only --pkg-dir or --pkg-path on the "
                          "command line, or the ROS environment, name folders outside it)",
                          needle=f"$(find {package}")
        return folder

    def substitution_eval(self, text: str, context: dict[str, Any]) -> str:
        """``$(eval ...)``: arguments by name (typed as xacro does), arg(), the math names."""
        from xacro.substitution_args import _eval_arg, convert_value

        args = context.setdefault("arg", {})
        names: dict[str, Any] = dict(make_globals({})["math"])
        names.update(true=True, false=False)
        functions = {
            "arg": lambda name: convert_value(_eval_arg(name, args=args), "auto"),
            "dirname": lambda: os.path.dirname(self.path),
            "env": self.env, "optenv": self.optenv, "find": self.find,
        }
        names.update({k: SafeFunction(k, f) for k, f in functions.items()})
        try:
            return str(evaluate(text, _SubstitutionNames(args, names), self.attribute))
        except EvalRefused as exc:
            raise _refusal(str(exc), "$(eval " + text.strip()) from None

    # -- expressions -------------------------------------------------------------------------
    def safe_eval(self, expression: str, symbols: Any, _locals: Any = None) -> Any:
        try:
            value = evaluate(expression, symbols, self.attribute)
        except EvalRefused as exc:
            raise _refusal(str(exc), expression.strip()) from None
        self.meter.charge(cost(value))  # xacro writes it out as text
        return value

    @staticmethod
    def attribute(value: Any, name: str) -> Any:
        import xacro

        if isinstance(value, xacro.YamlDictWrapper):
            if name in ("keys", "values", "items", "get"):
                return plain_attribute(dict(value), name)
            try:
                return value[name]
            except AttributeError as exc:
                raise AttributeError(str(exc)) from None
        if isinstance(value, xacro.NameSpace):
            try:
                return value[name]
            except KeyError:
                raise NameError(f"name '{name}' is not defined") from None
        return plain_attribute(value, name)

    def load_yaml(self, filename: str) -> Any:
        """xacro's ``load_yaml``, reading only a regular file inside the roots."""
        import xacro

        path = xacro.abs_filename_spec(filename)
        self.check_readable(path, "load_yaml")
        if not os.path.exists(path):  # the checkout of a package its CMake lays out anew
            path = installed_source(path) or path
            self.check_readable(path, "load_yaml")
        key = os.path.realpath(path)
        if key not in self.yaml:  # no expression can change a value it loaded: shared
            self.yaml[key] = self._read_yaml(filename, path)
        xacro.all_includes.append(path)
        return xacro.YamlListWrapper.wrap(self.yaml[key])

    def _read_yaml(self, filename: str, path: str) -> Any:
        import xacro
        import yaml

        try:
            data = read_regular(path)
        except TooLarge as exc:
            raise Refusal(str(exc)) from None
        except InputError as exc:
            raise xacro.XacroException(str(exc)) from None
        self.meter.charge(1 + len(data) * YAML_STEPS_PER_BYTE)
        loader = _unit_loader(xacro, yaml)
        xacro.filestack.append(path)
        try:
            node = yaml.compose(data, Loader=loader)
            if _yaml_nodes(node) > MAX_YAML_NODES:
                raise Refusal(f"{filename}: a YAML document of more than {MAX_YAML_NODES} "
                              "nodes once its aliases are expanded (a safety limit)")
            value = loader(data).construct_document(node) if node is not None else None
        except yaml.YAMLError as exc:
            # PyYAML's message quotes the line and the token it stopped at: the file may be no
            # YAML at all (a key, a token), so only where it stopped is said.
            mark = getattr(exc, "problem_mark", None)
            where = f" (line {mark.line + 1}, column {mark.column + 1})" if mark else ""
            raise xacro.XacroException(f"load_yaml('{filename}'): not a YAML document txtool "
                                       f"reads{where}; its text is not shown") from None
        finally:
            xacro.filestack.pop()
        return value

    def globals(self) -> dict[str, Any]:
        import xacro

        upstream = dict(xacro._global_symbols["xacro"])
        upstream["load_yaml"] = self.load_yaml
        upstream["tokenize"] = tokenize
        return make_globals(upstream)

    @contextlib.contextmanager
    def installed(self) -> Iterator[None]:
        import xacro
        from xacro import substitution_args

        saved = (xacro.safe_eval, xacro._global_symbols, substitution_args._eval,
                 substitution_args._eval_env, substitution_args._eval_optenv,
                 substitution_args._eval_find, xacro.glob, xacro.eval_text,
                 xacro.handle_macro_call)
        xacro.eval_text = self._priced_eval_text(xacro.eval_text)
        xacro.handle_macro_call = self._priced_macro_call(xacro.handle_macro_call)
        xacro.safe_eval = self.safe_eval
        xacro._global_symbols = self.globals()
        substitution_args._eval = self.substitution_eval
        substitution_args._eval_env = self.env
        substitution_args._eval_optenv = self.optenv
        substitution_args._eval_find = self.find
        xacro.glob = _Glob(self.glob)
        try:
            with metered(self.meter), self._tree_counted():
                yield
        finally:
            (xacro.safe_eval, xacro._global_symbols, substitution_args._eval,
             substitution_args._eval_env, substitution_args._eval_optenv,
             substitution_args._eval_find, xacro.glob, xacro.eval_text,
             xacro.handle_macro_call) = saved

    def _priced_macro_call(self, handle_macro_call: Any) -> Any:
        """xacro's ``handle_macro_call`` (asked for every element eval_all does not know
        otherwise), charged for the element, and for the call when it is one."""
        def priced(node: Any, macros: Any, symbols: Any) -> Any:
            tag = getattr(node, "tagName", "")
            self.meter.charge(MACRO_CALL_STEPS if tag.startswith("xacro:") else ELEMENT_STEPS)
            return handle_macro_call(node, macros, symbols)
        return priced

    def _priced_eval_text(self, eval_text: Any) -> Any:
        """xacro's ``eval_text``, charged before it lexes: its lexer copies what is left of
        the text after each token, so a text of many ``$`` tokens (a block inserted again
        re-reads what its expressions wrote) costs its length times its tokens."""
        def priced(text: Any, symbols: Any) -> Any:
            if isinstance(text, str):
                tokens = 2 * text.count("$") + 1
                # a text without '$' is one token, matched by a regular expression in C
                self.meter.charge(1 + tokens * len(text) // 2 // LEXER_COPY_PER_STEP)
            return eval_text(text, symbols)
        return priced

    @contextlib.contextmanager
    def _tree_counted(self) -> Iterator[None]:
        """minidom's cloning counted against :data:`MAX_NODES`, and its child-list walks
        (``insertBefore`` finds its reference child and the moved one's old place in lists)
        charged to the meter, for the time of the expansion."""
        node = minidom.Node
        saved = (minidom._clone_node, node.insertBefore, node.removeChild,  # type: ignore[attr-defined]
                 node.appendChild)
        clone, insert, remove, append = saved

        def counted_clone(original: Any, deep: bool, owner: Any) -> Any:
            self.nodes -= 1
            if self.nodes < 0:
                raise NodeLimit
            self.meter.charge(CLONE_STEPS)
            return clone(original, deep, owner)

        def scans(*lists: Any) -> int:  # list.index and list.remove: C loops, cheap steps
            return 1 + sum(len(nodes) for nodes in lists) // LIST_SCAN_PER_STEP

        def old_children(child: Any) -> Any:
            old = getattr(child, "parentNode", None)
            return old.childNodes if old is not None else ()

        def counted_insert(parent: Any, child: Any, reference: Any) -> Any:
            self.meter.charge(scans(parent.childNodes, old_children(child)))
            return insert(parent, child, reference)

        def counted_remove(parent: Any, child: Any) -> Any:
            self.meter.charge(scans(parent.childNodes))
            return remove(parent, child)

        def counted_append(parent: Any, child: Any) -> Any:  # appends: only the move scans
            self.meter.charge(scans(old_children(child)))
            return append(parent, child)

        minidom._clone_node = counted_clone  # type: ignore[attr-defined]
        node.insertBefore, node.removeChild = counted_insert, counted_remove  # type: ignore[method-assign]
        node.appendChild = counted_append  # type: ignore[method-assign]
        try:
            yield
        finally:
            minidom._clone_node = saved[0]  # type: ignore[attr-defined]
            node.insertBefore, node.removeChild, node.appendChild = saved[1:]  # type: ignore[method-assign]

    def reraise_refusal(self, cause: BaseException) -> None:
        """Let a refusal through xacro's error handling unchanged, as a :class:`Refusal`."""
        if isinstance(cause, Refusal | NodeLimit | WorkLimit | MemoryError | RecursionError):
            raise cause
        if isinstance(cause, ExpatError) and cause.code == _EXPAT_NO_MEMORY:
            raise MemoryError  # expat says so as a syntax error: the memory limit, not the file
        if isinstance(cause, EvalRefused):
            raise _refusal(str(cause), None) from None


class _Glob:
    """What xacro's ``glob`` module is, for an untrusted expansion: ``glob.glob`` checked."""

    def __init__(self, function: Any) -> None:
        self.glob = function


def tokenize(text: str, sep: str = ",; ", skip_empty: bool = True) -> list[str]:
    """``xacro.tokenize``: ``text`` split at any character of ``sep``. Upstream puts ``sep``
    into a regular expression's character class; here each character is text, so no
    separator can make a pattern that backtracks."""
    if not isinstance(text, str) or not isinstance(sep, str):
        raise EvalRefused("xacro.tokenize() takes strings")
    parts = re.split("[" + "".join(re.escape(c) for c in sep) + "]", text) if sep else [text]
    return [part for part in parts if part] if skip_empty else parts


def _refusal(reason: str, expression: str | None) -> Refusal:
    if "--trust-xacro" not in reason and "safety limit" not in reason:
        reason += " (txtool's restricted xacro evaluator; see --trust-xacro)"
    return Refusal(reason, needle=expression[:200] if expression else None)


class _SubstitutionNames(Mapping[str, Any]):
    """``$(eval)``'s names: functions first, then the arguments (as xacro's _DictWrapper)."""

    def __init__(self, args: Mapping[str, str], functions: Mapping[str, Any]) -> None:
        self.args = args
        self.functions = functions

    def __getitem__(self, key: str) -> Any:
        from xacro.substitution_args import convert_value

        if key in self.functions:
            return self.functions[key]
        return convert_value(self.args[key], "auto")

    def __iter__(self) -> Iterator[str]:
        return iter({**self.args, **self.functions})

    def __len__(self) -> int:
        return len({**self.args, **self.functions})


def _roots(path: str) -> list[str]:
    """The folders an untrusted expansion may read: the repository or workspace of ``path``
    (see :func:`txtool.io.packages.workspace_roots`), else its package's folder, else its own."""
    roots = workspace_roots(path)
    manifest = enclosing_manifest(path)
    if manifest is not None:
        roots.append(str(manifest.parent))
    return roots or [os.path.dirname(path)]


def _yaml_nodes(root: Any) -> int:
    """Nodes of a composed YAML document with every alias expanded, counted up to the limit
    plus one (a shared node is counted as often as it is referred to, without expanding it)."""
    import yaml

    memo: dict[int, int] = {}

    def size(node: Any) -> int:
        known = memo.get(id(node))
        if known is not None:
            return known
        memo[id(node)] = MAX_YAML_NODES + 1  # a cycle counts as too large
        total = 1
        if isinstance(node, yaml.SequenceNode):
            for child in node.value:
                total += size(child)
                if total > MAX_YAML_NODES:
                    break
        elif isinstance(node, yaml.MappingNode):
            for key, child in node.value:
                total += size(key) + size(child)
                if total > MAX_YAML_NODES:
                    break
        memo[id(node)] = total
        return total

    return size(root) if root is not None else 0


def _unit_loader(xacro: Any, yaml: Any) -> Any:
    """yaml's SafeLoader with xacro's unit tags (``!degrees 90``), evaluated safely."""

    class Loader(yaml.SafeLoader):  # type: ignore[misc, name-defined]
        pass

    for unit in xacro.ConstructUnits:
        Loader.add_constructor(unit.value.tag, unit.constructor)
    return Loader

