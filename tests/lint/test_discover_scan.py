"""The folder walk of validate: os.walk's order and pruning, with each entry's link-ness."""

from __future__ import annotations

import os

from txtool.lint.discover import scan


def tree(tmp_path):
    for folder in ("a/b", "a/c", "d", "skip/deep"):
        (tmp_path / folder).mkdir(parents=True)
    for name in ("a/b/x.urdf", "a/y.xacro", "d/z.txt", "top.urdf", "skip/deep/w.urdf"):
        (tmp_path / name).write_text("<robot/>")
    (tmp_path / "linked_folder").symlink_to(tmp_path / "a")  # listed, not entered
    (tmp_path / "a" / "linked.urdf").symlink_to(tmp_path / "top.urdf")
    (tmp_path / "dangling.urdf").symlink_to(tmp_path / "missing")
    return str(tmp_path)


def named(walk):
    for root, dirs, files in walk:
        names = sorted(d if isinstance(d, str) else d.name for d in dirs)
        dirs[:] = [d for d in sorted(dirs, key=lambda d: getattr(d, "name", d))
                   if getattr(d, "name", d) != "skip"]
        yield root, names, sorted(f if isinstance(f, str) else f.name for f in files)


def test_scan_walks_as_os_walk_does_with_pruning(tmp_path):
    top = tree(tmp_path)
    assert list(named(scan(top))) == list(named(os.walk(top)))
    assert any(root.endswith("linked_folder") for root, _, _ in os.walk(top, followlinks=True))


def test_entries_know_their_paths_and_links(tmp_path):
    top = tree(tmp_path)
    entries = {entry.path: entry for _, dirs, files in scan(top) for entry in dirs + files}
    assert entries[os.path.join(top, "linked_folder")].is_symlink()
    assert entries[os.path.join(top, "a", "linked.urdf")].is_symlink()
    assert entries[os.path.join(top, "dangling.urdf")].is_symlink()
    assert not entries[os.path.join(top, "top.urdf")].is_symlink()
    assert os.path.join(top, "a", "b", "x.urdf") in entries
