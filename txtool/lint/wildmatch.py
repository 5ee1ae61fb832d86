"""gitignore patterns matched in time linear in the path: pathspec's translation, run without
backtracking.

pathspec turns each pattern into a Python regular expression, and ``re`` backtracks: the
pattern ``**/a**a**a**a**a**a**a**a**a**a**a**b`` against a folder named with twenty-two ``a``
takes twenty seconds, a few more ``a`` hours. Here the same regular expressions (pathspec stays
the authority on what a pattern means) run on a Pike virtual machine: every alternative is
followed at once, one step per character, so one match costs at most (path length) x (pattern
length) steps, and ``re``'s choice among alternatives (which decides whether a pattern matched
the path itself or a folder holding it) is kept. Steps already taken from the same set of
alternatives on the same character are remembered, so common patterns cost a dictionary look-up
per character.

Only the part of the regular expression language pathspec writes is understood (literals,
``.``, character classes, ``(?:...)``, ``(?P<ps_d>...)``, ``|``, ``*``, ``+``, ``?``, ``^``,
``$``); anything else is a ``ValueError``.
"""

from __future__ import annotations

import os
import re
from typing import NamedTuple

# Instructions: (operation, argument, second argument).
_CHAR, _ANY, _SET, _SPLIT, _JUMP, _START, _END, _MARK, _MATCH = range(9)
_MARK_GROUP = "ps_d"  # pathspec's group for "matched a folder holding the path"
_MEMO_LIMIT = 20_000

Thread = tuple[int, bool]  # (instruction, whether the folder mark was passed)
State = tuple[Thread, ...]


