"""Ctrl-C and SIGTERM: one line, exit 130 or 143, and nothing half-written left behind.

Each test runs the real entry point (``txtool.cli.main``) in a fresh interpreter. A write is
made to wait (its ``fsync`` blocks after leaving a mark) so that the signal lands while the
temporary file exists; without a handler SIGTERM kills the process there and leaves it.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from tests.conftest import neutral

ROOT = Path(__file__).resolve().parents[2]
DEMO = (ROOT / "fixtures" / "demo_robot.urdf").read_bytes()
# Read at import, before the suite's neutral environment (tests/conftest.py) applies.
ENV = {**neutral(os.environ), "PYTHONPATH": str(ROOT)}


def as_from_a_terminal() -> None:
    """In the child, before Python starts: Ctrl-C as a terminal leaves it. A runner that
    ignores it (a background job) would hand the ignoring down, and Python would then not
    install its handler, which the tests below tell txtool's own handler from."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def program(sabotage: str) -> str:
    return textwrap.dedent(sabotage) + textwrap.dedent("""
        import sys
        from txtool.cli import main
        sys.argv = ["txtool", *sys.argv[1:]]
        main()
    """)


def txtool_with(sabotage: str, *args: str, cwd: Path) -> tuple[int, str, str]:
    result = subprocess.run([sys.executable, "-c", program(sabotage), *args], cwd=cwd,
                            capture_output=True, text=True, timeout=120, env=ENV,
                            preexec_fn=as_from_a_terminal)
    return result.returncode, result.stdout, result.stderr


SLOW_FSYNC = """
import os, time
real_fsync = os.fsync

def fsync(handle):
    open("writing", "w").close()  # the temporary file exists and holds the data
    time.sleep(60)
    real_fsync(handle)

os.fsync = fsync
"""


@pytest.mark.parametrize(("number", "code", "line"), [
    (signal.SIGTERM, 143, "txtool: terminated\n"),
    (signal.SIGINT, 130, "txtool: interrupted\n"),
])
@pytest.mark.parametrize("command", [
    ["convert", "demo.urdf", "--to", "ros2-p2", "-o", "out.urdf"],
    ["convert", "demo.urdf", "--to", "ros2-p2", "-o", "demo.urdf", "--write"],
    ["migrate", "--write", "--to", "ros2-p2", "--allow-lossy", "demo.urdf"],
])
def test_a_signal_during_a_write_leaves_no_temporary_file(tmp_path, command, number, code,
                                                           line):
    (tmp_path / "demo.urdf").write_bytes(DEMO)
    (tmp_path / "out.urdf").write_bytes(b"<robot name='previous'/>\n")
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    process = subprocess.Popen([sys.executable, "-c", program(SLOW_FSYNC), *command],
                               cwd=tmp_path, env=ENV, preexec_fn=as_from_a_terminal,
                               stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not (tmp_path / "writing").exists():
        assert process.poll() is None and time.monotonic() < deadline, process.communicate()
        time.sleep(0.02)
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".txtool-")]
    process.send_signal(number)
    out, err = process.communicate(timeout=60)
    (tmp_path / "writing").unlink()
    assert (process.returncode, out, err) == (code, "", line)
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


# Ctrl-C while the command starts. The program is the console script pip writes for
# `[project.scripts] txtool = "txtool.cli:main"`, with a trap in front: an import hook that
# marks the moment the import of a given module begins, once txtool's first handler is in place
# (before that, a signal lands in Python's own start-up or in site's .pth files, where only
# Python's traceback is possible), and then holds that import for a while. The signal is sent
# after the mark, so it lands in txtool's loading, deterministically.
CONSOLE_SCRIPT = """\
import os, signal, sys, time

class Trap:
    def find_spec(self, name, path=None, target=None):
        armed = signal.getsignal(signal.SIGINT) is not signal.default_int_handler
        if armed and name in {pause!r}:
            sys.meta_path.remove(self)
            open("armed", "w").close()
            time.sleep({hold})
        return None

sys.meta_path.insert(0, Trap())
{start}
"""
CONSOLE_START = """\
from txtool.cli import main
if __name__ == '__main__':
    sys.exit(main())
"""
MODULE_START = """\
import runpy
sys.argv[0], sys.orig_argv = "-m", [sys.executable, "-m", "txtool", *sys.argv[1:]]
runpy.run_module("txtool", run_name="__main__", alter_sys=True)
"""


