#!/usr/bin/env bash
# Issue 24's measurements of sequences and motion blur (docs/performance.md, "Animation and
# motion blur"; bench/animation/README.md). Four parts, each selectable with --part:
#   sequence  frames per minute of a CesiumMan sequence (FRAMES frames at SIZE, SPP samples,
#             --no-denoise, THREADS threads) rendered by ONE `glint --frames A:B` process against
#             one `glint --frame N` process per frame; RUNS rounds, the two ways alternating
#             which goes first; median wall times, frames per minute, their ratio, and a cmp of
#             every frame between the two ways (they must be byte-identical).
#   phases    where a sequence frame's time goes: `glint --frames ... --stats` prints parse
#             (for frame 0 the file's parse; for the others posing the parsed document and
#             building the scene from it), build (the BVHs: built for frame 0, refitted for the
#             others), render and write for each frame; medians per frame for CesiumMan and Fox
#             ('Survey'). CesiumMan's come from the sequence part's runs when it ran.
#   blur      the cost of motion blur: render time (--stats) and wall time with --shutter
#             -0.25:0.25 against none at equal spp, RUNS interleaved pairs, medians and ratios,
#             on BoxAnimated at frame 40 (a rigid node turning), scenes/spinning.test (spheres,
#             boxes and cylinders moved by `motion`; also with its picture's shutter 0:1) and
#             CesiumMan at frame 10 (a skinned mesh: deforming); and whether the images differ.
#   refit     refitting a sequence's BVHs against building them anew (glint_refit_bench, built
#             with the benchmarks): prepare times, the trees' box areas and the render times of
#             both, medians over the frames, for CesiumMan (every 2nd of FRAMES frames), Fox
#             ('Survey', every 2nd frame of its 84) and a 1M-triangle knot (glint_gen_mesh)
#             turning and sliding under a scene file's `motion` (frames 0 to 12), at 320x180.
#   instructions  (not in `all`; needs valgrind) the blur part's cases counted by callgrind at
#             320x180, SPP samples, one thread: instructions of the whole run, still and
#             blurred, and their ratio, which the machine's load does not move.
# Usage: bench/animation/run.sh [OPTIONS] BUILD_DIR [OUT_DIR]
#   BUILD_DIR  holds glint (a Release build)
#   OUT_DIR    frames, logs and summary.md [a temporary folder, removed at the end]
# Options (defaults in brackets):
#   --part sequence|phases|blur|refit|instructions|all [all: the first four]   --runs N [3]
#   --spp N [16]   --size WxH [640x360]
#   --threads N [2]   --frames N [100]   --step S [1: every frame; 4: every 4th of the N]
#   --fps F [50: 100 frames cover CesiumMan's 2-second walk once]
#   --models DIR  Khronos' samples [../shared/real-world/gltf-ext beside the repository]
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
usage() {
    sed -n '/^# Usage:/,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
    exit 2
}
part=all runs=3 spp=16 size=640x360 threads=2 frames=100 step=1 fps=50
models=$repo/../shared/real-world/gltf-ext
positional=()
while [ $# -gt 0 ]; do
    case $1 in
        --part) part=${2:?}; shift 2 ;;
        --runs) runs=${2:?}; shift 2 ;;
        --spp) spp=${2:?}; shift 2 ;;
        --size) size=${2:?}; shift 2 ;;
        --threads) threads=${2:?}; shift 2 ;;
        --frames) frames=${2:?}; shift 2 ;;
        --step) step=${2:?}; shift 2 ;;
        --fps) fps=${2:?}; shift 2 ;;
        --models) models=${2:?}; shift 2 ;;
        -h | --help) usage ;;
        -*) echo "run.sh: unknown option $1" >&2; usage ;;
        *) positional+=("$1"); shift ;;
    esac
