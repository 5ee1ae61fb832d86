#!/usr/bin/env bash
# The steps of the txtool GitHub Action (action.yml), kept in a script so they can be tested
# outside GitHub. Inputs come from the environment:
#   cache-key: TXTOOL_VERSION, TXTOOL_ACTION_REF (github.action_ref), RUNNER_OS
#   install:  TXTOOL_VERSION (pip requirement; empty: the action's checkout, TXTOOL_ACTION_PATH),
#             TXTOOL_CACHE (the folder action.yml caches between runs; default
#             ~/.cache/txtool-action)
#   every step: TXTOOL_PYTHON (the Python that builds and runs txtool; default python on PATH)
#             and TXTOOL_VENV (a virtual environment of txtool's own, made from it, which
#             install fills and validate runs; empty: the Python itself). action.yml gives
#             both, so the job's Python and its packages are left as they were.
#   validate: TXTOOL_PATHS (one path a line; see paths_of), TXTOOL_ARGS (options, split on
#             spaces), TXTOOL_SARIF (empty: no SARIF), TXTOOL_CONFIG (empty: the repository's
#             own configuration; on a pull request, the base commit's: see base_config),
#             TXTOOL_TRUST_XACRO (true or false, default false); GITHUB_EVENT_NAME and
#             GITHUB_EVENT_PATH (the base commit of a pull request)
# cache-key writes to GITHUB_OUTPUT the key and the prefix to restore the cache by.
# install uses uv where it is on PATH, else pip, each with its cache in TXTOOL_CACHE; the
# action's checkout is built into a wheel once per content (wheel_of), not on every run.
# validate writes workflow-command annotations (--format github) and, when asked, SARIF, in
# one run; its exit code is txtool's, also written to GITHUB_OUTPUT as exit-code. With
# GITHUB_STEP_SUMMARY set, the same run's JSON report becomes the job summary (job_summary).
# Paths are file names a pull request chooses: they go after "--", so that a file named
# "--exit-zero" is a file, and "-" becomes "./-" (after "--" txtool still reads "-" as stdin).
set -uo pipefail

PY="${TXTOOL_PYTHON:-python}"

# The cache's key: the runner's OS, the Python version and a digest of the version input and
# the action's ref (the cache refuses keys holding a comma, which a requirement may hold).
cache_key() {
    local prefix digest
    prefix="txtool-action-${RUNNER_OS:-local}-$("$PY" -c \
        'import sys; print("py%d.%d.%d" % sys.version_info[:3])')-" || return 2
    digest="$(printf '%s\n%s' "${TXTOOL_VERSION:-}" "${TXTOOL_ACTION_REF:-}" | "$PY" -c \
        'import hashlib, sys; print(hashlib.sha256(sys.stdin.buffer.read()).hexdigest()[:16])'
    )" || return 2
    if [ -n "${GITHUB_OUTPUT:-}" ]; then
        printf 'key=%s%s\nprefix=%s\n' "$prefix" "$digest" "$prefix" >> "$GITHUB_OUTPUT"
    fi
}

install() {
    local requirement="${TXTOOL_VERSION:-}" cache="${TXTOOL_CACHE:-$HOME/.cache/txtool-action}"
    case "$requirement" in
        -*) echo "txtool action: version: expected a requirement such as txtool==0.1.0," \
                 "got '$requirement'" >&2
            return 2 ;;
        "") requirement="$(wheel_of "${TXTOOL_ACTION_PATH:?TXTOOL_ACTION_PATH is not set}" \
                                    "$cache")" || return $? ;;
    esac
    local target
    target="$(target_python)" || return 2
    if command -v uv > /dev/null 2>&1; then
        UV_CACHE_DIR="$cache/uv" uv pip install --quiet --python "$target" \
            -- "$requirement"
    else
        PIP_CACHE_DIR="$cache/pip" "$target" -m pip install --quiet \
            --disable-pip-version-check -- "$requirement"
    fi
}

# The Python txtool is installed into: TXTOOL_VENV's, made from TXTOOL_PYTHON the first time;
# without TXTOOL_VENV, TXTOOL_PYTHON itself (or python on PATH).
target_python() {
    if [ -z "${TXTOOL_VENV:-}" ]; then
        command -v "$PY"
        return
    fi
    if [ ! -x "$TXTOOL_VENV/bin/python" ]; then
        "$PY" -m venv -- "$TXTOOL_VENV" >&2 || return 2
    fi
    printf '%s\n' "$TXTOOL_VENV/bin/python"
}

