#!/usr/bin/env bash
# What glint-mpi adds to glint's work, in instructions (callgrind: repeatable where wall-clock
# times on a shared machine are not): the path-traced Cornell box at 128x128 and 16 samples per
# pixel, rendered by glint -t 1 and by `mpirun -np 2 glint-mpi -t 1`, each process under
# callgrind. Prints each run's total, and the instructions inside render() (glint's one call;
# glint-mpi's calls, one per tile, on both ranks): the same work, whatever the split.
# Usage: bench/mpi_instructions.sh BUILD_DIR [GLINT_OPTIONS...]   (needs valgrind)
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [GLINT_OPTIONS...]" >&2
    exit 2
fi
build=$(cd "$1" && pwd)
shift
here=$(cd "$(dirname "$0")" && pwd)
args=("$here/../scenes/cornell.test" --integrator path --size 128x128 --spp 16 -q -t 1 "$@")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cd "$out"
mpirun=(mpirun --bind-to none --mca pml ob1 --mca btl self,vader)
[ "$(id -u)" = 0 ] && mpirun+=(--allow-run-as-root)

valgrind --tool=callgrind --callgrind-out-file=cg.glint "$build/glint" "${args[@]}" -o a.png \
    2>/dev/null
"${mpirun[@]}" -np 2 valgrind --tool=callgrind --callgrind-out-file='cg.mpi.%q{OMPI_COMM_WORLD_RANK}' \
    "$build/glint-mpi" "${args[@]}" -o b.png 2>/dev/null
cmp a.png b.png || { echo "$0: glint-mpi's image differs from glint's" >&2; exit 1; }

# "total" and "render" of a callgrind file: the program's instructions, and render()'s inclusive.
count() {
    callgrind_annotate --inclusive=yes "$1" 2>/dev/null | awk '
        /PROGRAM TOTALS/ {gsub(",", "", $1); total = $1}
        /glint::render\(glint::Scene const&, glint::RenderOptions const&\) \[/ {
            gsub(",", "", $1); if ($1 > render) render = $1 }
        END {print total, render}'
}
read -r gt gr < <(count cg.glint)
read -r m0t m0r < <(count cg.mpi.0)
read -r m1t m1r < <(count cg.mpi.1)
awk -v gt="$gt" -v gr="$gr" -v m0t="$m0t" -v m0r="$m0r" -v m1t="$m1t" -v m1r="$m1r" 'BEGIN {
    printf "| run | instructions | in render() | elsewhere |\n|---|---|---|---|\n"
    printf "| glint -t 1 | %.1f M | %.1f M | %.1f M |\n", gt / 1e6, gr / 1e6, (gt - gr) / 1e6
    printf "| glint-mpi, rank 0 | %.1f M | %.1f M | %.1f M |\n", m0t / 1e6, m0r / 1e6, (m0t - m0r) / 1e6
    printf "| glint-mpi, rank 1 | %.1f M | %.1f M | %.1f M |\n", m1t / 1e6, m1r / 1e6, (m1t - m1r) / 1e6
    printf "| glint-mpi, both | %.1f M (%+.2f%%) | %.1f M (%+.3f%%) | %.1f M |\n", (m0t + m1t) / 1e6,
        100 * ((m0t + m1t) / gt - 1), (m0r + m1r) / 1e6, 100 * ((m0r + m1r) / gr - 1),
        (m0t + m1t - m0r - m1r) / 1e6
}'
