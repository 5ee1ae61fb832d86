"""The Action's configuration on a pull request is the base commit's, never the pull
request's own: a ``.txtool.toml`` the pull request adds or edits at the root to silence every
finding does not apply unless ``config:`` names it. Each test runs the Action's validate step
on a real git history: the base commit, then the pull request's commit checked out."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from tests.lint.conftest import BROKEN
from tests.lint.test_ci_integration import action_step

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
SILENCE = 'ignore = ["ALL"]\n'
GIT_ENV = {"GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@example.com",
           "GIT_COMMITTER_NAME": "t", "GIT_COMMITTER_EMAIL": "t@example.com",
           "GIT_CONFIG_GLOBAL": os.devnull, "GIT_CONFIG_NOSYSTEM": "1"}


def git(repo: Path, *args: str) -> str:
    done = subprocess.run(["git", *args], cwd=repo, env={**os.environ, **GIT_ENV},
                          capture_output=True, text=True, check=True, timeout=60)
    return done.stdout.strip()


def history(tmp_path: Path, base: dict[str, str], head: dict[str, str]) -> tuple[Path, str]:
    """A repository whose base commit holds ``base`` (with a broken robot) and whose checked
    out pull request commit writes ``head`` over it; (its folder, the base's hash)."""
    repo = tmp_path / "repo"
    (repo / "urdf").mkdir(parents=True)
    (repo / "urdf" / "broken.urdf").write_text(BROKEN)
    git(repo, "init", "-q")
    for name, text in base.items():
        (repo / name).write_text(text)
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "base")
    sha = git(repo, "rev-parse", "HEAD")
    for name, text in head.items():
        (repo / name).write_text(text)
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "pull request")
    return repo, sha


def pull_request(tmp_path: Path, repo: Path, sha: str | None, **inputs: str
                 ) -> tuple[int, set[str], str]:
    event = tmp_path / "event.json"
    event.write_text(json.dumps({"pull_request": {"base": {"sha": sha}}} if sha else {}))
    done = action_step("validate", repo, TXTOOL_PATHS="urdf", GITHUB_EVENT_NAME="pull_request",
                       GITHUB_EVENT_PATH=str(event), RUNNER_TEMP=str(tmp_path), **inputs)
    codes = set(re.findall(r"title=(TX\d+)", done.stdout))
    return done.returncode, codes, done.stderr


def test_a_configuration_the_pull_request_adds_does_not_apply(tmp_path: Path):
    repo, sha = history(tmp_path, {}, {".txtool.toml": SILENCE})
    assert pull_request(tmp_path, repo, sha)[:2] == (1, {"TX102", "TX106"})


def test_the_base_commit_s_configuration_applies_not_the_pull_request_s_edit(tmp_path: Path):
    repo, sha = history(tmp_path, {".txtool.toml": 'ignore = ["TX102"]\n'},
                        {".txtool.toml": SILENCE})
    assert pull_request(tmp_path, repo, sha)[:2] == (1, {"TX106"})


def test_the_base_commit_s_pyproject_table_applies(tmp_path: Path):
    repo, sha = history(tmp_path, {"pyproject.toml": '[tool.txtool]\nignore = ["TX102"]\n'},
                        {"pyproject.toml": f"[tool.txtool]\n{SILENCE}"})
    assert pull_request(tmp_path, repo, sha)[:2] == (1, {"TX106"})


def test_config_named_by_the_workflow_applies(tmp_path: Path):
    repo, sha = history(tmp_path, {}, {".txtool.toml": SILENCE})
    pinned = tmp_path / "pinned.toml"
    pinned.write_text(SILENCE)
    assert pull_request(tmp_path, repo, sha, TXTOOL_CONFIG=str(pinned))[:2] == (0, set())


def test_on_a_push_the_checkout_s_configuration_applies(tmp_path: Path):
    repo, _ = history(tmp_path, {}, {".txtool.toml": SILENCE})
    done = action_step("validate", repo, TXTOOL_PATHS="urdf", GITHUB_EVENT_NAME="push")
    assert (done.returncode, done.stdout) == (0, "")


@pytest.mark.parametrize("sha", [None, "0" * 40, "not-a-commit; touch pwned"])
def test_a_base_commit_that_cannot_be_read_stops_the_run_in_one_line(tmp_path: Path,
                                                                     sha: str | None):
    repo, _ = history(tmp_path, {}, {".txtool.toml": SILENCE})
    code, codes, err = pull_request(tmp_path, repo, sha)
    assert (code, codes) == (2, set()) and len(err.splitlines()) == 1, err
    assert err.startswith("txtool action: ") and "set config:" in err
    assert not (repo / "pwned").exists()
