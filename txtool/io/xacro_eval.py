"""A restricted evaluator for xacro's ``${...}`` and ``$(eval ...)``: data, never code.

xacro evaluates expressions with Python's ``eval``; a file from a pull request can then escape
to ``os.system`` through dunder attributes. This evaluator walks the expression's syntax tree
and knows only:

- literals: numbers (not complex), strings, ``True``/``False``/``None``, lists, tuples, sets
  and dicts, f-strings;
- arithmetic (``+ - * / // % **``), bit operations, unary ``- + ~ not``, comparisons (``in``,
  ``is`` too), ``and``/``or``, ``x if c else y``, indexing and slicing;
- names: properties, macro arguments, and the functions and constants xacro itself exposes
  (:data:`GLOBALS`: xacro's ``create_global_symbols``, with the ``math`` and ``python``
  namespaces; never ``type``, ``vars``, ``isinstance``, ``issubclass``, ``hash``);
- attributes: namespaces (``math.pi``, ``xacro.load_yaml``, an include's ``ns``), keys of a
  loaded YAML dictionary (``limits.upper``, xacro's ``YamlDictWrapper``), and a few methods of
  strings, lists and dicts (:data:`STR_METHODS`, ...); never a name starting with ``__``.

No lambda, comprehension, walrus, starred call or keyword splat. Sizes are bounded: integers
to :data:`MAX_INT_BITS` bits, strings and sequences to :data:`MAX_LENGTH` items, before they
are built (``9**9**9``, ``'a' * 10**9`` and ``'%9999999999d'`` are refused, not computed).

Work is priced as it is done, against one budget per file (:class:`Meter`,
:data:`MAX_WORK` steps): every node evaluated, and every value an operation reads or makes at
its size (a string by its length, a container by its items counted through nested ones, a
range by its length, an integer by its bits). Operations whose cost a size does not say are
bounded by their arguments first (rounding digits, products over ranges, format widths in
every syntax), and ``map``, ``filter``, ``zip``, ``enumerate`` and ``reversed`` give lists,
so no lazy pipeline runs unpriced inside a builtin. Past the budget: :class:`WorkLimit`.
"""

from __future__ import annotations

import ast
import contextlib
import itertools
import math
import re
import string
from collections.abc import Callable, Iterator, Mapping
from typing import Any

MAX_EXPRESSION = 100_000  # characters of one expression
MAX_INT_BITS = 4096
MAX_LENGTH = 1_000_000  # characters of a string, items of a list, tuple, set, dict or range
MAX_WIDTH = 1000  # of a field in a format string (%-format, str.format, f-string)
MAX_DIGITS = MAX_INT_BITS  # of round(x, n): |n| (a negative n builds 10**-n)
# Steps of work one file's expansion may take: each about a tenth of a microsecond of work,
# so the budget is spent in well under a second; real robots take a few thousand.
MAX_WORK = 5_000_000
CALL_STEPS = 10  # a node evaluated or a function called: about a microsecond of Python


class EvalRefused(Exception):
    """The expression uses something outside the restricted grammar, or is too large."""


class WorkLimit(Exception):
    """The expansion of one file took more than its budget of work (:class:`Meter`)."""

    def __init__(self, budget: int) -> None:
        super().__init__(f"{budget} steps of work")
        self.what = f"{budget} steps of work"


class Meter:
    """The work one file's expansion may still do: charged as it is done, never reset."""

    def __init__(self, budget: int = MAX_WORK) -> None:
        self.budget = budget
        self.left = budget

    def charge(self, steps: int) -> None:
        self.left -= steps
        if self.left < 0:
            raise WorkLimit(self.budget)

    def charge_values(self, *values: Any) -> None:
        self.charge(sum(cost(v) for v in values))


_meter: Meter | None = None  # the file's, while an expansion runs (see metered)


