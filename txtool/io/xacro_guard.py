"""Hooks that make upstream xacro safe for a file nobody vouches for, without forking it.

Installed for one expansion (:meth:`XacroGuard.installed`), they replace:

- ``xacro.safe_eval`` (every ``${...}``, and the ``!degrees``-style YAML units) and
  ``substitution_args._eval`` (``$(eval ...)``) by :mod:`txtool.io.xacro_eval`;
- xacro's global symbols by :func:`txtool.io.xacro_eval.make_globals`;
- ``$(env NAME)``: the value only for a name the configuration's ``xacro-env`` lists and that
  does not look like a secret, else a refusal; ``$(optenv NAME DEFAULT)``: its default then;
- ``$(find PKG)``: as before, and the package found becomes a root files may be read from;
- ``xacro.load_yaml`` and ``<xacro:include>``: only regular files inside the roots (the
  repository of the top file, its package, packages ``$(find)`` found), symbolic links
  resolved first; a YAML document expanding to more than :data:`MAX_YAML_NODES` nodes
  (an alias bomb) is refused.
"""

from __future__ import annotations

import contextlib
import os
import re
from collections.abc import Iterator, Mapping
from typing import Any

from txtool.io.packages import enclosing_manifest, find_package, workspace_roots
from txtool.io.xacro_eval import (
    EvalRefused,
    SafeFunction,
    evaluate,
    make_globals,
    plain_attribute,
)
from txtool.io.xmlio import InputError, TooLarge, XacroOptions, read_regular

MAX_YAML_NODES = 1_000_000
# Names never passed to $(env): a configuration file is in the pull request's hands.
SECRET_NAME = re.compile(
    r"TOKEN|SECRET|PASSW|PASSPHRASE|CREDENTIAL|PRIVATE|_KEY$|^KEY$|API_?KEY|AUTH|COOKIE|SESSION"
    r"|^(GITHUB|ACTIONS|RUNNER|AWS|AZURE|GCP|GOOGLE|CI_JOB|NPM|PYPI|DOCKER|SSH)_",
    re.IGNORECASE,
)


class Refusal(Exception):
    """What the guard refused: a one-line reason, and a text to find the line by."""

    def __init__(self, reason: str, needle: str | None = None) -> None:
        super().__init__(reason)
        self.reason = reason
        self.needle = needle


class NodeLimit(Exception):
    """The expansion created more XML nodes than the sandbox allows."""


def secret_looking(name: str) -> bool:
    return bool(SECRET_NAME.search(name))


class XacroGuard:
    """The hooks of one expansion of ``path``."""

    def __init__(self, path: str, options: XacroOptions, environment: Mapping[str, str]) -> None:
        self.path = os.path.abspath(path)
        self.options = options
        self.environment = {k: v for k, v in environment.items()
                            if k in options.env and not secret_looking(k)}
        self.roots = [os.path.realpath(root) for root in _roots(self.path)]

    # -- files -------------------------------------------------------------------------------
    def check_readable(self, path: str, what: str) -> None:
        """Refuse a file outside the roots (after resolving symbolic links)."""
        real = os.path.realpath(path)
        if not any(real == root or real.startswith(root.rstrip(os.sep) + os.sep)
                   for root in self.roots):
            raise Refusal(f"{what} of '{path}' is outside the repository and the packages "
                          "found (txtool reads no other file for an untrusted xacro; "
                          "see --trust-xacro)", needle=os.path.basename(path))

    def add_package_root(self, folder: str) -> None:
        if os.path.isfile(os.path.join(folder, "package.xml")):
            self.roots.append(os.path.realpath(folder))

    # -- substitution args -------------------------------------------------------------------
    def env(self, name: str) -> str:
        if name not in self.options.env or secret_looking(name):
            why = ("its name looks like a secret" if secret_looking(name)
                   else "only names listed in xacro-env are read")
            raise Refusal(f"$(env {name}) is not allowed ({why}; see --trust-xacro)",
                          needle=f"$(env {name}")
        try:
            return self.environment[name]
        except KeyError:
            from xacro.substitution_args import SubstitutionException

            raise SubstitutionException(f"environment variable '{name}' is not set") from None

    def optenv(self, name: str, default: str = "") -> str:
        return self.environment.get(name, default)

    def find(self, package: str) -> str:
        folder = find_package(package, near=self.path, pkg_paths=self.options.pkg_paths,
                              pkg_dirs=self.options.pkg_dirs)
        self.add_package_root(folder)
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
            return evaluate(expression, symbols, self.attribute)
        except EvalRefused as exc:
            raise _refusal(str(exc), expression.strip()) from None

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
        import yaml

        path = xacro.abs_filename_spec(filename)
        self.check_readable(path, "load_yaml")
        try:
            data = read_regular(path)
        except TooLarge as exc:
            raise Refusal(str(exc)) from None
        except InputError as exc:
            raise xacro.XacroException(str(exc)) from None
        loader = _unit_loader(xacro, yaml)
        xacro.filestack.append(path)
        try:
            node = yaml.compose(data, Loader=loader)
            if _yaml_nodes(node) > MAX_YAML_NODES:
                raise Refusal(f"{filename}: a YAML document of more than {MAX_YAML_NODES} "
                              "nodes once its aliases are expanded (a safety limit)")
            value = loader(data).construct_document(node) if node is not None else None
        finally:
            xacro.filestack.pop()
        xacro.all_includes.append(path)
        return xacro.YamlListWrapper.wrap(value)

    def globals(self) -> dict[str, Any]:
        import xacro

        upstream = dict(xacro._global_symbols["xacro"])
        upstream["load_yaml"] = self.load_yaml
        return make_globals(upstream)

    @contextlib.contextmanager
    def installed(self) -> Iterator[None]:
        import xacro
        from xacro import substitution_args

        saved = (xacro.safe_eval, xacro._global_symbols, substitution_args._eval,
                 substitution_args._eval_env, substitution_args._eval_optenv,
                 substitution_args._eval_find)
        xacro.safe_eval = self.safe_eval
        xacro._global_symbols = self.globals()
        substitution_args._eval = self.substitution_eval
        substitution_args._eval_env = self.env
        substitution_args._eval_optenv = self.optenv
        substitution_args._eval_find = self.find
        try:
            yield
        finally:
            (xacro.safe_eval, xacro._global_symbols, substitution_args._eval,
             substitution_args._eval_env, substitution_args._eval_optenv,
             substitution_args._eval_find) = saved

    def reraise_refusal(self, cause: BaseException) -> None:
        """Let a refusal through xacro's error handling unchanged, as a :class:`Refusal`."""
        if isinstance(cause, Refusal | NodeLimit | MemoryError | RecursionError):
            raise cause
        if isinstance(cause, EvalRefused):
            raise _refusal(str(cause), None) from None


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

