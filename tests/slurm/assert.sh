# Assertions for the shell tests of tests/slurm/ (sourced, bash). Each failed check prints
# what was expected and what came, and counts; finish reports and sets the exit code.

CHECKS=0
FAILURES=0

# run CMD...: runs CMD with a 60 s limit, keeping its exit code in RC, stdout in OUT and stderr
# in ERR.
run() {
    local out_file err_file
    out_file=$(mktemp) err_file=$(mktemp)
    timeout 60 "$@" >"$out_file" 2>"$err_file"
    RC=$?
    OUT=$(cat "$out_file") ERR=$(cat "$err_file")
    rm -f "$out_file" "$err_file"
}

check() {  # check DESCRIPTION CONDITION...: passes when CONDITION (a command) succeeds
    local what=$1
    shift
    CHECKS=$((CHECKS + 1))
    if ! "$@"; then
        FAILURES=$((FAILURES + 1))
        echo "FAILED: $what" >&2
        return 1
    fi
}

check_eq() {  # check_eq DESCRIPTION EXPECTED ACTUAL
    CHECKS=$((CHECKS + 1))
    if [ "$2" != "$3" ]; then
        FAILURES=$((FAILURES + 1))
        printf 'FAILED: %s\n  expected: %s\n  actual:   %s\n' "$1" "$2" "$3" >&2
        return 1
    fi
}

check_contains() {  # check_contains DESCRIPTION HAYSTACK NEEDLE
    CHECKS=$((CHECKS + 1))
    if [[ $2 != *"$3"* ]]; then
        FAILURES=$((FAILURES + 1))
        printf 'FAILED: %s\n  expected to contain: %s\n  actual: %s\n' "$1" "$3" "$2" >&2
        return 1
    fi
}

check_rc() {  # check_rc DESCRIPTION EXPECTED_RC: the last run's exit code (stderr shown if not)
    CHECKS=$((CHECKS + 1))
    if [ "$RC" != "$2" ]; then
        FAILURES=$((FAILURES + 1))
        printf 'FAILED: %s: exit code %s, expected %s\n  stdout: %s\n  stderr: %s\n' \
            "$1" "$RC" "$2" "$OUT" "$ERR" >&2
        return 1
    fi
}

finish() {
    if [ "$FAILURES" -gt 0 ]; then
        echo "$FAILURES of $CHECKS checks failed" >&2
        return 1
    fi
    echo "all $CHECKS checks passed"
}