@contextlib.contextmanager
def metered(meter: Meter) -> Iterator[Meter]:
    """Charge every evaluation inside to ``meter`` (one file's expansion)."""
    global _meter
    saved, _meter = _meter, meter
    try:
        yield meter
    finally:
        _meter = saved


def current_meter() -> Meter:
    """The meter of the running expansion; a fresh one outside any."""
    return _meter if _meter is not None else Meter()


def _words(value: Any) -> int:
    return abs(value).bit_length() // 64 + 1 if isinstance(value, int) else 1


def int_work(*values: Any) -> int:
    """Steps of an arithmetic operation on integers: CPython multiplies, divides and prints
    them in time the product of their sizes in 64-bit words (one number: its square)."""
    sizes = sorted((_words(v) for v in values if isinstance(v, int)
                    and not isinstance(v, bool)), reverse=True)
    if not sizes:
        return 0
    return sizes[0] * (sizes[1] if len(sizes) > 1 else sizes[0]) // 8


def cost(value: Any) -> int:
    """Steps to read or make ``value``: its size, as :func:`deep_size` counts it."""
    if isinstance(value, str | bytes):
        return 1 + len(value) // 16
    if isinstance(value, int) and not isinstance(value, bool):
        return 1 + value.bit_length() // 64
    if isinstance(value, list | tuple | set | frozenset | dict | range):
        return deep_size(value)
    return 1


class Namespace(dict):
    """A namespace of functions (``math``, ``python``, ``xacro``): dotted access only."""


class SafeFunction:
    """A function an expression may call (wrapping the real one, which it never exposes)."""

    __slots__ = ("function", "name")

    def __init__(self, name: str, function: Callable[..., Any]) -> None:
        self.name = name
        self.function = function

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        meter = current_meter()
        meter.charge(CALL_STEPS + int_work(*args))
        meter.charge_values(*args, *kwargs.values())
        result = self.function(*args, **kwargs)
        meter.charge(cost(result))
        return result

    def __repr__(self) -> str:
        return f"<function {self.name}>"


_TOO_LONG = f"a value of more than {MAX_LENGTH} items (a safety limit)"
_TOO_BIG = f"a number over {MAX_INT_BITS} bits (a safety limit)"


def _refuse_large(value: Any) -> Any:
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > MAX_INT_BITS:
        raise EvalRefused(_TOO_BIG)
    sized = isinstance(value, str | bytes | list | tuple | set | frozenset | dict | range)
    if sized and len(value) > MAX_LENGTH:
        raise EvalRefused(_TOO_LONG)
    return value


def deep_size(value: Any, budget: int = MAX_LENGTH) -> int:
    """Items in ``value``, counting nested containers and characters, up to ``budget`` + 1
    (a list of one list repeated is as large as what printing it writes)."""
    stack, total = [value], 0
    while stack and total <= budget:
        item = stack.pop()
        if isinstance(item, str):
            total += len(item)
        elif isinstance(item, dict):
            total += 1
            stack.extend(item.keys())
            stack.extend(item.values())
        elif isinstance(item, list | tuple | set | frozenset):
            total += 1
            stack.extend(item)
        elif isinstance(item, range):
            total += 1 + len(item)
        else:
            total += 1
    return total


def _refuse_deep(value: Any) -> Any:
    if isinstance(value, list | tuple | set | frozenset | dict) and deep_size(value) > MAX_LENGTH:
        raise EvalRefused(_TOO_LONG)
    return value


def _int_size(value: Any) -> int:
    return abs(value).bit_length() if isinstance(value, int) and not isinstance(value, bool) else 0


def _sized(value: Any) -> int | None:
    return deep_size(value) if isinstance(value, str | list | tuple) else None


