#!/usr/bin/env bash
# Whole renders of the benchmark scenes of issue 3, Glint against POV-Ray 3.7 on the same scenes
# (bench/gen_scenes.cpp writes each as NAME.test and NAME.pov), 1280x720, 2 threads, at 1 and
# 16 camera rays per pixel. Prints medians of RUNS runs:
#   - trace time of each renderer (Glint's `render` from --stats, POV-Ray's "Trace Time"; neither
#     includes start-up, parsing or acceleration-structure build) and the ratio POV-Ray / Glint;
#   - for the 1M-triangle torus, scene loading: Glint's parse + BVH build against POV-Ray's
#     parse (which builds its mesh bounding tree) + bounding time;
#   - Glint's thread scaling: 16-spp render time on 1 thread / on 2 threads.
# Usage: bench/render_compare.sh BUILD_DIR [RUNS]
#   BUILD_DIR holds glint and bench/glint_bench_scenes (configure with -DGLINT_BUILD_BENCH=ON).
set -euo pipefail

usage() { echo "usage: $0 BUILD_DIR [RUNS]" >&2; exit 2; }
if [ $# -lt 1 ] || [ $# -gt 2 ]; then usage; fi
build=$(cd "$1" && pwd) || usage
runs=${2:-3}
[[ $runs =~ ^[1-9][0-9]*$ ]] || usage

glint=$build/glint
gen=$build/bench/glint_bench_scenes
scenes=$build/bench/scenes
imgdiff=$build/imgdiff
threads=2
names=(spheres mirrors torus)

for exe in "$glint" "$gen"; do
    if [ ! -x "$exe" ]; then
        echo "render_compare: $exe not found; build $build with -DGLINT_BUILD_BENCH=ON" >&2
        exit 1
    fi
done
if ! command -v povray >/dev/null; then
    echo "render_compare: povray not found (apt-get install povray, or make bench)" >&2
    exit 1
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# --- Scenes: regenerate when missing or older than the generator. ---------------------------
stamp=$scenes/.generated
fresh=yes
[ -f "$stamp" ] && [ ! "$gen" -nt "$stamp" ] || fresh=no
for n in "${names[@]}"; do
    [ -f "$scenes/$n.test" ] && [ -f "$scenes/$n.pov" ] || fresh=no
done
if [ $fresh = no ]; then
    echo "Generating the scenes in $scenes ..."
    "$gen" "$scenes"
    touch "$stamp"
fi

# --- POV-Ray set-up. ------------------------------------------------------------------------
# A private HOME with an empty user configuration file: POV-Ray stops complaining that it
# cannot open ~/.povray/3.7/povray.conf and keeps the system's I/O restrictions. It runs in
# $tmp (a permitted write directory) and writes its image there.
mkdir -p "$tmp/home/.povray/3.7" "$tmp/pov"
: >"$tmp/home/.povray/3.7/povray.conf"
# 16 camera rays per pixel: method 1 (non-recursive) antialiasing with threshold 0 supersamples
# every pixel on a jittered 4x4 grid (+R4), after one first ray per pixel; POV-Ray also traces
# the pixels along each 32x32 render block's border again. The exact count is taken from its
# statistics (Pixels + Samples) and printed.
pov_aa_1=(-A)
pov_aa_16=(+A0.0 +AM1 +R4 +J)
# Linear output (File_Gamma 1, as the scenes' assumed_gamma), like Glint's PNG: lets the images
# be compared pixel for pixel.
pov_common=(-D -P "+WT$threads" +FN File_Gamma=1.0)

size_of() { awk '$1 == "size" {w = $2; h = $3} END {print w, h}' "$1"; }

# run_glint SCENE SPP THREADS -> "render parse build camera_rays shadow_rays reflection_rays"
run_glint() {
    local out=$tmp/glint-$1-$2.png
    "$glint" -q --stats -t "$3" --spp "$2" "$scenes/$1.test" -o "$out" >"$tmp/glint.stats"
    awk '/^Time/ {for (i = 1; i < NF; i++) {
                     if ($i == "parse") p = $(i + 1); if ($i == "build") b = $(i + 1)
                     if ($i == "render") r = $(i + 1)}}
         /^Rays/ {for (i = 2; i <= NF; i++) {
                     if ($i ~ /^camera/) c = $(i - 1); if ($i ~ /^shadow/) sh = $(i - 1)
                     if ($i ~ /^reflection/) rf = $(i - 1)}}
         END {if (r == "" || c == "") exit 1; print r, p, b, c, sh + 0, rf + 0}' "$tmp/glint.stats" || {
        echo "render_compare: cannot read glint --stats output:" >&2
        cat "$tmp/glint.stats" >&2
        exit 1
    }
}

