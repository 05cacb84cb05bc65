#!/usr/bin/env bash
# Start-up: whole runs of the glint program, where the time of a small scene is mostly the
# program's own start (loading its libraries, their static constructors): `glint --version`,
# `glint --check` of a course scene and its render. Each binary given runs in turn with the
# others (so a busy machine slows all alike), RUNS times; prints the median wall time and the
# median peak memory (resident set) of each.
#
#   bench/startup.sh build/glint OTHER/glint ...     (RUNS=9 by default)
#
# docs/performance.md, "Start-up", has the figures and the builds they compare.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${RUNS:-9}
scene=${SCENE:-$root/../shared/scenes/cse167x/scene7.test}
[ -f "$scene" ] || scene=$root/scenes/demo.test
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cases=("--version" "-q --check $scene" "-q -t 2 $scene -o $out/image.png")
names=("--version" "--check $(basename "$scene")" "-t 2 $(basename "$scene")")

median() { sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }

printf '%-22s' case
for bin in "$@"; do printf ' %30s' "$bin"; done
echo
for c in "${!cases[@]}"; do
    read -r -a args <<<"${cases[$c]}"
    declare -A times=() memory=()
    for ((r = 0; r < runs; ++r)); do
        for b in "$@"; do
            start=$(date +%s%N)
            /usr/bin/time -f %M -o "$out/rss" "$b" "${args[@]}" >/dev/null
            end=$(date +%s%N)
            times[$b]+="$(((end - start) / 1000)) "
            memory[$b]+="$(tail -1 "$out/rss") "
        done
    done
    printf '%-22s' "${names[$c]}"
    for b in "$@"; do
        t=$(tr ' ' '\n' <<<"${times[$b]}" | grep . | median)
        m=$(tr ' ' '\n' <<<"${memory[$b]}" | grep . | median)
        printf ' %19.3f s %7.1f MB' "$(echo "$t / 1000000" | bc -l)" "$(echo "$m / 1024" | bc -l)"
    done
    echo
    unset times memory
done