def _check_binop(op: ast.operator, left: Any, right: Any) -> None:
    """Refuse, before computing it, a result that would be too large."""
    if isinstance(op, ast.Pow):
        base, exponent = _int_size(left), right if isinstance(right, int) else 0
        if base > 1 and exponent > 0 and base * exponent > MAX_INT_BITS:
            raise EvalRefused(_TOO_BIG)
    elif isinstance(op, ast.Mult):
        for sequence, count in ((left, right), (right, left)):
            size = _sized(sequence)
            if size is not None and isinstance(count, int) and size * max(count, 0) > MAX_LENGTH:
                raise EvalRefused(_TOO_LONG)
        if _int_size(left) + _int_size(right) > MAX_INT_BITS:
            raise EvalRefused(_TOO_BIG)
    elif isinstance(op, ast.LShift) and isinstance(right, int):
        if _int_size(left) + max(right, 0) > MAX_INT_BITS:
            raise EvalRefused(_TOO_BIG)
    elif isinstance(op, ast.Add):
        sizes = _sized(left), _sized(right)
        if sizes[0] is not None and sizes[1] is not None and sum(sizes) > MAX_LENGTH:  # type: ignore[arg-type]
            raise EvalRefused(_TOO_LONG)
    elif isinstance(op, ast.Mod) and isinstance(left, str):
        _check_percent_format(left)


def _check_percent_format(template: str) -> None:
    """Refuse a ``%`` field wider or more precise than :data:`MAX_WIDTH`, or one whose width
    comes from the arguments (``*``), read as CPython's ``%`` reads them: a ``(key)`` may hold
    nested parentheses, so no regular expression finds every width."""
    meter = current_meter()
    at = template.find("%")
    while at >= 0:
        meter.charge(CALL_STEPS)  # read here in Python, then formatted: a field at a time
        at += 1
        if template.startswith("(", at):
            depth = 0
            while at < len(template):
                depth += {"(": 1, ")": -1}.get(template[at], 0)
                at += 1
                if depth == 0:
                    break
        while at < len(template) and template[at] in "-+ #0":
            at += 1
        at = _percent_number(template, at)
        if template.startswith(".", at):
            at = _percent_number(template, at + 1)
        at = template.find("%", at + 1)


def _percent_number(template: str, at: int) -> int:
    """Past a width or precision at ``at``, refused when ``*`` or over the limit."""
    if template.startswith("*", at):
        raise EvalRefused(f"a format field wider than {MAX_WIDTH} (a safety limit)")
    end = at
    while end < len(template) and template[end].isdigit():
        end += 1
    if end - at > 4 or (end > at and int(template[at:end]) > MAX_WIDTH):
        raise EvalRefused(f"a format field wider than {MAX_WIDTH} (a safety limit)")
    return end


def _check_format_spec(spec: str) -> None:
    for number in re.findall(r"\d+", spec):
        if len(number) > 4 or int(number) > MAX_WIDTH:
            raise EvalRefused(f"a format field wider than {MAX_WIDTH} (a safety limit)")


def _safe_format(template: str, *args: Any, **kwargs: Any) -> str:
    """``str.format`` for plain fields: ``{}``, ``{0}``, ``{name}``, with a bounded spec; never
    ``{0.attr}`` or ``{0[key]}``, which reach into objects."""
    meter = current_meter()
    for _text, field, spec, _conversion in string.Formatter().parse(template):
        meter.charge(CALL_STEPS)
        if field is None:
            continue
        if "." in field or "[" in field:
            raise EvalRefused("a format field with '.' or '[' is not allowed")
        if spec:
            if "{" in spec:
                raise EvalRefused("a nested format field is not allowed")
            _check_format_spec(spec)
    return _refuse_large(template.format(*args, **kwargs))


def _safe_replace(text: str, old: str, new: str, count: int = -1) -> str:
    found = text.count(old) if old else len(text) + 1
    if count >= 0:
        found = min(found, count)
    if len(text) + found * max(len(new) - len(old), 0) > MAX_LENGTH:
        raise EvalRefused(_TOO_LONG)
    return text.replace(old, new, count)


