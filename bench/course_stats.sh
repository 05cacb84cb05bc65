#!/usr/bin/env bash
# Medians of `glint --stats` over repeated runs for the course scenes.
# Usage: bench/course_stats.sh [GLINT_BINARY] [RUNS] [THREADS]
set -euo pipefail
glint=${1:-build/glint}
runs=${2:-7}
threads=${3:-2}
data=$(cd "$(dirname "$0")/../tests/data/cse167x" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

printf '%-16s %9s %9s %9s %9s %9s %10s %9s\n' scene parse_s build_s render_s write_s total_s Mrays Mrays/s
for scene in scene4-specular scene5 scene6 scene7; do
    : >"$out/runs"
    for ((i = 0; i < runs; i++)); do
        start=$(date +%s.%N)
        "$glint" -q --stats -t "$threads" "$data/$scene.test" -o "$out/img.png" >"$out/stats"
        end=$(date +%s.%N)
        awk -v total="$(echo "$end - $start" | bc)" '
            /^Time/ {parse=$3; build=$6; render=$9; write=$12}
            /^Rays/ {rays=$8}
            /^Throughput/ {tp=$2}
            END {print parse, build, render, write, total, rays / 1e6, tp}' "$out/stats" >>"$out/runs"
    done
    row=""
    for col in 1 2 3 4 5 6 7; do row="$row $(cut -d' ' -f$col "$out/runs" | median)"; done
    # shellcheck disable=SC2086
    printf '%-16s %9.3f %9.3f %9.3f %9.3f %9.3f %10.2f %9.2f\n' "$scene" $row
done
echo "(medians of $runs runs, $threads threads; total = wall clock of the whole command)"
