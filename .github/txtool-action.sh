#!/usr/bin/env bash
# The steps of the txtool GitHub Action (action.yml), kept in a script so they can be tested
# outside GitHub. Inputs come from the environment:
#   install:  TXTOOL_VERSION (pip requirement; empty: the action's checkout, TXTOOL_ACTION_PATH)
#   validate: TXTOOL_PATHS (one path a line; see paths_of), TXTOOL_ARGS (options, split on
#             spaces), TXTOOL_SARIF (empty: no SARIF), TXTOOL_CONFIG (empty: the repository's
#             own configuration), TXTOOL_TRUST_XACRO (true or false, default false)
# validate writes workflow-command annotations (--format github) and, when asked, SARIF; its
# exit code is txtool's, also written to GITHUB_OUTPUT as exit-code.
# Paths are file names a pull request chooses: they go after "--", so that a file named
# "--exit-zero" is a file, and "-" becomes "./-" (after "--" txtool still reads "-" as stdin).
set -uo pipefail

install() {
    local requirement="${TXTOOL_VERSION:-}"
    if [ -z "$requirement" ]; then
        requirement="${TXTOOL_ACTION_PATH:?TXTOOL_ACTION_PATH is not set}"
    fi
    python -m pip install --quiet --disable-pip-version-check "$requirement"
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
    fi
    case "${TXTOOL_TRUST_XACRO:-false}" in
        true) options+=(--trust-xacro) ;;
        false | "") ;;
        *) echo "txtool action: trust-xacro: expected true or false, got '$TXTOOL_TRUST_XACRO'" >&2
           record 2
           return 2 ;;
    esac
    local code=0 sarif=0
    if [ -n "${TXTOOL_SARIF:-}" ]; then
        # --exit-zero: only files that could not be read (recorded in the SARIF too) or a
        # report that could not be written end it non-zero; the annotations run either way.
        txtool validate --format sarif --exit-zero --output "$TXTOOL_SARIF" \
            "${options[@]}" "${args[@]}" -- "${paths[@]}" || sarif=$?
    fi
    txtool validate --format github "${options[@]}" "${args[@]}" -- "${paths[@]}" || code=$?
    if [ "$code" -lt 2 ] && [ "$sarif" -ne 0 ]; then
        code=$sarif
    fi
    record "$code"
    return "$code"
}

record() {
    if [ -n "${GITHUB_OUTPUT:-}" ]; then
        echo "exit-code=$1" >> "$GITHUB_OUTPUT"
    fi
}

case "${1:-}" in
    install) install ;;
    validate) validate ;;
    *) echo "usage: $0 install|validate" >&2; exit 2 ;;
esac