def _safe_join(separator: str, items: Any) -> str:
    items = list(items)
    if deep_size(items) + len(separator) * len(items) > MAX_LENGTH:
        raise EvalRefused(_TOO_LONG)
    return separator.join(items)


def _bounded_round(number: Any, *digits: Any) -> Any:
    if digits and isinstance(digits[0], int) and abs(digits[0]) > MAX_DIGITS:
        raise EvalRefused(f"round() to more than {MAX_DIGITS} digits (a safety limit)")
    return round(number, *digits)


def _bounded_prod(items: Any, *, start: Any = 1) -> Any:
    """``math.prod``, refusing a product over :data:`MAX_INT_BITS` bits as it grows."""
    product = start
    for item in items:
        product = _refuse_large(product * item)
    return product


def _eager(function: Callable[..., Any]) -> Callable[..., list[Any]]:
    """``map`` and its kind as lists, at most :data:`MAX_LENGTH` items: a lazy pipeline would
    run inside the builtin that consumes it, one unpriced step per item."""
    def listed(*args: Any) -> list[Any]:
        items = list(itertools.islice(function(*args), MAX_LENGTH + 1))
        return _refuse_deep(_refuse_large(items))  # type: ignore[no-any-return]
    return listed


def _numeric_sum(items: Any, start: Any = 0) -> Any:
    if not isinstance(start, int | float):
        raise EvalRefused("sum() of anything but numbers is not allowed")
    return sum(items, start)


def _padded(method: str) -> Callable[..., str]:
    def pad(text: str, width: int, *rest: Any) -> str:
        if width > MAX_WIDTH + len(text):
            raise EvalRefused(f"a format field wider than {MAX_WIDTH} (a safety limit)")
        return getattr(text, method)(width, *rest)  # type: ignore[no-any-return]
    return pad


STR_METHODS: dict[str, Callable[..., Any]] = {
    name: getattr(str, name) for name in (
        "split", "rsplit", "splitlines", "strip", "lstrip", "rstrip", "lower", "upper", "title",
        "capitalize", "swapcase", "casefold", "startswith", "endswith", "find", "rfind", "index",
        "rindex", "count", "partition", "rpartition", "isdigit", "isalpha", "isalnum",
        "isnumeric", "isdecimal", "isspace", "islower", "isupper", "removeprefix",
        "removesuffix",
    )
}
STR_METHODS.update(format=_safe_format, join=_safe_join, replace=_safe_replace,
                   center=_padded("center"), ljust=_padded("ljust"), rjust=_padded("rjust"),
                   zfill=_padded("zfill"))
SEQUENCE_METHODS = {"index": "index", "count": "count"}
DICT_METHODS = {"keys": "keys", "values": "values", "items": "items", "get": "get"}


def _bounded_range(*args: int) -> range:
    return _refuse_large(range(*args))  # type: ignore[no-any-return]


def _bounded_int(name: str, function: Callable[..., Any], limit: int) -> Callable[..., Any]:
    def checked(*args: Any) -> Any:
        if any(isinstance(a, int) and abs(a) > limit for a in args):
            raise EvalRefused(f"{name}() of a number over {limit} (a safety limit)")
        return _refuse_large(function(*args))
    return checked


def _math_namespace() -> Namespace:
    space = Namespace()
    for name, value in vars(math).items():
        if name.startswith("_"):
            continue
        if callable(value):
            if name in ("factorial", "comb", "perm", "lcm"):
                value = _bounded_int(name, value, 1000)
            elif name == "prod":
                value = _bounded_prod
            space[name] = SafeFunction(f"math.{name}", value)
        else:
            space[name] = value
    return space


_PYTHON_BUILTINS = (
    "list", "dict", "map", "len", "str", "float", "int", "bool", "min", "max", "round", "abs",
    "all", "any", "divmod", "enumerate", "filter", "frozenset", "ord", "chr", "repr",
    "reversed", "set", "sum", "tuple", "zip", "sorted",
)