# run_pov SCENE SPP -> "trace parse camera_rays shadow_rays reflected_rays"
run_pov() {
    local aa log=$tmp/pov.log w h
    read -r w h < <(size_of "$scenes/$1.test")
    if [ "$2" = 1 ]; then aa=("${pov_aa_1[@]}"); else aa=("${pov_aa_16[@]}"); fi
    if ! (cd "$tmp/pov" && HOME=$tmp/home povray "+I$scenes/$1.pov" "+O$1-$2.png" "+W$w" "+H$h" \
        "${pov_common[@]}" "${aa[@]}" >"$log" 2>&1); then
        echo "render_compare: povray failed on $1.pov:" >&2
        tr '\r' '\n' <"$log" | grep -v '^Rendered' | tail -20 >&2
        exit 1
    fi
    tr '\r' '\n' <"$log" | awk '
        function secs(line) { sub(/.*\(/, "", line); sub(/ seconds\).*/, "", line); return line }
        /Trace Time:/ {t = secs($0)}
        /Parse Time:/ {p = secs($0)}
        /Bounding Time:/ {bt = secs($0)}
        /^Pixels:/ {px = $2; s = $4}
        /^Shadow Ray Tests:/ {sh = $4}
        /^Reflected Rays:/ {rf = $3}
        END {if (t == "" || px == "") exit 1; print t, p + bt, px + s, sh + 0, rf + 0}' || {
        echo "render_compare: cannot read POV-Ray's statistics:" >&2
        tr '\r' '\n' <"$log" | grep -v '^Rendered' | tail -40 >&2
        exit 1
    }
    if [ "$2" = 1 ]; then cp "$tmp/pov/$1-$2.png" "$tmp/pov-$1-$2.png"; fi
}

median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2)}'; }
col() { cut -d' ' -f"$1" "$2" | median; }

pov_version=$(HOME=$tmp/home povray --version 2>&1 | sed -n 's/^POV-Ray \([0-9][0-9.]*[0-9]\).*/\1/p')
echo "Whole renders: Glint vs POV-Ray ${pov_version:-?}," \
    "1280x720, $threads threads, medians of $runs runs"
echo "POV-Ray: ${pov_common[*]}; 1 spp: ${pov_aa_1[*]}; 16 spp: ${pov_aa_16[*]}"
echo "Seconds are trace time only (no start-up, parse or BVH build). rays/px = camera rays per"
echo "pixel each renderer reported; per-ray = the ratio scaled to equal camera rays."
echo
echo "1-minute load average at start: $(cut -d' ' -f1 /proc/loadavg) (on $(nproc) hardware threads)"
echo
printf '%-8s %4s %11s %11s %9s %9s %10s %8s\n' \
    scene spp glint_ray/px pov_ray/px glint_s povray_s pov/glint per-ray