class _Parser:
    """Regular expression text to a tree: ("seq", [...]), ("alt", [...]), ("star"|"plus"|"opt",
    node), ("mark", node), ("char", c), ("any",), ("set", compiled), ("start",), ("end",)."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.at = 0

    def parse(self) -> tuple:
        node = self._alternatives()
        if self.at != len(self.text):
            raise ValueError(f"unexpected {self.text[self.at]!r} in {self.text!r}")
        return node

    def _alternatives(self) -> tuple:
        branches = [self._sequence()]
        while self._peek() == "|":
            self.at += 1
            branches.append(self._sequence())
        return branches[0] if len(branches) == 1 else ("alt", branches)

    def _sequence(self) -> tuple:
        items = []
        while self._peek() not in ("", "|", ")"):
            atom = self._atom()
            quantifier = self._peek()
            if quantifier in ("*", "+", "?"):
                self.at += 1
                if self._peek() in ("?", "+"):
                    raise ValueError(f"lazy or possessive quantifier in {self.text!r}")
                atom = ({"*": "star", "+": "plus", "?": "opt"}[quantifier], atom)
            items.append(atom)
        return ("seq", items)

    def _atom(self) -> tuple:
        text, char = self.text, self.text[self.at]
        self.at += 1
        if char == "(":
            return self._group()
        if char == "[":
            return self._set()
        if char == "\\":
            if self.at >= len(text) or text[self.at].isalnum():
                raise ValueError(f"escape not understood in {text!r}")
            self.at += 1
            return ("char", text[self.at - 1])
        if char == ".":
            return ("any",)
        if char == "^":
            return ("start",)
        if char == "$":
            return ("end",)
        if char in "*+?{":
            raise ValueError(f"unexpected {char!r} in {text!r}")
        return ("char", char)

    def _group(self) -> tuple:
        named = re.match(r"\?P<(\w+)>", self.text[self.at:])
        if self.text.startswith("?:", self.at):
            self.at += 2
        elif named:
            self.at += named.end()
        else:
            raise ValueError(f"group not understood in {self.text!r}")
        inner = self._alternatives()
        if self._peek() != ")":
            raise ValueError(f"unclosed group in {self.text!r}")
        self.at += 1
        return ("mark", inner) if named and named.group(1) == _MARK_GROUP else inner

    def _set(self) -> tuple:
        text, start = self.text, self.at - 1
        end = self.at + (text.startswith("^", self.at))
        end += text.startswith("]", end)
        while end < len(text) and text[end] != "]":
            end += 2 if text[end] == "\\" else 1
        if end >= len(text):
            raise ValueError(f"unclosed character class in {text!r}")
        self.at = end + 1
        return ("set", re.compile(text[start:self.at]))  # one character: nothing to backtrack

    def _peek(self) -> str:
        return self.text[self.at] if self.at < len(self.text) else ""


def _emit(node: tuple, code: list[list]) -> None:
    """Append the instructions of ``node`` to ``code`` (jump targets are absolute)."""
    kind = node[0]
    if kind == "seq":
        for item in node[1]:
            _emit(item, code)
    elif kind == "alt":
        jumps = []
        for index, branch in enumerate(node[1]):
            if index < len(node[1]) - 1:
                split = [_SPLIT, len(code) + 1, None]
                code.append(split)
                _emit(branch, code)
                jumps.append([_JUMP, None, None])
                code.append(jumps[-1])
                split[2] = len(code)
            else:
                _emit(branch, code)
        for jump in jumps:
            jump[1] = len(code)
    elif kind in ("star", "opt"):
        split = [_SPLIT, len(code) + 1, None]
        code.append(split)
        _emit(node[1], code)
        if kind == "star":
            code.append([_JUMP, code.index(split), None])
        split[2] = len(code)
    elif kind == "plus":
        top = len(code)
        _emit(node[1], code)
        code.append([_SPLIT, top, len(code) + 1])
    elif kind == "mark":
        _emit(node[1], code)
        code.append([_MARK, None, None])
    else:
        operation = {"char": _CHAR, "any": _ANY, "set": _SET, "start": _START, "end": _END}[kind]
        code.append([operation, node[1] if len(node) > 1 else None, None])


def _required_text(tree: tuple) -> str:
    """The longest run of characters every match holds (the top sequence's plain characters
    that stand next to each other), or ``""``."""
    runs, run = [""], ""
    for item in tree[1] if tree[0] == "seq" else ():
        if item[0] == "char":
            run += item[1]
        else:
            runs.append(run)
            run = ""
    runs.append(run)
    return max(runs, key=len)


class Program:
    """One regular expression, compiled for :meth:`search`."""

    def __init__(self, regex: str) -> None:
        tree = _Parser(regex).parse()
        self._needle = _required_text(tree)
        code: list[list] = []
        _emit(tree, code)
        code.append([_MATCH, None, None])
        self._code = [tuple(instruction) for instruction in code]
        # States (tuples of threads) are numbered once; a step is then one look-up of
        # (state number, character, flags), as in a lazily built automaton.
        self._numbers: dict[State, int] = {}
        self._states: list[State] = []
        self._memo: dict[tuple[int, str, int], tuple[int, bool | None]] = {}
        self._number(())  # 0: no thread left
        self._starts = {flag: self._number(self._closure(((0, False),), True, flag))
                        for flag in (False, True)}
        self._kept = len(self._states)

    def search(self, text: str) -> bool | None:
        """As ``re.search`` (what pathspec calls): None when nothing matches, else whether the
        folder mark group took part in the match ``re`` would return."""
        if self._needle not in text:  # most paths are turned down here, at the speed of C
            return None
        last = len(text) - 1
        newline_last = last >= 0 and text[last] == "\n"
        state = self._starts[last < 0 or (last == 0 and newline_last)]
        memo, matched = self._memo, None
        for position, char in enumerate(text):
            # flags: 1 while nothing matched, 2 where ``$`` holds next (before a final newline)
            flags = (matched is None) | (
                2 if position >= last or (position == last - 1 and newline_last) else 0)
            step = memo.get((state, char, flags))
            if step is None:
                step = self._step(state, char, flags)
            state, found = step
            if found is not None:
                matched = found
            if state == 0:
                return matched
        for pc, mark in self._states[state]:
            if self._code[pc][0] == _MATCH:
                return mark
        return matched

    def _number(self, state: State) -> int:
        number = self._numbers.get(state)
        if number is None:
            number = self._numbers[state] = len(self._states)
            self._states.append(state)
        return number

    def _step(self, number: int, char: str, flags: int) -> tuple[int, bool | None]:
        """The state after ``char``, and the mark of a match found before it (if any).

        While nothing has matched (flag 1), a match may still start at the next character: a
        thread from the start is added, after all others (re prefers the leftmost start)."""
        if len(self._memo) >= _MEMO_LIMIT:  # a bound on memory; each step stays linear
            state = self._states[number]
            self._memo.clear()
            self._numbers.clear()
            del self._states[self._kept:]
            self._numbers.update((known, index) for index, known in enumerate(self._states))
            number = self._number(state)
        code, moved, found = self._code, [], None
        for pc, mark in self._states[number]:
            operation, argument, _ = code[pc]
            if operation == _MATCH:
                found = mark  # a match here cuts every alternative re would try after it
                break
            if (
                (operation == _CHAR and char == argument)
                or (operation == _ANY and char != "\n")
                or (operation == _SET and argument.match(char))
            ):
                moved.append((pc + 1, mark))
        if flags & 1 and found is None:
            moved.append((0, False))
        result = (self._number(self._closure(tuple(moved), False, bool(flags & 2))), found)
        self._memo[(number, char, flags)] = result
        return result

    def _closure(self, threads: State, at_start: bool, at_end: bool) -> State:
        """The threads after following every jump, split, anchor and mark, in re's order of
        preference; each instruction once (the first arrival is the one re would prefer)."""
        code, seen, out = self._code, set(), []
        stack = list(reversed(threads))
        while stack:
            pc, mark = stack.pop()
            if pc in seen:
                continue
            seen.add(pc)
            operation, first, second = code[pc]
            if operation == _JUMP:
                stack.append((first, mark))
            elif operation == _SPLIT:
                stack.append((second, mark))
                stack.append((first, mark))
            elif operation == _START:
                if at_start:
                    stack.append((pc + 1, mark))
            elif operation == _END:
                if at_end:
                    stack.append((pc + 1, mark))
            elif operation == _MARK:
                stack.append((pc + 1, True))
            else:
                out.append((pc, mark))
        return tuple(out)


class _Rule(NamedTuple):
    include: bool
    program: Program


class GitIgnore:
    """A list of gitignore patterns, matched as ``pathspec.GitIgnoreSpec`` matches them.

    A pattern git would not accept (pathspec raises on it) is passed over, as git passes over
    an invalid line of a ``.gitignore``.
    """

    def __init__(self, lines: tuple[str, ...]) -> None:
        from pathspec.patterns.gitignore.spec import GitIgnorePatternError, GitIgnoreSpecPattern

        rules: list[_Rule] = []
        for line in lines:
            try:
                pattern = GitIgnoreSpecPattern(line)
            except GitIgnorePatternError:
                continue
            if pattern.include is not None and pattern.regex is not None:
                rules.append(_Rule(pattern.include, Program(pattern.regex.pattern)))
        self._rules = tuple(reversed(rules))  # the last matching line decides

    def match_file(self, path: str) -> bool:
        """Whether ``path`` (relative, ``/``-separated; a folder ends with ``/``) is matched.

        The order of decision is pathspec's (``GitIgnoreSpec``): from the last line up, a line
        matching the path itself beats one matching a folder holding it, and a line that
        re-includes a folder holding the path is kept over a later match of that kind.
        """
        file = path.replace(os.sep, "/") if os.sep != "/" else path
        file = file[1:] if file.startswith("/") else file[2:] if file.startswith("./") else file
        include: bool | None = None
        priority = 0
        for rule in self._rules:
            folder_mark = rule.program.search(file)
            if folder_mark is None:
                continue
            rank = 1 if folder_mark else 2
            if rank > priority:
                include, priority = rule.include, rank
            if rank == 2:
                break
        return bool(include)
