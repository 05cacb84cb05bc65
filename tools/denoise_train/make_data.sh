#!/usr/bin/env bash
# Renders the denoiser's training data (tools/denoise_train/README.md): every training scene
# (views.py lists them: the shared glTF models and meshes, the course-format scenes, the
# repository's scenes, random scenes from gen_scenes.py and glint_bench_scenes; never the
# benchmark's held-out scenes) from a few random, reproducible views, each at 1, 4, 16 and 64
# spp with every render pass (glint --aov all --no-denoise) and a reference at REF_SPP (default
# 1024, for speed; OIDN's own data and bench/denoise use 4096), split into PFM files:
#   OUT/VIEW_SPP.pfm, .albedo.pfm, .normal.pfm;  OUT/VIEW_ref.pfm (colour alone)
# Each render has its own --seed, so the noise of the inputs and of the reference is
# independent. Existing outputs are skipped: a stopped run goes on where it was.
# Usage: make_data.sh BUILD_DIR OUT_DIR [REF_SPP [SIZE [NAME...]]]
#   BUILD_DIR holds glint and bench/glint_aov_split (and bench/glint_bench_scenes);
#   SIZE WxH, default 256x192; NAME... keeps the views whose ID contains one of the words.
# Environment: VIEWS (views per scene, default 3), GENERATED (random scenes, default 40),
#   THREADS (glint's threads, default 2), LIMIT (seconds per render, default 900: a scene
#   slower than that is skipped with a message), KEEP_EXR=1 to keep the EXRs, LIST_ONLY=1 to
#   write OUT/views.tsv (and the generated scenes) and stop.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
build=${1:?build dir}
out=${2:?output dir}
ref=${3:-1024}
size=${4:-256x192}
shift $(($# < 4 ? $# : 4))
names=("$@")
shared=${SHARED:-$repo/../shared}
[ -d "$shared/real-world" ] || shared=/work/shared
python=/usr/bin/python3
glint=$build/glint
split=$build/bench/glint_aov_split
mkdir -p "$out/scenes"
out=$(cd "$out" && pwd)

# The generated scenes: random ones, and the whole-render benchmark's spheres and mirrors.
"$python" "$here/gen_scenes.py" "$out/scenes" "${GENERATED:-40}"
if [ -x "$build/bench/glint_bench_scenes" ] && [ ! -f "$out/scenes/spheres.test" ]; then
    tmp=$(mktemp -d)
    "$build/bench/glint_bench_scenes" "$tmp" >/dev/null
    cp "$tmp/spheres.test" "$tmp/mirrors.test" "$out/scenes/"
    rm -rf "$tmp"
fi

"$python" "$here/views.py" "$glint" "$shared" "$repo" "$out/scenes" "${VIEWS:-3}" "$size" \
    "${names[@]}" >"$out/views.tsv"
echo "make_data: $(wc -l <"$out/views.tsv") views in $out/views.tsv"
[ -z "${LIST_ONLY:-}" ] || exit 0

render() {  # VIEW SCENE ARGS SPP SEED NAME
    local view=$1 scene=$2 args=$3 spp=$4 seed=$5 name=$6
    [ -f "$out/${view}_$name.pfm" ] && return 0
    # shellcheck disable=SC2086  # args: words without spaces (views.py)
    if ! timeout "${LIMIT:-900}" "$glint" "$scene" $args --size "$size" --spp "$spp" \
        --seed "$seed" --no-denoise --aov all -q -t "${THREADS:-2}" \
        -o "$out/${view}_$name.exr" 2>"$out/${view}_$name.log"; then
        echo "make_data: $view at $spp spp failed or took too long (${view}_$name.log)" >&2
        rm -f "$out/${view}_$name.exr"
        return 1
    fi
    "$split" "$out/${view}_$name.exr" "$out/${view}_$name" >/dev/null
    # Kept: colour, albedo and normal (the reference's colour alone).
    local f
    for f in "$out/${view}_$name".*; do
        case $f in
            "$out/${view}_$name.pfm") ;;
            *.albedo.pfm | *.normal.pfm) [ "$name" = ref ] && rm -f "$f" ;;
            *.exr) [ -n "${KEEP_EXR:-}" ] || rm -f "$f" ;;
            *) rm -f "$f" ;;
        esac
    done
}

while IFS=$'\t' read -r view scene args; do
    # The reference first: a view whose reference cannot be rendered is not worth its inputs.
    render "$view" "$scene" "$args" "$ref" 1000 ref || continue
    k=0
    for spp in 1 4 16 64; do
        k=$((k + 1))
        render "$view" "$scene" "$args" "$spp" "$k" "$spp" || break
    done
    echo "make_data: $view"
done <"$out/views.tsv"