# The wheel of the checkout at $1, built once into a folder of $2/wheels named by a digest of
# what the wheel is made of (a cache restored from another version of the action holds other
# folders). Prints the wheel's path.
wheel_of() {
    local source="$1" cache="$2" wheels="$2/wheels" digest folder building
    digest="$("$PY" - "$source" <<'PYTHON'
import hashlib, sys
from pathlib import Path

root = Path(sys.argv[1])
digest = hashlib.sha256()
for top in ("pyproject.toml", "README.md", "LICENSE", "txtool", "fixtures", "schemas"):
    found = [root / top] if (root / top).is_file() else sorted((root / top).rglob("*"))
    for path in found:
        if path.is_file() and "__pycache__" not in path.parts:
            name = path.relative_to(root).as_posix().encode()
            digest.update(name + b"\0" + path.read_bytes() + b"\0")
print(digest.hexdigest())
PYTHON
)" || return 2
    folder="$wheels/$digest"
    if [ ! -d "$folder" ]; then
        mkdir -p "$wheels" && building="$(mktemp -d "$wheels/.building.XXXXXX")" || return 2
        PIP_CACHE_DIR="$cache/pip" "$PY" -m pip wheel \
            --quiet --disable-pip-version-check --no-deps --wheel-dir "$building" -- "$source" \
            >&2 || { rm -rf "$building"; return 2; }
        if [ -d "$folder" ]; then  # built meanwhile by another run sharing the cache
            rm -rf "$building"
        else
            mv "$building" "$folder" || return 2
        fi
    fi
    local wheel
    for wheel in "$folder"/txtool-*.whl; do
        [ -f "$wheel" ] || { echo "txtool action: no wheel built in $folder" >&2; return 2; }
        printf '%s\n' "$wheel"
        return 0
    done
}

# The paths input, one path a line (a path may hold spaces). A single line that names no
# existing file or folder is split on spaces, as the input was read before it took lines.
paths_of() {
    local text="${TXTOOL_PATHS:-}" line
    text="${text//$'\r'/}"
    if [[ "$text" != *$'\n'* ]]; then
        line="${text#"${text%%[![:space:]]*}"}"
        line="${line%"${line##*[![:space:]]}"}"
        if [ -n "$line" ] && [ ! -e "$line" ] && [ ! -L "$line" ]; then
            read -r -a paths <<< "$line"
            return
        fi
        text="$line"
    fi
    while IFS= read -r line; do
        line="${line#"${line%%[![:space:]]*}"}"
        line="${line%"${line##*[![:space:]]}"}"
        [ -z "$line" ] || paths+=("$line")
    done <<< "$text"
}

# A pull request's checkout holds the pull request's own configuration at its root, which
# could silence every finding: unless config: names a file, the base commit's configuration
# applies (its .txtool.toml, else its pyproject.toml with [tool.txtool], else the defaults).
# The base commit is read from the checkout, fetched (one commit) when it is not there; when
# it cannot be read the run stops with one line rather than use the pull request's.
base_config() {
    case "${GITHUB_EVENT_NAME:-}" in
        pull_request | pull_request_target) ;;
        *) return 0 ;;
    esac
    local base="" folder
    if [ -n "${GITHUB_EVENT_PATH:-}" ] && [ -f "$GITHUB_EVENT_PATH" ]; then
        base=$(python -c 'import json, sys; print(json.load(open(sys.argv[1]))["pull_request"]["base"]["sha"])' \
               "$GITHUB_EVENT_PATH" 2>/dev/null)
    fi
    if ! [[ "$base" =~ ^[0-9a-f]{40}([0-9a-f]{24})?$ ]]; then
        echo "txtool action: a pull request whose base commit is not in GITHUB_EVENT_PATH: set config: to the base branch's configuration (see docs/ci.md)" >&2
        return 2
    fi
    if ! git cat-file -e "$base^{commit}" 2>/dev/null \
            && ! git fetch --quiet --no-tags --depth=1 origin "$base" 2>/dev/null; then
        echo "txtool action: cannot read the pull request's base commit $base for its configuration: set config: to the base branch's configuration (see docs/ci.md)" >&2
        return 2
    fi
    folder=$(mktemp -d "${RUNNER_TEMP:-${TMPDIR:-/tmp}}/txtool-base.XXXXXX") || return 2
    if git show "$base:.txtool.toml" > "$folder/.txtool.toml" 2>/dev/null; then
        options+=(--config "$folder/.txtool.toml")
    elif git show "$base:pyproject.toml" > "$folder/pyproject.toml" 2>/dev/null \
            && grep -q '^[[:space:]]*\[tool\.txtool' "$folder/pyproject.toml"; then
        options+=(--config "$folder/pyproject.toml")
    else
        : > "$folder/.txtool.toml"  # the base has none: the defaults, not the pull request's
        options+=(--config "$folder/.txtool.toml")
    fi
}