def _python_namespace() -> Namespace:
    import builtins

    space = Namespace({"True": True, "False": False})
    for name in _PYTHON_BUILTINS:
        space[name] = SafeFunction(name, getattr(builtins, name))
    for name in ("map", "filter", "zip", "enumerate", "reversed"):
        space[name] = SafeFunction(name, _eager(getattr(builtins, name)))
    space["round"] = SafeFunction("round", _bounded_round)
    space["range"] = SafeFunction("range", _bounded_range)
    space["sum"] = SafeFunction("sum", _numeric_sum)
    space["pow"] = SafeFunction("pow", _bounded_pow)
    space["slice"] = SafeFunction("slice", slice)
    return space


def _bounded_pow(base: Any, exponent: Any, *modulo: Any) -> Any:
    if not modulo or modulo[0] is None:
        _check_binop(ast.Pow(), base, exponent)
    elif isinstance(exponent, int):  # a squaring and a product per bit of the exponent
        current_meter().charge(abs(exponent).bit_length() * int_work(modulo[0]))
    return _refuse_large(pow(base, exponent, *modulo))


def make_globals(xacro_functions: Mapping[str, Callable[..., Any]]) -> dict[str, Any]:
    """The global symbols of an expression, as xacro's ``create_global_symbols`` has them.

    ``xacro_functions`` are the ``xacro.`` namespace's functions (load_yaml, arg, message,
    ...), given by the caller: they touch files and xacro's state.
    """
    math_space = _math_namespace()
    python_space = _python_namespace()
    xacro_space = Namespace({name: SafeFunction(f"xacro.{name}", function)
                             for name, function in xacro_functions.items()})
    symbols: dict[str, Any] = dict(math_space)
    for name in ("list", "dict", "map", "len", "str", "float", "int", "bool", "min", "max",
                 "round", "sorted", "range", "True", "False"):
        symbols[name] = python_space[name]
    for name in ("load_yaml", "abs_filename", "dotify"):
        if name in xacro_space:
            symbols[name] = xacro_space[name]
    symbols.update(math=math_space, python=python_space, xacro=xacro_space)
    return symbols


