#!/usr/bin/env bash
# Runs every libFuzzer harness in BUILD_DIR/fuzz for SECONDS each, side by side (`make fuzz`
# calls this): the whole run takes about SECONDS, however many harnesses there are.
#
#   fuzz/run.sh BUILD_DIR SECONDS
#
# Harness glint_fuzz_NAME starts from a copy of fuzz/corpus/NAME with fuzz/NAME.dict, in a
# scratch directory: nothing is written into the repository. Exits non-zero if any harness
# finds a crash, sanitizer report, leak, timeout or out-of-memory, and prints where the
# reproducers are. Environment:
#   FUZZ_WORKDIR  keep the corpora and artifacts here (NAME/corpus, NAME/artifacts, NAME.log)
#                 and reuse them next time, instead of a temporary directory
#   FUZZ_FLAGS    extra libFuzzer flags, e.g. "-fork=1 -ignore_crashes=1" for long runs that
#                 go on after a finding
# Reproduce a finding with BUILD_DIR/fuzz/glint_fuzz_NAME FILE; minimise it with
# -minimize_crash=1 -runs=10000 FILE.
set -euo pipefail

if [ $# -ne 2 ] || ! [[ $2 =~ ^[0-9]+$ ]]; then
    echo "usage: $0 BUILD_DIR SECONDS" >&2
    exit 2
fi
build=$1
seconds=$2
here=$(cd "$(dirname "$0")" && pwd)

fuzzers=()
for f in "$build"/fuzz/glint_fuzz_*; do
    [ -f "$f" ] && [ -x "$f" ] && fuzzers+=("$f")
done
if [ ${#fuzzers[@]} -eq 0 ]; then
    echo "fuzz: no harness in $build/fuzz (configure with -DGLINT_BUILD_FUZZERS=ON)" >&2
    exit 2
fi

if [ -n "${FUZZ_WORKDIR:-}" ]; then
    work=$FUZZ_WORKDIR
    mkdir -p "$work"
    keep=1
else
    work=$(mktemp -d "${TMPDIR:-/tmp}/glint-fuzz.XXXXXX")
    keep=0
fi

# UBSan is built not to recover; these make any report print its stack and stop the run.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

count() { find "$1" -type f | wc -l; }

# One harness: its report goes to $work/NAME.report, and NAME.failed exists if it found
# something.
fuzz_one() {
    local exe=$1 bin name corpus artifacts log dict before start status elapsed last execs rate found
    bin=$(basename "$exe")
    name=${bin#glint_fuzz_}
    corpus=$work/$name/corpus
    artifacts=$work/$name/artifacts
    log=$work/$name.log
    mkdir -p "$corpus" "$artifacts"
    if [ -d "$here/corpus/$name" ]; then cp -n "$here/corpus/$name"/* "$corpus"/; fi
    dict=()
    [ -f "$here/$name.dict" ] && dict=("-dict=$here/$name.dict")
    before=$(count "$artifacts")

    echo "fuzz: $bin for ${seconds}s, corpus $corpus ($(count "$corpus") inputs), log $log"
    exec >"$work/$name.report" 2>&1
    start=$(date +%s)
    status=0
    # shellcheck disable=SC2086  # FUZZ_FLAGS is a list of flags
    "$exe" "$corpus" "${dict[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
        -artifact_prefix="$artifacts/" -print_final_stats=1 ${FUZZ_FLAGS:-} \
        >"$log" 2>&1 || status=$?
    elapsed=$(($(date +%s) - start))

    # Figures: executions from the final stats (or the last status line in fork mode), and
    # the last line that reports coverage.
    last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -n 1 || true)
    execs=$(grep -oE 'stat::number_of_executed_units: [0-9]+' "$log" | tail -n 1 |
        grep -oE '[0-9]+$' || true)
    [ -z "$execs" ] && execs=$(echo "$last" | grep -oE '^#[0-9]+' | tr -d '#' || true)
    execs=${execs:-0}
    rate=$((execs / (elapsed > 0 ? elapsed : 1)))
    echo "fuzz: $bin: $execs executions in ${elapsed}s ($rate exec/s)," \
        "corpus now $(count "$corpus") inputs"
    echo "fuzz: $bin: final: ${last:-(no coverage line; see the log)}"

    found=$(count "$artifacts")
    if [ "$status" -ne 0 ] || [ "$found" -gt "$before" ]; then
        : >"$work/$name.failed"
        echo "fuzz: $bin: FINDING (exit status $status); the log is $log" >&2
        grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error|.*non-finite pixel|.*deadly signal|.*ALARM)' \
            "$log" | sort | uniq -c | head -n 20 >&2 || true
        find "$artifacts" -type f | sort | sed 's/^/fuzz: reproducer: /' >&2
    fi
}

for exe in "${fuzzers[@]}"; do
    rm -f "$work/$(basename "$exe" | sed 's/^glint_fuzz_//').failed"
    fuzz_one "$exe" &
done
wait
failed=0
for exe in "${fuzzers[@]}"; do
    name=$(basename "$exe")
    name=${name#glint_fuzz_}
    cat "$work/$name.report"
    if [ -e "$work/$name.failed" ]; then
        failed=1
        keep=1
    fi
done

if [ "$keep" -eq 1 ]; then
    echo "fuzz: corpora, artifacts and logs kept in $work"
else
    rm -rf "$work"
fi
exit "$failed"
