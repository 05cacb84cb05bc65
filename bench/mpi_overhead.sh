#!/usr/bin/env bash
# glint-mpi against glint on this machine (docs/scale-out.md, "MPI"): the path-traced Cornell
# box at its size (512x512) and 64 samples per pixel, rendered by
#   glint -t 2                        one process, two threads (the plain render)
#   mpirun -np 1 glint-mpi -t 2       one rank, two render threads: what MPI itself costs
#   mpirun -np 2 glint-mpi -t 1       two ranks of one thread each
#   mpirun -np 3 glint-mpi -t 1       three ranks on two cores (oversubscribed)
# Wall-clock medians of RUNS runs each with hyperfine (mpirun's start included), their ratio to
# the plain render, and from one --stats run of each MPI command: the render phase, the bytes
# sent, the CPU time of rank 0's MPI thread. Every image is checked to be glint's, byte for byte.
# Usage: bench/mpi_overhead.sh BUILD_DIR [RUNS] [GLINT_OPTIONS...]
# BUILD_DIR needs glint and glint-mpi (Open MPI found). Needs hyperfine and python3.
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [RUNS] [GLINT_OPTIONS...]" >&2
    exit 2
fi
build=$(cd "$1" && pwd)
runs=${2:-5}
shift $(($# < 2 ? $# : 2))
here=$(cd "$(dirname "$0")" && pwd)
scene=$here/../scenes/cornell.test
opts=(--integrator path --spp 64 -q "$@")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# One machine: shared memory only; as root if need be; more ranks than cores for -np 3; no
# binding (Open MPI would bind -np 1 to one core, leaving -t 2 one core for two threads).
mpirun=(mpirun --oversubscribe --bind-to none --mca pml ob1 --mca btl self,vader)
[ "$(id -u)" = 0 ] && mpirun+=(--allow-run-as-root)

cd "$out"
plain="$build/glint $scene ${opts[*]} -t 2 -o plain.png"
cmds=("$plain")
for np in 1 2 3; do
    t=$((np == 1 ? 2 : 1))
    cmds+=("${mpirun[*]} -np $np $build/glint-mpi $scene ${opts[*]} -t $t -o mpi$np.png")
done
hyperfine --style basic --warmup 1 --runs "$runs" --export-json times.json "${cmds[@]}" >&2
hyperfine --style basic --runs "$runs" --export-json start.json \
    "${mpirun[*]} -np 2 $build/glint-mpi --version" >&2

for np in 1 2 3; do
    cmp plain.png "mpi$np.png" || { echo "$0: mpi$np.png differs from glint's image" >&2; exit 1; }
    t=$((np == 1 ? 2 : 1))
    "${mpirun[@]}" -np "$np" "$build/glint-mpi" "$scene" "${opts[@]}" -t "$t" -o stats.png \
        --stats --timings "timings$np.json" >"stats$np.txt"
done
"$build/glint" "$scene" "${opts[@]}" -t 2 -o stats.png --stats >stats0.txt

python3 - "$runs" <<'EOF'
import json, statistics, sys
runs = sys.argv[1]
times = json.load(open("times.json"))["results"]
start = statistics.median(json.load(open("start.json"))["results"][0]["times"])
names = ["glint -t 2", "mpirun -np 1 glint-mpi -t 2", "mpirun -np 2 glint-mpi -t 1",
         "mpirun -np 3 glint-mpi -t 1"]
def render(i):  # the render phase, from --stats
    for line in open(f"stats{i}.txt"):
        if line.startswith("Time"):
            return float(line.split()[8])
base = statistics.median(times[0]["times"])
base_render = render(0)
print(f"| command | wall median (s) | vs glint | render phase (s) | vs glint | bytes to rank 0 "
      f"| bytes from rank 0 | rank 0's MPI thread CPU (s) |")
print("|---|---|---|---|---|---|---|---|")
for i, r in enumerate(times):
    wall = statistics.median(r["times"])
    row = f"| `{names[i]}` | {wall:.2f} | {100 * (wall / base - 1):+.1f}% | {render(i):.2f} | " \
          f"{100 * (render(i) / base_render - 1):+.1f}% |"
    if i == 0:
        row += " - | - | - |"
    else:
        t = json.load(open(f"timings{i}.json"))
        row += f" {t['bytes_to_root']:.0f} | {t['bytes_from_root']:.0f} | " \
               f"{t['coordinator_cpu_seconds']:.3f} |"
    print(row)
print(f"\nmpirun -np 2 glint-mpi --version (start and end of a job): {start:.2f} s median")
print(f"(wall: medians of {runs} runs by hyperfine; render phase: one --stats run each)")
EOF