class Evaluator:
    """Evaluates one parsed expression against a symbol table (xacro's ``Table``)."""

    def __init__(self, symbols: Mapping[str, Any], attribute: Callable[[Any, str], Any],
                 meter: Meter | None = None) -> None:
        self.symbols = symbols
        self.attribute = attribute
        self.meter = meter or current_meter()

    def _made(self, value: Any) -> Any:
        """``value``, charged at its size (what making or reading it cost)."""
        self.meter.charge(cost(value))
        return value

    def run(self, node: ast.AST) -> Any:
        self.meter.charge(CALL_STEPS)
        handler = getattr(self, "_" + type(node).__name__, None)
        if handler is None:
            raise EvalRefused(f"{_describe(node)} is not allowed in a xacro expression "
                              "(txtool evaluates a restricted grammar; see --trust-xacro)")
        return _refuse_large(handler(node))

    def _Expression(self, node: ast.Expression) -> Any:
        return self.run(node.body)

    def _Constant(self, node: ast.Constant) -> Any:
        if isinstance(node.value, complex | bytes) or node.value is Ellipsis:
            raise EvalRefused(f"the constant {node.value!r} is not allowed")
        return node.value

    def _Name(self, node: ast.Name) -> Any:
        if node.id.startswith("__"):
            raise EvalRefused(f"the name '{node.id}' is not allowed")
        try:
            return self.symbols[node.id]
        except KeyError:
            raise NameError(f"name '{node.id}' is not defined") from None

    def _Attribute(self, node: ast.Attribute) -> Any:
        if node.attr.startswith("__"):  # (a YAML key may start with one underscore)
            raise EvalRefused(f"the attribute '{node.attr}' is not allowed")
        return self.attribute(self.run(node.value), node.attr)

    def _Call(self, node: ast.Call) -> Any:
        function = self.run(node.func)
        if not isinstance(function, SafeFunction | BoundMethod):
            raise EvalRefused(f"calling {_describe_value(function)} is not allowed")
        args = []
        for arg in node.args:
            if isinstance(arg, ast.Starred):
                raise EvalRefused("a starred argument is not allowed")
            args.append(self.run(arg))
        kwargs = {}
        for keyword in node.keywords:
            if keyword.arg is None:
                raise EvalRefused("a ** argument is not allowed")
            kwargs[keyword.arg] = self.run(keyword.value)
        return _refuse_deep(function(*args, **kwargs))

    def _BinOp(self, node: ast.BinOp) -> Any:
        left, right = self.run(node.left), self.run(node.right)
        _check_binop(node.op, left, right)
        self.meter.charge(int_work(left, right))
        self.meter.charge_values(left, right)
        return self._made(_refuse_deep(_BINARY[type(node.op)](left, right)))

    def _UnaryOp(self, node: ast.UnaryOp) -> Any:
        operand = self.run(node.operand)
        return self._made(_UNARY[type(node.op)](operand))

    def _BoolOp(self, node: ast.BoolOp) -> Any:
        value: Any = None
        for operand in node.values:
            value = self.run(operand)
            if isinstance(node.op, ast.And) and not value:
                return value
            if isinstance(node.op, ast.Or) and value:
                return value
        return value

    def _Compare(self, node: ast.Compare) -> Any:
        left = self.run(node.left)
        for op, right_node in zip(node.ops, node.comparators, strict=True):
            right = self.run(right_node)
            self.meter.charge_values(left, right)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True

    def _IfExp(self, node: ast.IfExp) -> Any:
        return self.run(node.body) if self.run(node.test) else self.run(node.orelse)

    def _List(self, node: ast.List) -> Any:
        return self._made(_refuse_deep([self.run(item) for item in self._items(node.elts)]))

    def _Tuple(self, node: ast.Tuple) -> Any:
        return self._made(_refuse_deep(tuple(self.run(item) for item in self._items(node.elts))))

    def _Set(self, node: ast.Set) -> Any:
        return self._made({self.run(item) for item in self._items(node.elts)})

    def _Dict(self, node: ast.Dict) -> Any:
        if any(key is None for key in node.keys):
            raise EvalRefused("a ** in a dict literal is not allowed")
        pairs = zip(node.keys, node.values, strict=True)
        return self._made(_refuse_deep({self.run(k): self.run(v)  # type: ignore[arg-type]
                                        for k, v in pairs}))

    @staticmethod
    def _items(items: list[ast.expr]) -> list[ast.expr]:
        if any(isinstance(item, ast.Starred) for item in items):
            raise EvalRefused("a starred item is not allowed")
        return items

    def _Subscript(self, node: ast.Subscript) -> Any:
        container = self.run(node.value)
        index = self.run(node.slice)
        if not isinstance(container, str | list | tuple | dict | range):
            raise EvalRefused(f"indexing {_describe_value(container)} is not allowed")
        return self._made(container[index])

    def _Slice(self, node: ast.Slice) -> Any:
        parts = [None if part is None else self.run(part)
                 for part in (node.lower, node.upper, node.step)]
        return slice(*parts)

    def _JoinedStr(self, node: ast.JoinedStr) -> Any:
        return self._made("".join(str(self.run(part)) for part in node.values))

    def _FormattedValue(self, node: ast.FormattedValue) -> Any:
        value = self.run(node.value)
        spec = self.run(node.format_spec) if node.format_spec is not None else ""
        _check_format_spec(spec)
        if node.conversion == ord("r"):
            value = repr(value)
        elif node.conversion == ord("s"):
            value = str(value)
        elif node.conversion == ord("a"):
            value = ascii(value)
        self.meter.charge(cost(value))
        return self._made(format(value, spec))


