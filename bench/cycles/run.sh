#!/usr/bin/env bash
# Glint's path tracer against Blender Cycles on the Cornell box (issue 11, "Against Cycles" and
# "Speed"; bench/cycles/README.md explains the set-up). At SIZE x SIZE pixels on THREADS threads:
#   (a) converged: a long Cycles reference (REF_SPP) and a long Glint render (GLINT_REF_SPP),
#       compared with `imgdiff --blocks 16`: relative difference of the image means and the
#       largest of the 16x16 block means, against what noise alone gives;
#   (b) speed: SPP samples per pixel, RUNS runs each (interleaved), each renderer's own render
#       time (Cycles: bpy.ops.render.render, scene sync included; Glint: `render` of --stats),
#       medians, samples (paths) per second and their ratio;
#   (c) equal time: Glint at the spp that takes Cycles' median SPP-spp time, and Cycles at SPP,
#       RMSE of each against the Cycles reference (and Glint's against its own long render).
# Images (EXR, and PNG previews through imgdiff --preview: sRGB, no exposure) go to OUT_DIR;
# the Cycles reference is rendered once and kept in OUT_DIR/ref (delete it to render anew).
# Without a path integrator in Glint (or with --cycles-only) only the Cycles half runs.
#
# Usage: bench/cycles/run.sh [OPTIONS] BUILD_DIR [OUT_DIR]
#   BUILD_DIR  holds glint and imgdiff (make build, or make bench's build-bench)
#   OUT_DIR    default: cycles-out beside the repository (/work/cycles-out for /work/main)
# Options (defaults in brackets):
#   --runs N [3]  --spp N [256]  --ref-spp N [4096]  --glint-ref-spp N [REF_SPP]
#   --threads N [2]  --size N [256]  --variant quad|mtl [quad]  --cycles-only
#   --obj FILE     the OBJ Cycles renders [../shared/scenes/cornell/cornell.obj beside the repo]
#   --glint-scene FILE  the scene Glint renders [bench/cycles/cornell.test; -mtl.test for mtl]
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)

usage() {
    sed -n '/^# Usage:/,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
    exit 2
}
runs=3 spp=256 ref_spp=4096 glint_ref_spp= threads=2 size=256 variant=quad cycles_only=no
glint_scene=
obj=$repo/../shared/scenes/cornell/cornell.obj
positional=()
while [ $# -gt 0 ]; do
    case $1 in
        --runs) runs=${2:?}; shift 2 ;;
        --spp) spp=${2:?}; shift 2 ;;
        --ref-spp) ref_spp=${2:?}; shift 2 ;;
        --glint-ref-spp) glint_ref_spp=${2:?}; shift 2 ;;
        --threads) threads=${2:?}; shift 2 ;;
        --size) size=${2:?}; shift 2 ;;
        --variant) variant=${2:?}; shift 2 ;;
        --obj) obj=${2:?}; shift 2 ;;
        --glint-scene) glint_scene=${2:?}; shift 2 ;;
        --cycles-only) cycles_only=yes; shift ;;
        -h | --help) usage ;;
        -*) echo "run.sh: unknown option $1" >&2; usage ;;
        *) positional+=("$1"); shift ;;
    esac
done
[ ${#positional[@]} -ge 1 ] && [ ${#positional[@]} -le 2 ] || usage
glint_ref_spp=${glint_ref_spp:-$ref_spp}
for n in "$runs" "$spp" "$ref_spp" "$glint_ref_spp" "$threads" "$size"; do
    [[ $n =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: '$n' is not a positive integer" >&2; exit 2; }
done
case $variant in
    quad) scene=$here/cornell.test light=front ;;
    mtl) scene=$here/cornell-mtl.test light=mtl ;;
    *) echo "run.sh: --variant is quad or mtl" >&2; exit 2 ;;
esac
scene=${glint_scene:-$scene}
build=$(cd "${positional[0]}" && pwd) || usage
out=${positional[1]:-$repo/../cycles-out}
mkdir -p "$out/ref" "$out/logs"
out=$(cd "$out" && pwd)
glint=$build/glint
imgdiff=$build/imgdiff

command -v blender >/dev/null || {
    echo "run.sh: blender not found (apt-get install --no-install-recommends blender, or make bench)" >&2
    exit 1
}
[ -x "$imgdiff" ] || { echo "run.sh: $imgdiff not found: build $build first" >&2; exit 1; }
[ -f "$obj" ] || { echo "run.sh: $obj not found (--obj names the Cornell box OBJ)" >&2; exit 1; }
obj=$(cd "$(dirname "$obj")" && pwd)/$(basename "$obj")

median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2)}'; }