for n in "${names[@]}"; do
    read -r w h < <(size_of "$scenes/$n.test")
    : >"$tmp/load-$n"
    for spp in 1 16; do
        : >"$tmp/g" && : >"$tmp/p"
        for ((i = 0; i < runs; i++)); do
            run_glint "$n" "$spp" "$threads" >>"$tmp/g"
            run_pov "$n" "$spp" >>"$tmp/p"
        done
        gs=$(col 1 "$tmp/g") ps=$(col 1 "$tmp/p")
        grays=$(tail -1 "$tmp/g" | cut -d' ' -f4) prays=$(tail -1 "$tmp/p" | cut -d' ' -f3)
        awk -v n="$n" -v spp="$spp" -v gs="$gs" -v ps="$ps" -v gr="$grays" -v pr="$prays" -v px=$((w * h)) '
            BEGIN {printf "%-8s %4d %11.2f %11.2f %9.3f %9.3f %10.2f %8.2f\n",
                   n, spp, gr / px, pr / px, gs, ps, ps / gs, (ps / pr) / (gs / gr)}'
        # Scene loading: Glint parse + build, POV-Ray parse + bounding, from every run.
        paste -d' ' <(cut -d' ' -f2,3 "$tmp/g") <(cut -d' ' -f2 "$tmp/p") >>"$tmp/load-$n"
        if [ "$spp" = 1 ]; then
            echo "$n $(tail -1 "$tmp/g" | cut -d' ' -f5,6) $(tail -1 "$tmp/p" | cut -d' ' -f4,5)" >>"$tmp/work"
        fi
        if [ "$spp" = 16 ]; then
            : >"$tmp/g1"
            for ((i = 0; i < runs; i++)); do run_glint "$n" 16 1 >>"$tmp/g1"; done
            echo "$n $(col 1 "$tmp/g1") $gs" >>"$tmp/scaling"
        fi
    done
done

echo
echo "Scene loading, torus (1,000,002 triangles; $(du -m "$scenes/torus.test" | cut -f1) MB Glint file," \
    "$(du -m "$scenes/torus.pov" | cut -f1) MB POV-Ray file), medians of $((2 * runs)) runs"
printf '%-8s %9s %9s %13s %13s %10s\n' scene parse_s build_s glint_total_s povray_parse_s pov/glint
awk '{print $1 + $2, $1, $2, $3}' "$tmp/load-torus" >"$tmp/load"
gl=$(col 1 "$tmp/load") gp=$(col 2 "$tmp/load") gb=$(col 3 "$tmp/load") pp=$(col 4 "$tmp/load")
awk -v gl="$gl" -v gp="$gp" -v gb="$gb" -v pp="$pp" \
    'BEGIN {printf "%-8s %9.3f %9.3f %13.3f %13.3f %10.2f\n", "torus", gp, gb, gl, pp, pp / gl}'

echo
echo "Glint thread scaling, 16 spp: render seconds on 1 and $threads threads"
printf '%-8s %9s %9s %9s\n' scene 1_thread "${threads}_threads" speedup
awk '{printf "%-8s %9.3f %9.3f %9.2f\n", $1, $2, $3, $2 / $3}' "$tmp/scaling"

echo
echo "Same work, same picture? 1 spp, each renderer's own counts. POV-Ray's reflected rays include"
echo "those it stops at max_trace_level before tracing them; image: pixels whose largest channel"
echo "differs by more than 2/255 between the two PNGs (linear, 8-bit)."
printf '%-8s %12s %12s %12s %12s %12s\n' scene glint_shadow pov_shadow glint_refl pov_refl image_diff
while read -r n gsh grf psh prf; do
    hot="-"
    if [ -x "$imgdiff" ]; then
        hot=$("$imgdiff" --threshold 2 --budget 1000000000 "$tmp/glint-$n-1.png" "$tmp/pov-$n-1.png" |
            awk '/^threshold 2:/ {print $3}') || true
    fi
    printf '%-8s %12d %12d %12d %12d %12s\n' "$n" "$gsh" "$psh" "$grf" "$prf" "${hot:-?}"
done <"$tmp/work"