class BoundMethod(SafeFunction):
    """A whitelisted method of a string, list or dict, bound to its value (read at each call,
    and charged as an argument is)."""

    __slots__ = ("value",)

    def __init__(self, name: str, function: Callable[..., Any], value: Any) -> None:
        super().__init__(name, function)
        self.value = value

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        current_meter().charge(cost(self.value))
        return super().__call__(*args, **kwargs)


def plain_attribute(value: Any, name: str) -> Any:
    """The attributes an expression may read: namespace entries and whitelisted methods."""
    if isinstance(value, Namespace):
        if name in value:
            return value[name]
        raise NameError(f"name '{name}' is not defined")
    if isinstance(value, str) and name in STR_METHODS:
        method = STR_METHODS[name]
        return BoundMethod(f"str.{name}", lambda *a, **k: method(value, *a, **k), value)
    if isinstance(value, list | tuple) and name in SEQUENCE_METHODS:
        return BoundMethod(name, getattr(value, SEQUENCE_METHODS[name]), value)
    if isinstance(value, dict) and name in DICT_METHODS:
        return BoundMethod(name, getattr(value, DICT_METHODS[name]), value)
    raise EvalRefused(f"the attribute '{name}' of {_describe_value(value)} is not allowed")


def _describe(node: ast.AST) -> str:
    names = {"Lambda": "a lambda", "ListComp": "a comprehension", "SetComp": "a comprehension",
             "DictComp": "a comprehension", "GeneratorExp": "a generator expression",
             "NamedExpr": "an assignment (:=)", "Await": "await", "Yield": "yield",
             "YieldFrom": "yield", "Starred": "a starred item"}
    return names.get(type(node).__name__, type(node).__name__)


def _describe_value(value: Any) -> str:
    return f"a value of type '{type(value).__name__}'"


def _div(left: Any, right: Any) -> Any:
    return left / right


_BINARY: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b, ast.Mult: lambda a, b: a * b,
    ast.Div: _div, ast.FloorDiv: lambda a, b: a // b, ast.Mod: lambda a, b: a % b,
    ast.Pow: lambda a, b: a ** b, ast.LShift: lambda a, b: a << b,
    ast.RShift: lambda a, b: a >> b, ast.BitOr: lambda a, b: a | b,
    ast.BitAnd: lambda a, b: a & b, ast.BitXor: lambda a, b: a ^ b,
}
_UNARY: dict[type, Callable[[Any], Any]] = {
    ast.USub: lambda a: -a, ast.UAdd: lambda a: +a, ast.Not: lambda a: not a,
    ast.Invert: lambda a: ~a,
}
_COMPARE: dict[type, Callable[[Any, Any], bool]] = {
    ast.Eq: lambda a, b: a == b, ast.NotEq: lambda a, b: a != b, ast.Lt: lambda a, b: a < b,
    ast.LtE: lambda a, b: a <= b, ast.Gt: lambda a, b: a > b, ast.GtE: lambda a, b: a >= b,
    ast.In: lambda a, b: a in b, ast.NotIn: lambda a, b: a not in b,
    ast.Is: lambda a, b: a is b, ast.IsNot: lambda a, b: a is not b,
}


def parse_expression(text: str) -> ast.Expression:
    """Parse one expression (as xacro does: stripped), refusing an over-long one."""
    text = text.strip()
    if len(text) > MAX_EXPRESSION:
        raise EvalRefused(f"an expression of more than {MAX_EXPRESSION} characters "
                          "(a safety limit)")
    return ast.parse(text, "<expression>", mode="eval")


def evaluate(text: str, symbols: Mapping[str, Any],
             attribute: Callable[[Any, str], Any] = plain_attribute) -> Any:
    """The value of the expression ``text`` over ``symbols``; :class:`EvalRefused` when the
    expression leaves the grammar, or Python's own error (NameError, ZeroDivisionError, ...)."""
    return Evaluator(symbols, attribute).run(parse_expression(text))
