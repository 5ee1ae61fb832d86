"""In-place writes keep the file's identity, or refuse.

``migrate --write`` and ``convert --write`` replace a file by renaming a new one over it (see
test_atomic_writes.py). The new file gets the old one's owner, group, mode, extended attributes
and ACLs; a file the user could not write is not replaced because its folder is writable; a
file with several hard links is refused (a rename would leave the other names on the old text).
The tests that change owners need root; the user's side runs in a forked process that has
dropped to ``nobody``.
"""

from __future__ import annotations

import os
import shutil
import stat
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from click.testing import CliRunner

import txtool.io.signals  # noqa: F401  (loaded before a fork drops privileges)
from tests.hardening.test_atomic_writes import ROBOT  # the same legacy arm
from txtool.cli import cli
from txtool.io.xmlio import InputError, write_atomic

NOBODY = 65534
as_root = pytest.mark.skipif(os.geteuid() != 0, reason="changing owners needs root")


def migrate(path: Path) -> tuple[int, str]:
    result = CliRunner().invoke(cli, ["migrate", "--write", str(path)], catch_exceptions=False)
    return result.exit_code, result.stderr


def _identity(path: Path) -> tuple[int, int, int, dict[str, bytes]]:
    status = os.stat(path)
    xattrs = {name: os.getxattr(path, name) for name in os.listxattr(path)}
    return status.st_uid, status.st_gid, stat.S_IMODE(status.st_mode), xattrs


def _acl(*entries: tuple[int, int, int]) -> bytes:
    """A POSIX ACL as Linux stores it in ``system.posix_acl_access`` (version 2)."""
    data = (2).to_bytes(4, "little")
    for tag, permissions, ident in entries:
        data += tag.to_bytes(2, "little") + permissions.to_bytes(2, "little")
        data += ident.to_bytes(4, "little")
    return data


ANY = 0xFFFFFFFF
# user::rw-, user:1234:rw-, group::r--, mask::rw-, other::r--
ACL = _acl((0x01, 6, ANY), (0x02, 6, 1234), (0x04, 4, ANY), (0x10, 6, ANY), (0x20, 4, ANY))


@as_root
def test_owner_group_and_mode_are_kept(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_bytes(ROBOT)
    os.chown(path, 1234, 5678)
    path.chmod(0o2640)
    before = _identity(path)
    assert migrate(path)[0] == 0
    assert path.read_bytes() != ROBOT
    assert _identity(path) == before


def test_extended_attributes_and_acls_are_kept(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_bytes(ROBOT)
    try:
        os.setxattr(path, "user.origin", b"vendor drop 2024-03")
        os.setxattr(path, "system.posix_acl_access", ACL)
    except OSError as exc:
        pytest.skip(f"this file system keeps no extended attributes or ACLs: {exc}")
    before = _identity(path)
    assert migrate(path)[0] == 0
    assert path.read_bytes() != ROBOT
    assert _identity(path) == before
    assert os.getxattr(path, "system.posix_acl_access") == ACL


def test_a_hard_linked_file_is_refused_and_every_name_keeps_its_text(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_bytes(ROBOT)
    os.link(path, tmp_path / "copy.urdf")
    assert migrate(path) == (2, (
        f"txtool: {path}: has 2 hard links; replacing it would leave the other names with the "
        "old text, so it is not written (copy the file to break the link)\n"
        "1 file(s) could not be read or written\n"))
    assert path.read_bytes() == ROBOT == (tmp_path / "copy.urdf").read_bytes()
    assert path.stat().st_ino == (tmp_path / "copy.urdf").stat().st_ino


def as_nobody(function: Callable[[], None]) -> str:
    """Run ``function`` in a fork that has become ``nobody``; what it raised, or ''."""
    reader, writer = os.pipe()
    pid = os.fork()
    if pid == 0:  # pragma: no cover (runs in the fork)
        message = ""
        try:
            os.setgroups([])
            os.setgid(NOBODY)
            os.setuid(NOBODY)
            function()
        except BaseException as exc:
            message = f"{type(exc).__name__}: {exc}"
        finally:
            os.write(writer, message.encode())
            os._exit(0)
    os.close(writer)
    with os.fdopen(reader, "rb") as stream:
        outcome = stream.read().decode()
    os.waitpid(pid, 0)
    return outcome


@pytest.fixture
def shared() -> Iterator[Path]:
    """A folder anyone may write in (as a shared checkout or /tmp is), outside pytest's
    private temporary folders, which ``nobody`` cannot enter."""
    if os.geteuid() != 0:
        pytest.skip("needs root, to act as another user")
    folder = Path(tempfile.mkdtemp(prefix="txtool-shared-"))
    folder.chmod(0o777)
    yield folder
    shutil.rmtree(folder)


@pytest.mark.parametrize(("owner", "mode", "reason"), [
    (0, 0o644, "permission denied (the file is read-only for you; its folder being writable "
               "is not enough)"),
    (NOBODY, 0o444, "permission denied (the file is read-only for you; its folder being "
                    "writable is not enough)"),
    (0, 0o666, f"the file belongs to user 0, group {NOBODY}, which a replacement written by "
               "you could not keep"),
])
def test_a_file_the_user_may_not_keep_as_it_is_is_not_replaced(shared, owner, mode, reason):
    path = shared / "robot.urdf"
    path.write_bytes(ROBOT)
    os.chown(path, owner, NOBODY)
    path.chmod(mode)
    before = (_identity(path), path.stat().st_ino)
    outcome = as_nobody(lambda: write_atomic(str(path), b"<robot/>\n"))
    assert outcome == f"{InputError.__name__}: {path}: cannot write: {reason}"
    assert path.read_bytes() == ROBOT
    assert (_identity(path), path.stat().st_ino) == before
    assert [p.name for p in shared.iterdir()] == ["robot.urdf"]


def test_the_owner_replaces_their_own_file(shared):
    path = shared / "robot.urdf"
    path.write_bytes(ROBOT)
    os.chown(path, NOBODY, NOBODY)
    path.chmod(0o640)
    before = _identity(path)
    assert as_nobody(lambda: write_atomic(str(path), b"<robot/>\n")) == ""
    assert path.read_bytes() == b"<robot/>\n"
    assert _identity(path) == before
