"""Fuzz every command with mutated robot descriptions, for longer than the test suite does.

Run: ``python bench/fuzz.py [--examples N] [--seed S] [--command NAME ...] [--out DIR]
[--slow SECONDS]``.

The documents are those of the fuzz tests (``tests/hardening/fuzz_inputs.py``: the fixtures and
the shared corpus, mutated at tree and byte level); each example runs one command line, chosen
by hypothesis among ``--command`` (repeatable; default: every entry of ``COMMANDS`` there, e.g.
``show-json``, ``validate``, ``convert-ros2-p2``, ``roundtrip-against-json``, ``migrate-diff-to``,
``map``), in-process with click's ``CliRunner``, so that an internal error is an exception rather
than the CLI's one-line ``internal error`` message. Unlike the test suite the run is not
derandomized (``--seed`` makes it repeatable) and does not stop at the first failure.

A failure is a run that does not end as txtool promises (see ``run_failure``: an exception, a
warning, an exit code other than 0/1/2, a traceback, no message, ``validate`` exiting 2 on a
readable file, bad JSON) or one taking more than ``--slow`` seconds of CPU time (default 2).
Failures are grouped by kind (the exception type and the innermost txtool frame, or the command
and what went wrong); for each kind the first one is saved in
``--out`` (default ``fuzz-out``) as ``NNN-<command>.<ext>`` (the document) and
``NNN-<command>.txt`` (command line, mutation steps, traceback), and a summary is printed:

    $ python bench/fuzz.py --examples 20000 --out /tmp/fuzz
    ...
    3 kind(s) of failure in 20000 example(s), 41.3 examples/s:
      [000] x12 convert-ros1: crash: ValueError: ... (txtool/dialects/translate.py:120)
"""

from __future__ import annotations

import argparse
import signal
import sys
import tempfile
import time
import traceback
import warnings
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from click.testing import CliRunner  # noqa: E402
from hypothesis import HealthCheck, given, seed, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from tests.hardening.fuzz_inputs import (  # noqa: E402
    COMMANDS,
    FuzzDocument,
    documents,
    extra_arguments,
    run_failure,
    write_inputs,
)
from txtool.cli import cli  # noqa: E402

HANG_LIMIT = 60  # seconds after which an example is abandoned as a hang


class Hang(BaseException):
    """Raised by the alarm; a BaseException so that CliRunner does not swallow it."""


@dataclass
class Kind:
    key: str
    summary: str
    count: int = 0
    saved: str = ""


@dataclass
class Tally:
    out: Path
    slow: float
    examples: int = 0
    kinds: dict[str, Kind] = field(default_factory=dict)

    def record(self, key: str, summary: str, command: str, argv: list[str],
               document: FuzzDocument, detail: str) -> None:
        kind = self.kinds.get(key)
        if kind is None:
            kind = self.kinds[key] = Kind(key, summary)
            stem = f"{len(self.kinds) - 1:03d}-{command}"
            (self.out / (stem + document.suffix)).write_bytes(document.data)
            (self.out / (stem + ".txt")).write_text(
                f"seed: {document.seed}\nsteps: {list(document.steps)}\n"
                f"command: txtool {' '.join(argv)}\n{summary}\n\n{detail}\n", encoding="utf-8")
            kind.saved = stem
            print(f"new failure [{stem}]: {summary}", flush=True)
        kind.count += 1


def innermost_txtool_frame(exc: BaseException) -> str:
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if "/txtool/" in f.filename]
    if not frames:
        return "outside txtool"
    last = frames[-1]
    return f"{last.filename[last.filename.rindex('/txtool/') + 1:]}:{last.lineno}"


def run_one(tally: Tally, command: str, document: FuzzDocument, extra: tuple[str, ...]) -> None:
    tally.examples += 1
    with tempfile.TemporaryDirectory() as folder:
        run = write_inputs(folder, command, document, extra)
        path, argv = run.path, run.argv
        signal.alarm(HANG_LIMIT)
        start = time.process_time()  # CPU time: other jobs on the machine do not count
        try:
            result = CliRunner().invoke(cli, argv, input=run.stdin, catch_exceptions=True)
        except Hang:
            tally.record(f"hang {command}", f"{command}: hang (> {HANG_LIMIT} s)", command,
                         argv, document, "")
            return
        finally:
            signal.alarm(0)
        elapsed = time.process_time() - start
    failure = run_failure(command, path, result)
    if failure is not None:
        exc = result.exception
        crashed = exc is not None and not isinstance(exc, SystemExit)
        where = innermost_txtool_frame(exc) if crashed else failure.split(":")[0]
        key = f"{type(exc).__name__ if crashed else command} {where}"
        detail = "".join(traceback.format_exception(exc)) if crashed else (
            f"exit {result.exit_code}\nstdout:\n{result.stdout[:3000]}\n"
            f"stderr:\n{result.stderr[:3000]}")
        tally.record(key, f"{command}: {failure} ({where})", command, argv, document, detail)
    elif elapsed > tally.slow:
        tally.record(f"slow {command}", f"{command}: slow ({elapsed:.1f} s)", command, argv,
                     document, "")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--examples", type=int, default=20_000)
    parser.add_argument("--seed", type=int, default=None)
    parser.add_argument("--command", action="append", choices=sorted(COMMANDS))
    parser.add_argument("--out", type=Path, default=Path("fuzz-out"))
    parser.add_argument("--slow", type=float, default=2.0)
    options = parser.parse_args()
    options.out.mkdir(parents=True, exist_ok=True)
    tally = Tally(options.out, options.slow)
    commands = options.command or sorted(COMMANDS)

    def on_alarm(signum, frame):
        raise Hang

    signal.signal(signal.SIGALRM, on_alarm)
    # As in the test suite (filterwarnings = error): a warning is output nobody asked for.
    warnings.simplefilter("error")
    for module in ("xacro", "pkg_resources"):
        warnings.filterwarnings("ignore", category=DeprecationWarning, module=module)

    @settings(max_examples=options.examples, deadline=None, database=None,
              suppress_health_check=list(HealthCheck), derandomize=False)
    @given(data=st.data(), command=st.sampled_from(commands), document=documents())
    def explore(data, command: str, document: FuzzDocument) -> None:
        run_one(tally, command, document, data.draw(extra_arguments(command, document)))

    if options.seed is not None:
        explore = seed(options.seed)(explore)
    start = time.perf_counter()
    explore()
    elapsed = time.perf_counter() - start
    print(f"{len(tally.kinds)} kind(s) of failure in {tally.examples} example(s), "
          f"{tally.examples / elapsed:.1f} examples/s:")
    for kind in sorted(tally.kinds.values(), key=lambda k: -k.count):
        print(f"  [{kind.saved}] x{kind.count} {kind.summary}")
    sys.exit(1 if tally.kinds else 0)


if __name__ == "__main__":
    main()
