#!/usr/bin/env bash
# glint-mpi against glint on this machine (docs/scale-out.md, "MPI"): the path-traced Cornell
# box at its size (512x512) and 64 samples per pixel, rendered by
#   glint -t 2                        one process, two threads (the plain render)
#   mpirun -np 1 glint-mpi -t 2       one rank, two render threads: what MPI itself costs
#   mpirun -np 2 glint-mpi -t 1       two ranks of one thread each
#   mpirun -np 3 glint-mpi -t 1       three ranks on two cores (oversubscribed)
# in RUNS rounds, each running every command once with hyperfine, so that the load of a shared
# machine falls on all of them alike (round r starts with command r mod 4). Prints the medians
# of the wall time (mpirun's start included), of the CPU time (user + system of every process:
# the steadier figure on a busy machine) and of the render phase (--stats), their ratios to the
# plain render, and the bytes sent and rank 0's MPI thread's CPU time (--timings). Every image
# is checked to be glint's, byte for byte.
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
scene=$(cd "$here/../scenes" && pwd)/cornell.test
opts="--integrator path -q --stats ${*:---spp 64}"  # GLINT_OPTIONS replace --spp 64
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# One machine: shared memory only; as root if need be; more ranks than cores for -np 3; no
# binding (Open MPI would bind -np 1 to one core, leaving -t 2 one core for two threads).
mpirun="mpirun --oversubscribe --bind-to none --mca pml ob1 --mca btl self,vader"
[ "$(id -u)" = 0 ] && mpirun="$mpirun --allow-run-as-root"

cd "$out"
commands() {  # the four commands of round $1
    echo "$build/glint $scene $opts -t 2 -o plain.png >stats0-$1.txt"
    for np in 1 2 3; do
        echo "$mpirun -np $np $build/glint-mpi $scene $opts -t $((np == 1 ? 2 : 1)) -o mpi$np.png" \
            "--timings timings$np-$1.json >stats$np-$1.txt"
    done
}
mapfile -t cmds < <(commands warmup)
for c in "${cmds[@]}"; do sh -c "$c"; done  # warm the caches once
for ((r = 0; r < runs; r++)); do
    mapfile -t cmds < <(commands "$r")
    k=$((r % ${#cmds[@]}))  # each round starts with the next command: no place in a round is favoured
    cmds=("${cmds[@]:k}" "${cmds[@]:0:k}")
    hyperfine --style basic --runs 1 --export-json "round$r.json" "${cmds[@]}" >&2
done
hyperfine --style basic --runs "$runs" --export-json start.json \
    "$mpirun -np 2 $build/glint-mpi --version" >&2
for np in 1 2 3; do
    cmp plain.png "mpi$np.png" || { echo "$0: mpi$np.png differs from glint's image" >&2; exit 1; }
done

python3 - "$runs" <<'EOF'
import json, statistics, sys
runs = int(sys.argv[1])
names = ["glint -t 2", "mpirun -np 1 glint-mpi -t 2", "mpirun -np 2 glint-mpi -t 1",
         "mpirun -np 3 glint-mpi -t 1"]
wall = [[] for _ in names]
cpu = [[] for _ in names]
for r in range(runs):
    for j, res in enumerate(json.load(open(f"round{r}.json"))["results"]):
        i = (j + r) % len(names)  # round r ran the commands rotated by r
        wall[i].append(res["times"][0])
        cpu[i].append(res["user"] + res["system"])
def render(i, r):  # the render phase, from --stats
    for line in open(f"stats{i}-{r}.txt"):
        if line.startswith("Time"):
            return float(line.split()[8])
phase = [[render(i, r) for r in range(runs)] for i in range(len(names))]
med = statistics.median
print("| command | wall (s) | vs glint | CPU (s) | vs glint | render phase (s) | vs glint "
      "| bytes to rank 0 | bytes from rank 0 | rank 0's MPI thread CPU (s) |")
print("|---|---|---|---|---|---|---|---|---|---|")
for i, name in enumerate(names):
    row = f"| `{name}` "
    for v in (wall, cpu, phase):
        row += f"| {med(v[i]):.2f} | {100 * (med(v[i]) / med(v[0]) - 1):+.1f}% "
    if i == 0:
        row += "| - | - | - |"
    else:
        t = [json.load(open(f"timings{i}-{r}.json")) for r in range(runs)]
        row += f"| {med(x['bytes_to_root'] for x in t):.0f} " \
               f"| {med(x['bytes_from_root'] for x in t):.0f} " \
               f"| {med(x['coordinator_cpu_seconds'] for x in t):.3f} |"
    print(row)
# The machine's other work only ever slows a run: the fastest of the rounds, beside the medians.
print("\nfastest of the rounds (wall, CPU): " + "; ".join(
    f"`{n}` {min(wall[i]):.2f} s ({100 * (min(wall[i]) / min(wall[0]) - 1):+.1f}%), "
    f"{min(cpu[i]):.2f} s ({100 * (min(cpu[i]) / min(cpu[0]) - 1):+.1f}%)"
    for i, n in enumerate(names)))
# The firm figure on a noisy machine: how much of the render phase each rank's render threads
# spent rendering tiles (--timings), the rest being waits for tiles and the frame's end.
for i, n in enumerate(names[1:], 1):
    busy = []
    for r in range(runs):
        t = json.load(open(f"timings{i}-{r}.json"))
        per = {}
        for tile in t["tiles"]:
            per[tile[4]] = per.get(tile[4], 0) + tile[5]
        busy.append(sum(per.values()) / (sum(t["threads"]) * t["render_seconds"]))
    print(f"`{n}`: render threads busy {100 * med(busy):.1f}% of the render phase (median)")
start = med(json.load(open("start.json"))["results"][0]["times"])
print(f"\nmpirun -np 2 glint-mpi --version (a job's start and end): {start:.2f} s")
print(f"(medians of {runs} rounds, each running every command once)")
EOF