done
[ ${#positional[@]} -ge 1 ] && [ ${#positional[@]} -le 2 ] || usage
for n in "$runs" "$spp" "$threads" "$frames" "$step"; do
    [[ $n =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: '$n' is not a positive integer" >&2; exit 2; }
done
case $part in sequence | phases | blur | refit | instructions | all) ;; *) usage ;; esac
build=$(cd "${positional[0]}" && pwd)
glint=$build/glint
[ -x "$glint" ] || { echo "run.sh: $glint not found: build it first" >&2; exit 1; }
if [ ${#positional[@]} -eq 2 ]; then
    mkdir -p "${positional[1]}"
    out=$(cd "${positional[1]}" && pwd)
else
    out=$(mktemp -d)
    trap 'rm -rf "$out"' EXIT
fi
man=$models/CesiumMan/glTF/CesiumMan.gltf
fox=$models/Fox/glTF/Fox.gltf
box=$models/BoxAnimated/glTF/BoxAnimated.gltf
for f in "$man" "$fox" "$box"; do
    [ -f "$f" ] || { echo "run.sh: $f not found (--models names the folder)" >&2; exit 1; }
done
last=$((frames - 1))
common=(--size "$size" --spp "$spp" --no-denoise -t "$threads" --fps "$fps")
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.3f", b - a }'; }
summary=$out/summary.md
: >"$summary"
say() { echo "$@" | tee -a "$summary"; }
say "Machine: $(nproc) cores, load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
say "glint: $("$glint" --version)"
say "Options: --size $size --spp $spp --no-denoise -t $threads --fps $fps; $runs runs"
say ""

# Per-frame --stats lines of a sequence log -> "frame parse build render write" rows.
stats_rows() {
    awk '/^Time +parse/ { gsub(",", ""); print n++, $3, $6, $9, $12 }' "$1"
}

if [ "$part" = sequence ] || [ "$part" = all ]; then
    mkdir -p "$out/seq" "$out/each"
    list=$(seq 0 "$step" "$last")
    count=$(echo "$list" | wc -l)
    : >"$out/seq/times.txt"
    one() {  # one process for the whole sequence, its --stats kept
        "$glint" "$man" --frames "0:$last:$step" -o "$out/seq/f_%04d.png" "${common[@]}" \
            -q --stats >"$out/seq/stats_$1.txt" 2>>"$out/seq/stderr.txt"
    }
    each() {  # a process per frame
        local n
        for n in $list; do
            "$glint" "$man" --frame "$n" -o "$(printf '%s/each/f_%04d.png' "$out" "$n")" \
                "${common[@]}" -q 2>>"$out/seq/stderr.txt"
        done
    }
    TIMEFORMAT='%3R %3U %3S'  # bash's `time`: wall, then user and system CPU of the children
    for ((r = 0; r < runs; r++)); do
        for j in 0 1; do
            if [ $(((r + j) % 2)) = 0 ]; then
                { time one "$r"; } 2>"$out/seq/time.txt"
                echo "one $(cat "$out/seq/time.txt")" >>"$out/seq/times.txt"
            else
                { time each; } 2>"$out/seq/time.txt"
                echo "each $(cat "$out/seq/time.txt")" >>"$out/seq/times.txt"
            fi
            echo "run.sh: sequence round $((r + 1)) of $runs: $(tail -1 "$out/seq/times.txt")" >&2
        done
    done
    if [ -s "$out/seq/stderr.txt" ]; then
        echo "run.sh: glint wrote on stderr:" >&2
        head "$out/seq/stderr.txt" >&2
    fi
    identical=0
    for n in $list; do
        f=$(printf 'f_%04d.png' "$n")
        if cmp -s "$out/seq/$f" "$out/each/$f"; then identical=$((identical + 1)); else
            echo "run.sh: frame $n differs between the two ways" >&2
        fi
    done
    python3 - "$out/seq/times.txt" "$count" "$last" "$step" "$identical" <<'EOF' | tee -a "$summary"
import statistics, sys
path, count, last, step, identical = sys.argv[1], *map(int, sys.argv[2:])
t, cpu = {}, {}
for line in open(path):
    k, wall, user, system = line.split()
    t.setdefault(k, []).append(float(wall))
    cpu.setdefault(k, []).append(float(user) + float(system))
one, each = statistics.median(t["one"]), statistics.median(t["each"])
cone, ceach = statistics.median(cpu["one"]), statistics.median(cpu["each"])
span = f"0:{last}" + (f":{step}" if step > 1 else "")
print(f"## (a) CesiumMan, {count} frames ({span}): one process against one per frame")
print()
print("| way | wall (s), median | runs | frames per minute | s per frame | CPU (s), median | runs |")
print("|---|---|---|---|---|---|---|")
print(f"| one `glint --frames {span}` | {one:.1f} | {', '.join(f'{x:.1f}' for x in t['one'])} "
      f"| {60 * count / one:.1f} | {one / count:.3f} | {cone:.1f} "
      f"| {', '.join(f'{x:.1f}' for x in cpu['one'])} |")
print(f"| {count} x `glint --frame N` | {each:.1f} | {', '.join(f'{x:.1f}' for x in t['each'])} "
      f"| {60 * count / each:.1f} | {each / count:.3f} | {ceach:.1f} "
      f"| {', '.join(f'{x:.1f}' for x in cpu['each'])} |")
print()
print(f"Ratio (one process per frame / one sequence): wall {each / one:.3f}, CPU "
      f"{ceach / cone:.3f}; saved per frame: wall {(each - one) / count:.3f} s, CPU "
      f"{(ceach - cone) / count:.3f} s")
print(f"Byte-identical frames (cmp): {identical} of {count}")
print()
EOF
fi

phases() {  # LABEL LOG...: medians per frame of the --stats lines of sequence logs
    local label=$1
    shift
    for log in "$@"; do stats_rows "$log"; done | python3 -c '
import statistics, sys
label = sys.argv[1]
rows = [list(map(float, l.split())) for l in sys.stdin if l.strip()]
first = [r for r in rows if r[0] == 0]
rest = [r for r in rows if r[0] != 0]
med = lambda rs, i: statistics.median(r[i] for r in rs)
total = sum(med(rest, i) for i in (1, 2, 3, 4))
print(f"| {label} | {len(rest)} | {med(rest, 1) * 1000:.1f} | {med(rest, 2) * 1000:.1f} | "
      f"{med(rest, 3) * 1000:.0f} | {med(rest, 4) * 1000:.1f} | "
      f"{100 * (med(rest, 1) + med(rest, 2)) / total:.1f}% | "
      f"{med(first, 1) * 1000:.0f} | {med(first, 2) * 1000:.1f} |")
' "$label"
}

if [ "$part" = phases ] || [ "$part" = all ]; then
    mkdir -p "$out/phases"
    logs=("$out"/seq/stats_*.txt)
    if [ ! -f "${logs[0]}" ]; then
        "$glint" "$man" --frames "0:$last:$step" -o "$out/phases/man_%04d.png" "${common[@]}" \
            -q --stats >"$out/phases/man.txt"
        logs=("$out/phases/man.txt")
    fi
    "$glint" "$fox" --animation Survey --frames "0:$last:$step" -o "$out/phases/fox_%04d.png" \
        "${common[@]}" -q --stats >"$out/phases/fox.txt"
    {
        echo "## (b) Where a sequence frame's time goes (medians per frame, ms; frame 0 apart)"
        echo
        echo "| model | frames (all runs) | parse/pose | BVH refit | render | write |" \
            "parse/pose + rebuild, of the frame | frame 0: parse | frame 0: BVH |"
        echo "|---|---|---|---|---|---|---|---|---|"
        phases "CesiumMan (4672 triangles, skinned)" "${logs[@]}"
        phases "Fox, Survey (576 triangles, skinned)" "$out/phases/fox.txt"
        echo
        echo "Frames after the first refit the last frame's BVHs (part refit compares)."
        echo
    } | tee -a "$summary"
fi

if [ "$part" = blur ] || [ "$part" = all ]; then
    mkdir -p "$out/blur"
    : >"$out/blur/times.txt"
    blur_case() {  # NAME SHUTTER FILE ARGS...: RUNS interleaved pairs, still and blurred
        local name=$1 shutter=$2 file=$3 r kind t0
        shift 3
        for ((r = 0; r < runs; r++)); do
            for kind in still blur; do
                [ $((r % 2)) = 1 ] && kind=$([ $kind = still ] && echo blur || echo still)
                local extra=()
                [ $kind = blur ] && extra=(--shutter "$shutter")
                t0=$(now)
                "$glint" "$file" "$@" "${extra[@]}" --size "$size" --spp "$spp" --no-denoise \
                    -t "$threads" -q --stats -o "$out/blur/${name}_$kind.png" \
                    >"$out/blur/${name}_${kind}_$r.txt"
                echo "$name $kind $(elapsed "$t0") $(awk '/^Time/ { gsub(",", ""); print $9 }' \
                    "$out/blur/${name}_${kind}_$r.txt")" >>"$out/blur/times.txt"
            done
        done
        if cmp -s "$out/blur/${name}_still.png" "$out/blur/${name}_blur.png"; then
            echo "$name identical" >>"$out/blur/same.txt"
        else
            echo "$name differ" >>"$out/blur/same.txt"
        fi
    }
    : >"$out/blur/same.txt"
    blur_case BoxAnimated -0.25:0.25 "$box" --frame 40 --fps 24
    blur_case spinning -0.25:0.25 "$repo/scenes/spinning.test"
    blur_case spinning_long 0:1 "$repo/scenes/spinning.test"
    blur_case CesiumMan -0.25:0.25 "$man" --frame 10 --fps 24
    python3 - "$out/blur/times.txt" "$out/blur/same.txt" "$spp" <<'EOF' | tee -a "$summary"
import statistics, sys
t = {}
for line in open(sys.argv[1]):
    name, kind, wall, render = line.split()
    t.setdefault((name, kind), []).append((float(wall), float(render)))
same = dict(l.split() for l in open(sys.argv[2]))
what = {"BoxAnimated": "BoxAnimated, frame 40 (rigid: the inner box turning) | -0.25:0.25",
        "spinning": "scenes/spinning.test (rigid: `motion`) | -0.25:0.25",
        "spinning_long": "scenes/spinning.test, its picture's shutter | 0:1",
        "CesiumMan": "CesiumMan, frame 10 (skinned: deforming) | -0.25:0.25"}
print(f"## (c) The cost of motion blur: --shutter against none, {sys.argv[3]} spp")
print()
print("| scene | shutter | render (s), still | blurred | ratio | wall (s), still | blurred | "
      "ratio | images |")
print("|---|---|---|---|---|---|---|---|---|")
for name in ("BoxAnimated", "spinning", "spinning_long", "CesiumMan"):
    s, b = t[(name, "still")], t[(name, "blur")]
    rs, rb = statistics.median(x[1] for x in s), statistics.median(x[1] for x in b)
    ws, wb = statistics.median(x[0] for x in s), statistics.median(x[0] for x in b)
    print(f"| {what[name]} | {rs:.2f} | {rb:.2f} | {rb / rs:.2f} | {ws:.2f} | {wb:.2f} | "
          f"{wb / ws:.2f} | {'identical' if same[name] == 'identical' else 'differ'} |")
print()
EOF
fi
if [ "$part" = refit ] || [ "$part" = all ]; then
    refit_bench=$build/bench/glint_refit_bench
    [ -x "$refit_bench" ] || { echo "run.sh: $refit_bench not found: build the benchmarks" >&2; exit 1; }
    mkdir -p "$out/refit"
    "$build/bench/glint_gen_mesh" "$out/refit/knot.obj" >/dev/null
    printf '%s\n' 'size 320 180' 'camera 0 0 9 0 0 0 0 1 0 45' 'directional 0 0 1 0.8 0.8 0.8' \
        'ambient 0.1 0.1 0.1' 'diffuse 0.7 0.5 0.3' 'motion 0.5 0 0 0 0 1 -90' 'mesh knot.obj' \
        >"$out/refit/knot.test"
    {
        echo "## (d) Refitting a sequence's BVHs against building them ($spp spp, 320x180)"
        echo
        for c in "CesiumMan|$man|0 $last 2 --fps $fps" "Fox, Survey|$fox|0 83 2" \
            "1M-triangle knot under motion|$out/refit/knot.test|0 12"; do
            IFS='|' read -r name file range <<<"$c"
            # shellcheck disable=SC2086  # the range is words
            echo "- $name: $("$refit_bench" "$file" $range --spp "$spp" --threads "$threads" |
                tail -1)"
        done
        echo
    } | tee -a "$summary"
fi

if [ "$part" = instructions ]; then
    command -v valgrind >/dev/null || { echo "run.sh: valgrind not found" >&2; exit 1; }
    mkdir -p "$out/instr"
    : >"$out/instr/counts.txt"
    count_case() {  # NAME SHUTTER FILE ARGS...: instructions of the whole run, still and blurred
        local name=$1 shutter=$2 file=$3 kind
        shift 3
        for kind in still blur; do
            local extra=()
            [ $kind = blur ] && extra=(--shutter "$shutter")
            valgrind --tool=callgrind --callgrind-out-file="$out/instr/$name.$kind.out" \
                "$glint" "$file" "$@" "${extra[@]}" --size 320x180 --spp "$spp" --no-denoise \
                -t 1 -q -o "$out/instr/${name}_$kind.png" 2>"$out/instr/$name.$kind.log"
            echo "$name $kind $(awk '/Collected/ { print $4 }' "$out/instr/$name.$kind.log")" \
                >>"$out/instr/counts.txt"
        done
    }
    count_case BoxAnimated -0.25:0.25 "$box" --frame 40 --fps 24
    count_case spinning -0.25:0.25 "$repo/scenes/spinning.test"
    count_case spinning_long 0:1 "$repo/scenes/spinning.test"
    count_case CesiumMan -0.25:0.25 "$man" --frame 10 --fps 24
    python3 - "$out/instr/counts.txt" "$spp" <<'EOF' | tee -a "$summary"
import sys
n = {}
for line in open(sys.argv[1]):
    name, kind, ir = line.split()
    n[(name, kind)] = int(ir)
print(f"## (c') The cost of motion blur in instructions (callgrind, 320x180, {sys.argv[2]} spp, "
      "-t 1, the whole run: loading and writing included)")
print()
print("| scene | shutter | instructions, still | blurred | ratio |")
print("|---|---|---|---|---|")
for name, shutter in (("BoxAnimated", "-0.25:0.25"), ("spinning", "-0.25:0.25"),
                      ("spinning_long", "0:1"), ("CesiumMan", "-0.25:0.25")):
    s, b = n[(name, "still")], n[(name, "blur")]
    print(f"| {name} | {shutter} | {s / 1e6:.0f} M | {b / 1e6:.0f} M | {b / s:.3f} |")
print()
EOF
fi
say "Load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