# cycles SPP SEED OUT.exr -> prints "render_seconds cpu_seconds"
cycles() {
    local log=$out/logs/$(basename "$3" .exr).log
    if ! blender -b --factory-startup --python "$here/cornell.py" -- --obj "$obj" --out "$3" \
        --width "$size" --height "$size" --spp "$1" --threads "$threads" --seed "$2" \
        --light "$light" >"$log" 2>&1; then
        echo "run.sh: Cycles failed; the end of $log:" >&2
        tail -20 "$log" >&2
        exit 1
    fi
    sed -n 's/^CYCLES_RESULT .*render_s=\([0-9.]*\).*cpu_s=\([0-9.]*\).*/\1 \2/p' "$log" |
        tail -1 | grep . || {
        echo "run.sh: no CYCLES_RESULT line in $log" >&2
        exit 1
    }
}

# glint_render SPP SEED OUT.exr -> prints "render_seconds cpu_seconds" (--stats in the log).
# The CPU time is the whole process's (parsing, BVH build and write too: milliseconds here).
glint_render() {
    local log=$out/logs/$(basename "$3" .exr).log TIMEFORMAT='%U %S' cpu
    if ! { time "$glint" "$scene" -q --stats -t "$threads" --size "${size}x$size" --spp "$1" \
        --seed "$2" -o "$3" >"$log" 2>&1; } 2>"$log.cpu"; then
        echo "run.sh: glint failed; $log:" >&2
        cat "$log" >&2
        exit 1
    fi
    cpu=$(awk '{print $1 + $2}' "$log.cpu") && rm -f "$log.cpu"
    awk -v cpu="$cpu" '/^Time/ {for (i = 1; i < NF; i++) if ($i == "render") print $(i + 1), cpu}' "$log" | grep . || {
        echo "run.sh: no render time in glint's --stats ($log)" >&2
        exit 1
    }
}

# compare A.exr B.exr [imgdiff options] -> imgdiff's report, B the reference
compare() { "$imgdiff" --blocks 16 "$@" || true; }
field() { awk -v k="$1" -v f="$2" '$1 == k {for (i = 2; i <= NF; i++) if (index($i, f "=") == 1) print substr($i, length(f) + 2)}'; }
preview() { "$imgdiff" --preview "${1%.exr}.png" "$1"; }

# --- Which halves run. ----------------------------------------------------------------------
glint_ok=yes why=
if [ $cycles_only = yes ]; then
    glint_ok=no why="--cycles-only"
elif [ ! -x "$glint" ]; then
    glint_ok=no why="$glint not found"
elif ! check=$("$glint" --check "$scene" 2>&1); then
    glint_ok=no why="glint cannot render $scene yet: $(echo "$check" | head -1)"
fi

echo "Cornell box: Glint's path tracer against Blender Cycles, $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "Machine: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) hardware threads;" \
    "1-minute load average at start: $(cut -d' ' -f1 /proc/loadavg)"
echo "Cycles: $(blender --version 2>/dev/null | head -1), CPU, $threads threads;" \
    "Glint: $([ $glint_ok = yes ] && "$glint" --version || echo "skipped ($why)")"
echo "Scene: $variant ($(basename "$scene"); Cycles: $obj, light $light), ${size}x$size," \
    "64 bounces, box filter 1 px, seeds differ between every pair of images compared"
echo "Output: $out"

# --- (a) Long renders. ------------------------------------------------------------------------
tag=$variant-${size}px
ref=$out/ref/cycles-$tag-${ref_spp}spp-seed1000.exr
echo
if [ -f "$ref" ]; then
    echo "Cycles reference: $ref (kept from an earlier run)"
else
    echo "Rendering the Cycles reference, $ref_spp spp (once; kept in $out/ref) ..."
    read -r t c < <(cycles "$ref_spp" 1000 "$ref")  # written atomically: never partial
    echo "  $t s (CPU $c s)"