def start_txtool(tmp_path: Path, *args: str, pause: set[str], hold: float,
                 start: str = CONSOLE_START) -> subprocess.Popen[str]:
    """The command, started; returns once the trap has marked the import in ``pause``."""
    script = tmp_path / "bin" / "txtool"  # argv[0] as the console script's
    script.parent.mkdir(exist_ok=True)
    script.write_text(CONSOLE_SCRIPT.format(pause=pause, hold=hold, start=start))
    process = subprocess.Popen([sys.executable, str(script), *args], cwd=tmp_path, env=ENV,
                               preexec_fn=as_from_a_terminal,
                               stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not (tmp_path / "armed").exists():
        assert process.poll() is None and time.monotonic() < deadline, process.communicate()
        time.sleep(0.005)
    return process


def interrupted(process: subprocess.Popen[str], delay: float = 0.0) -> tuple[int, str, str]:
    time.sleep(delay)
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=60)
    return process.returncode, out, err


# Where the command is held (each is imported while `txtool <command>` starts).
LOADING = {
    # (not a module of the standard library: coverage's subprocess start-up imports those first)
    "importing txtool's command line": (["--version"], "txtool.cli"),
    "importing click": (["--version"], "click"),
    "importing lxml": (["validate", "-"], "lxml"),
    "importing rich": (["show", "demo.urdf"], "rich"),
    "importing pydantic": (["schema"], "pydantic"),
    "loading a command": (["show", "demo.urdf"], "txtool.commands.show"),
}


@pytest.mark.parametrize("moment", LOADING)
def test_ctrl_c_while_the_command_loads_is_one_line_and_exit_130(tmp_path, moment):
    args, module = LOADING[moment]
    (tmp_path / "demo.urdf").write_bytes(DEMO)
    process = start_txtool(tmp_path, *args, pause={module}, hold=60)
    assert interrupted(process) == (130, "", "txtool: interrupted\n")


def test_ctrl_c_while_python_m_txtool_loads_is_one_line_and_exit_130(tmp_path):
    process = start_txtool(tmp_path, "show", "-", pause={"click"}, hold=60, start=MODULE_START)
    assert interrupted(process) == (130, "", "txtool: interrupted\n")


@pytest.mark.parametrize("delay_ms", [0, 5, 10, 20, 40, 80, 160])
def test_ctrl_c_at_any_moment_after_txtool_starts_is_one_line_and_exit_130(tmp_path, delay_ms):
    """The trap marks the first import after txtool's handler is in place and lets it go on;
    the signal comes ``delay_ms`` later: in the package, in click, lxml or rich, in the command
    or while it reads its input (stdin stays open, so it never finishes first)."""
    process = start_txtool(tmp_path, "show", "-", pause={"txtool.cli"}, hold=0)
    assert interrupted(process, delay_ms / 1000) == (130, "", "txtool: interrupted\n")


def test_importing_txtool_as_a_library_leaves_ctrl_c_alone():
    program = ("import signal, txtool.cli; "
               "print(signal.getsignal(signal.SIGINT) is signal.default_int_handler)")
    result = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                            env=ENV, timeout=120, preexec_fn=as_from_a_terminal)
    assert (result.returncode, result.stdout, result.stderr) == (0, "True\n", "")


def test_a_library_that_turns_ctrl_c_into_an_error_still_exits_130(tmp_path):
    """Some imports catch the interrupt and raise their own error: not an internal error."""
    sabotage = """
        import os, signal
        import txtool.dialects.read

        def read_source(source, **options):
            try:
                os.kill(os.getpid(), signal.SIGINT)
            except BaseException:
                raise ImportError("module failed to load") from None

        txtool.dialects.read.read_source = read_source
    """
    (tmp_path / "demo.urdf").write_bytes(DEMO)
    assert txtool_with(sabotage, "show", "demo.urdf", cwd=tmp_path) == (
        130, "", "txtool: interrupted\n")


def test_a_signal_inside_an_event_loops_callback_ends_the_process_once_the_callback_is_done():
    """asyncio catches what a callback raises and logs it, and the loop goes on: a signal
    raised there would be lost (``txtool lsp`` went on serving, with a traceback on stderr). It
    ends the process from the loop instead, after the callback's clean-up has run."""
    program = textwrap.dedent("""
        import asyncio, os, signal, time
        from txtool.io import signals

        def handler():
            try:
                os.kill(os.getpid(), signal.SIGTERM)
                time.sleep(0.2)
            finally:
                print("cleaned up", flush=True)

        async def serve():
            asyncio.get_running_loop().call_soon(handler)
            await asyncio.sleep(60)

        signals.stop_on_signals()
        asyncio.run(serve())
    """)
    result = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                            env=ENV, timeout=30)
    assert (result.returncode, result.stdout, result.stderr) == (
        143, "cleaned up\n", "txtool: terminated\n")