validate() {
    local -a paths=() args options=()
    paths_of
    [ "${#paths[@]}" -gt 0 ] || paths=(.)
    local i
    for i in "${!paths[@]}"; do
        [ "${paths[$i]}" != "-" ] || paths[$i]="./-"
    done
    read -r -a args <<< "${TXTOOL_ARGS:-}"
    if [ -n "${TXTOOL_CONFIG:-}" ]; then
        options+=(--config "$TXTOOL_CONFIG")
    elif ! base_config; then
        record 2
        return 2
    fi
    case "${TXTOOL_TRUST_XACRO:-false}" in
        true) options+=(--trust-xacro) ;;
        false | "") ;;
        *) echo "txtool action: trust-xacro: expected true or false, got '$TXTOOL_TRUST_XACRO'" >&2
           record 2
           return 2 ;;
    esac
    local -a formats=(--format github)
    if [ -n "${TXTOOL_SARIF:-}" ]; then
        # One run: the annotations on stdout, the SARIF report written to its file.
        formats+=(--format "sarif:$TXTOOL_SARIF")
    fi
    local summary=""
    if [ -n "${GITHUB_STEP_SUMMARY:-}" ]; then
        summary="$(mktemp "${RUNNER_TEMP:-${TMPDIR:-/tmp}}/txtool-summary.XXXXXX")" || summary=""
        [ -z "$summary" ] || formats+=(--format "json:$summary")
    fi
    local code=0 txtool=txtool
    [ -z "${TXTOOL_VENV:-}" ] || txtool="$TXTOOL_VENV/bin/txtool"
    "$txtool" validate "${formats[@]}" "${options[@]}" "${args[@]}" -- "${paths[@]}" || code=$?
    record "$code"
    if [ -n "$summary" ]; then
        job_summary "$summary" "$code" >> "$GITHUB_STEP_SUMMARY"
        rm -f -- "$summary"
    fi
    return "$code"
}

# The job summary (Markdown) of the JSON report at $1 of a run that exited $2: the counts and
# a table of the findings (the first 100). Names and messages come from the files checked:
# Markdown's special characters are escaped, so no finding can forge a link or a heading.
job_summary() {
    "$PY" - "$1" "$2" <<'PYTHON'
import json, re, sys

def cell(text):
    text = " ".join(str(text).split())
    return re.sub(r"([\\`*_\[\]<>|~])", r"\\\1", text)

code = sys.argv[2]
try:
    with open(sys.argv[1], encoding="utf-8") as handle:
        report = json.load(handle)
except (OSError, ValueError):
    print(f"## txtool validate\n\nNo report (exit code {code}).\n")
    sys.exit(0)
totals = report["summary"]
problems = report["problems"]
print("## txtool validate\n")
print(f"{totals['errors']} errors, {totals['warnings']} warnings, {totals['infos']} infos "
      f"in {totals['files']} files; {len(report['unreadable'])} unreadable; exit code {code}.\n")
if problems:
    print("| Where | Severity | Rule | Message |")
    print("| --- | --- | --- | --- |")
    for p in problems[:100]:
        print(f"| {cell(p['path'])}:{p['line']}:{p['column']} | {p['severity']} | "
              f"{p['code']} {p['name']} | {cell(p['message'])} |")
    if len(problems) > 100:
        print(f"\n{len(problems) - 100} more findings: see the annotations or the SARIF report.")
for failure in report["unreadable"]:
    print(f"\n- {cell(failure['message'])}")
print()
PYTHON
}

record() {
    if [ -n "${GITHUB_OUTPUT:-}" ]; then
        echo "exit-code=$1" >> "$GITHUB_OUTPUT"
    fi
}

case "${1:-}" in
    cache-key) cache_key ;;
    install) install ;;
    validate) validate ;;
    *) echo "usage: $0 cache-key|install|validate" >&2; exit 2 ;;
esac