fi
preview "$ref"
if [ $glint_ok = yes ]; then
    glint_ref=$out/glint-$tag-${glint_ref_spp}spp-seed1000.exr
    echo "Rendering Glint's long render, $glint_ref_spp spp ..."
    read -r t c < <(glint_render "$glint_ref_spp" 1000 "$glint_ref")
    echo "  $t s (CPU $c s)"
    preview "$glint_ref"
fi

# --- (b) Speed: interleaved runs, different seeds. --------------------------------------------
echo
echo "Speed: $spp spp, $runs runs each ..."
: >"$out/logs/times-cycles" && : >"$out/logs/times-glint"
for ((i = 0; i < runs; i++)); do
    cycles "$spp" "$i" "$out/cycles-$tag-${spp}spp-seed$i.exr" >>"$out/logs/times-cycles"
    if [ $glint_ok = yes ]; then
        glint_render "$spp" "$i" "$out/glint-$tag-${spp}spp-seed$i.exr" >>"$out/logs/times-glint"
    fi
done
preview "$out/cycles-$tag-${spp}spp-seed0.exr"
# Medians of the wall-clock render times (column 1) and of the CPU times (column 2).
tc=$(cut -d' ' -f1 "$out/logs/times-cycles" | median)
cc=$(cut -d' ' -f2 "$out/logs/times-cycles" | median)
echo "  Cycles runs (render s, CPU s): $(paste -sd, "$out/logs/times-cycles")"
if [ $glint_ok = yes ]; then
    preview "$out/glint-$tag-${spp}spp-seed0.exr"
    tg=$(cut -d' ' -f1 "$out/logs/times-glint" | median)
    cg=$(cut -d' ' -f2 "$out/logs/times-glint" | median)
    echo "  Glint runs (render s, CPU s):  $(paste -sd, "$out/logs/times-glint")"
fi

# --- (c) Equal time. ------------------------------------------------------------------------
if [ $glint_ok = yes ]; then
    eq_spp=$(awk -v s="$spp" -v c="$tc" -v g="$tg" 'BEGIN {n = int(s * c / g + 0.5); print n < 1 ? 1 : n}')
    echo
    echo "Equal time: Glint at $eq_spp spp (Cycles' median $spp-spp time) ..."
    eq=$out/glint-$tag-${eq_spp}spp-equal-time-seed7.exr
    read -r teq ceq < <(glint_render "$eq_spp" 7 "$eq")
    echo "  $teq s"
    preview "$eq"
fi

# --- Comparisons. ---------------------------------------------------------------------------
c0=$out/cycles-$tag-${spp}spp-seed0.exr
cyc_vs_ref=$(compare "$c0" "$ref")
noise_c= noise_g=
if [ "$runs" -ge 2 ]; then
    # Two renders of one renderer with different seeds: what noise alone gives at $spp spp.
    noise_c=$(compare "$c0" "$out/cycles-$tag-${spp}spp-seed1.exr")
    if [ $glint_ok = yes ]; then
        noise_g=$(compare "$out/glint-$tag-${spp}spp-seed0.exr" "$out/glint-$tag-${spp}spp-seed1.exr")
    fi
fi

# row NAME SPP WALL_S CPU_S RMSE [NOTE]
row() {
    awk -v n="$1" -v s="$2" -v t="$3" -v c="$4" -v r="$5" -v note="${6:-}" -v px=$((size * size)) \
        -v th="$threads" 'BEGIN {printf "%-8s %6d %10.3f %12.0f %10.3f %14.0f %10s %s\n",
                                 n, s, t, px * s / t, c, px * s * th / c, r, note}'
}
echo
echo "==== Summary (${size}x$size, $threads threads, 64 bounces) ===="
echo
printf '%-8s %6s %10s %12s %10s %14s %10s\n' renderer spp render_s paths_per_s cpu_s paths_per_s_cpu rmse_lum
row Cycles "$spp" "$tc" "$cc" "$(echo "$cyc_vs_ref" | field rmse rel_lum)" "(medians of $runs)"
if [ $glint_ok = yes ]; then
    g0=$out/glint-$tag-${spp}spp-seed0.exr
    gl_vs_ref=$(compare "$g0" "$ref")
    eq_vs_ref=$(compare "$eq" "$ref")
    eq_vs_own=$(compare "$eq" "$glint_ref")
    row Glint "$spp" "$tg" "$cg" "$(echo "$gl_vs_ref" | field rmse rel_lum)" "(medians of $runs)"
    row Glint "$eq_spp" "$teq" "$ceq" "$(echo "$eq_vs_ref" | field rmse rel_lum)" "(equal time)"