def threads_of(pid: int) -> dict[int, tuple[str, str, set[int]]]:
    """Each thread of process ``pid`` (Linux): its state, where it sleeps in the kernel
    (``wchan``, "0" where the kernel does not say) and which of SIGINT and SIGTERM it blocks."""
    threads = {}
    for task in Path(f"/proc/{pid}/task").iterdir():
        try:
            status = (task / "status").read_text()
            wchan = (task / "wchan").read_text().strip() if (task / "wchan").exists() else "0"
        except FileNotFoundError:  # the thread ended meanwhile
            continue
        fields = dict(line.split(":", 1) for line in status.splitlines() if ":" in line)
        mask = int(fields["SigBlk"], 16)
        threads[int(task.name)] = (fields["State"].split()[0], wchan or "0", {
            number for number in (signal.SIGINT, signal.SIGTERM) if mask >> (number - 1) & 1})
    return threads


def wait_until_it_waits_for_its_editor(process: subprocess.Popen[str]) -> None:
    """Until the language server has answered and has nothing left to do: every thread asleep,
    and its reading thread in a read of standard input where the kernel says where it sleeps
    (an editor that says nothing leaves it so). Without /proc, its answer is the sign."""
    if not Path("/proc/self/task").is_dir():
        return
    deadline = time.monotonic() + 60
    while True:
        threads = threads_of(process.pid)
        asleep = len(threads) > 1 and all(state == "S" for state, _, _ in threads.values())
        kernel_says = [wchan for _, wchan, _ in threads.values() if wchan != "0"]
        if asleep and (not kernel_says or any("pipe_read" in w for w in kernel_says)):
            return
        assert process.poll() is None and time.monotonic() < deadline, threads
        time.sleep(0.005)


def serving(tmp_path: Path) -> subprocess.Popen[str]:
    """``txtool lsp`` on standard input, once it has answered a request and waits for the next."""
    process = subprocess.Popen([sys.executable, "-m", "txtool", "lsp"], cwd=tmp_path, env=ENV,
                               preexec_fn=as_from_a_terminal,
                               stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    try:
        request = '{"jsonrpc":"2.0","id":1,"method":"shutdown"}'
        process.stdin.write(f"Content-Length: {len(request)}\r\n\r\n{request}")
        process.stdin.flush()
        process.stdout.readline()  # the answer's header: the server is serving
        wait_until_it_waits_for_its_editor(process)
    except BaseException:
        process.kill()
        raise
    return process


@pytest.mark.parametrize(("number", "code", "line"), [
    (signal.SIGTERM, 143, "txtool: terminated\n"),
    (signal.SIGINT, 130, "txtool: interrupted\n"),
])
def test_the_language_server_on_standard_input_ends_on_a_signal_while_its_editor_is_there(
        tmp_path, number, code, line):
    """The server reads its standard input in a thread; a normal exit waits for that thread,
    so a signal while the editor holds the pipe open must not end by the usual unwinding."""
    pytest.importorskip("pygls")
    with serving(tmp_path) as process:
        process.send_signal(number)
        try:
            returncode = process.wait(timeout=30)
        except subprocess.TimeoutExpired:  # where each thread is, to tell why
            where = threads_of(process.pid) if Path("/proc/self/task").is_dir() else "?"
            pytest.fail(f"still running 30 s after the signal; its threads: {where}")
        finally:
            process.kill()
            process.stdin.close()
        err = process.stderr.read()
    assert (returncode, err) == (code, line)


def test_outside_a_running_event_loop_the_signal_is_raised_where_the_program_is():
    import asyncio  # imported, as in txtool lsp before its loop starts, but not running

    from txtool.io import signals

    with pytest.raises(RuntimeError):
        asyncio.get_running_loop()
    before = signals._State.received
    try:
        signals._State.received = None
        with pytest.raises(signals.Stopped) as stop:
            signals._on_signal(signal.SIGTERM, None)
        assert stop.value.exit_code == 143
    finally:
        signals._State.received = before


@pytest.mark.skipif(not Path("/proc/self/task").is_dir(), reason="reads /proc (Linux)")
def test_the_language_servers_reading_thread_leaves_the_signals_to_the_main_thread(tmp_path):
    """The system may deliver a signal to any thread that does not block it; one delivered to
    the thread reading standard input would wait for the main thread, asleep in its event
    loop: the server would not end. Every thread but the main one blocks SIGINT and SIGTERM."""
    pytest.importorskip("pygls")
    with serving(tmp_path) as process:  # its reading thread waiting for the next message
        blocked = {tid: masked for tid, (_, _, masked) in threads_of(process.pid).items()}
        process.kill()
        process.stdin.close()
    others = [tid for tid in blocked if tid != process.pid]
    assert others and all(blocked[tid] == {signal.SIGINT, signal.SIGTERM} for tid in others)
    assert blocked[process.pid] == set()
