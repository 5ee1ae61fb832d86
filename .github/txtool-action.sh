#!/usr/bin/env bash
# The steps of the txtool GitHub Action (action.yml), kept in a script so they can be tested
# outside GitHub. Inputs come from the environment:
#   install:  TXTOOL_VERSION (pip requirement; empty: the action's checkout, TXTOOL_ACTION_PATH)
#   validate: TXTOOL_PATHS, TXTOOL_ARGS (split on spaces), TXTOOL_SARIF (empty: no SARIF)
# validate writes workflow-command annotations (--format github) and, when asked, SARIF; its
# exit code is txtool's, also written to GITHUB_OUTPUT as exit-code.
set -uo pipefail

install() {
    local requirement="${TXTOOL_VERSION:-}"
    if [ -z "$requirement" ]; then
        requirement="${TXTOOL_ACTION_PATH:?TXTOOL_ACTION_PATH is not set}"
    fi
    python -m pip install --quiet --disable-pip-version-check "$requirement"
}

validate() {
    local -a paths args
    read -r -a paths <<< "${TXTOOL_PATHS:-.}"
    read -r -a args <<< "${TXTOOL_ARGS:-}"
    [ "${#paths[@]}" -gt 0 ] || paths=(.)
    local code=0
    if [ -n "${TXTOOL_SARIF:-}" ]; then
        txtool validate --format sarif --exit-zero --output-file "$TXTOOL_SARIF" \
            "${args[@]}" "${paths[@]}" || code=$?
        if [ "$code" -ne 0 ]; then
            record "$code"
            return "$code"
        fi
    fi
    txtool validate --format github "${args[@]}" "${paths[@]}" || code=$?
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