fi
echo
echo "render_s: each renderer's own render time; paths_per_s = pixels x spp / render_s."
echo "cpu_s: CPU seconds of the process over it (all threads); paths_per_s_cpu = pixels x spp x"
echo "  threads / cpu_s: less disturbed than render_s by other jobs, not immune (they share"
echo "  caches and cores). Load average now: $(cut -d' ' -f1 /proc/loadavg), on $(nproc) hardware threads."
echo "rmse_lum: RMSE of luminance against the Cycles reference, relative to its mean luminance;"
echo "  the reference's own noise is in it, at $spp/$ref_spp of the variance."
if [ $glint_ok = yes ]; then
    echo
    awk -v tc="$tc" -v tg="$tg" -v cc="$cc" -v cg="$cg" 'BEGIN {
        printf "Speed: Glint / Cycles samples per second = %.2f by render time, %.2f by CPU time" \
               " (goal: at least 2)\n", tc / tg, cc / cg}'
    echo "Equal time, relative RMSE of luminance against the Cycles reference: Cycles" \
        "$(echo "$cyc_vs_ref" | field rmse rel_lum) at $spp spp, Glint" \
        "$(echo "$eq_vs_ref" | field rmse rel_lum) at $eq_spp spp (against its own long render:" \
        "$(echo "$eq_vs_own" | field rmse rel_lum))"
    echo "Glint's --stats of its first $spp-spp run:"
    grep -E '^(Rays|Throughput|Time)' "$out/logs/glint-$tag-${spp}spp-seed0.log" | sed 's/^/  /'
fi

if [ $glint_ok = yes ]; then
    echo
    echo "Converged: Glint $glint_ref_spp spp (A) against Cycles $ref_spp spp (B):"
    compare "$glint_ref" "$ref" --max-rel 0.03 | sed 's/^/  /'
fi
if [ -n "$noise_c" ]; then
    # A pair's difference has twice the variance of one render at $spp spp; the variance of one
    # render falls as 1/spp. So Glint at G spp against Cycles at C spp differs by noise alone by
    # about sqrt(x_c^2 spp / 2C + x_g^2 spp / 2G), x the pairs' figures (as many blocks, so the
    # largest block's too, roughly). Without Glint: two Cycles renders at C spp, x_c sqrt(spp / C).
    echo
    awk -v mc="$(echo "$noise_c" | field mean_rel lum)" -v bc="$(echo "$noise_c" | field block_rel lum)" \
        -v mg="$(echo "$noise_g" | field mean_rel lum)" -v bg="$(echo "$noise_g" | field block_rel lum)" \
        -v s="$spp" -v c="$ref_spp" -v g="$glint_ref_spp" -v glint=$glint_ok 'BEGIN {
        printf "Noise alone, luminance: two Cycles renders at %d spp (seeds 0, 1) differ by %.4f" \
               " (image mean) and %.4f (largest 16x16 block)", s, mc, bc
        if (glint == "yes") {
            printf ", two Glint renders by %.4f and %.4f.\n", mg, bg
            printf "Noise alone would give Glint at %d spp against Cycles at %d spp about %.4f and" \
                   " %.4f.\n", g, c, sqrt(mc^2 * s / (2 * c) + mg^2 * s / (2 * g)),
                   sqrt(bc^2 * s / (2 * c) + bg^2 * s / (2 * g))
        } else {
            printf ": about %.4f and %.4f at %d spp.\n", mc * sqrt(s / c), bc * sqrt(s / c), c
        }}'
fi
if [ $glint_ok = no ]; then
    echo
    echo "Glint half skipped: $why"
fi
echo
echo "Images: $out/*.exr, previews $out/*.png; logs in $out/logs"
