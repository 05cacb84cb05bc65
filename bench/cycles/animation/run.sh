#!/usr/bin/env bash
# Glint's animation against Blender Cycles (issue 24, "Against Blender Cycles"): Khronos'
# BoxAnimated (three frames) and CesiumMan (two), rendered by Glint and by Cycles (Blender's glTF
# importer, the scene at 24 fps: Blender's frame N is glTF time N / 24 s, Glint's --frame N)
# through the same orbit camera; their silhouettes compared by IoU at each frame, and between the
# frames to show what another pose scores (bench/cycles/animation/README.md).
#
# Usage: bench/cycles/animation/run.sh [OPTIONS] BUILD_DIR [OUT_DIR]
#   BUILD_DIR  holds glint
#   OUT_DIR    renders, logs and the picture [cycles-animation-out beside the repository];
#              Cycles' renders are kept there and reused (delete them to render anew)
# Options (defaults in brackets):
#   --size WxH [480x270]  --spp N [64: both renderers]  --threads N [2]
#   --supersample K [8: Glint's silhouette from K x K rays per pixel]
#   --docs DIR  copy the picture to DIR/animation-cycles.png
#   --models DIR  Khronos' samples [../shared/real-world/gltf-ext beside the repository]
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../../.." && pwd)
usage() {
    sed -n '/^# Usage:/,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
    exit 2
}
size=480x270 spp=64 threads=2 k=8 docs= models=$repo/../shared/real-world/gltf-ext
positional=()
while [ $# -gt 0 ]; do
    case $1 in
        --size) size=${2:?}; shift 2 ;;
        --spp) spp=${2:?}; shift 2 ;;
        --threads) threads=${2:?}; shift 2 ;;
        --supersample) k=${2:?}; shift 2 ;;
        --docs) docs=${2:?}; shift 2 ;;
        --models) models=${2:?}; shift 2 ;;
        -h | --help) usage ;;
        -*) echo "run.sh: unknown option $1" >&2; usage ;;
        *) positional+=("$1"); shift ;;
    esac
done
[ ${#positional[@]} -ge 1 ] && [ ${#positional[@]} -le 2 ] || usage
[[ $size =~ ^([1-9][0-9]*)x([1-9][0-9]*)$ ]] || { echo "run.sh: --size is WxH" >&2; exit 2; }
w=${BASH_REMATCH[1]} h=${BASH_REMATCH[2]}
build=$(cd "${positional[0]}" && pwd)
out=${positional[1]:-$repo/../cycles-animation-out}
mkdir -p "$out/logs"
out=$(cd "$out" && pwd)
glint=$build/glint
[ -x "$glint" ] || { echo "run.sh: $glint not found: build it first" >&2; exit 1; }
command -v blender >/dev/null || {
    echo "run.sh: blender not found (apt-get install --no-install-recommends blender python3-numpy)" >&2
    exit 1
}

# MODEL LABEL FRAME ORBIT [GLINT_SECONDS]. ORBIT: Glint's own framing of the model (its note
# prints the camera: eye on (0, 0.5, 1) from the centre of the bounds over the whole
# animation, fovy 40), turned 30 degrees about +y so that the pose reads in three quarters.
# BoxAnimated: frame 20 (0.83 s) rising, frame 45 (1.875 s) half-way through its turn, where
# linear interpolation of quaternion components (Blender's F-curves) and slerp (glTF's, Glint's)
# agree, and frame 40 (1.67 s), a third of the way, where they do not: Blender's box has turned
# 2 atan(1/2) = 53.13 degrees, glTF's 60. `40nlerp` is Cycles' frame 40 against Glint at the
# time its slerp reaches 53.13 degrees: 1.25 + 1.25 x 53.13 / 180 = 1.618959 s.
# CesiumMan's keys are 1/24 s apart: frames 10 and 30 fall on keys.
box_orbit=30,63.435,6.323,0,1.308,0
man_orbit=30,63.435,3.06,-0.05234,0.7528,-0.0201
views=(
    "BoxAnimated 20 20 $box_orbit"
    "BoxAnimated 45 45 $box_orbit"
    "BoxAnimated 40 40 $box_orbit"
    "BoxAnimated 40nlerp 40 $box_orbit 1.618959"
    "CesiumMan 10 10 $man_orbit"
    "CesiumMan 30 30 $man_orbit"
)
draw=BoxAnimated:20,BoxAnimated:45,BoxAnimated:40,CesiumMan:10,CesiumMan:30
names=()
for v in "${views[@]}"; do
    read -r model label frame orbit seconds <<<"$v"
    gltf=$models/$model/glTF/$model.gltf
    [ -f "$gltf" ] || { echo "run.sh: $gltf not found (--models names the folder)" >&2; exit 1; }
    stem=${model}_$label
    names+=("$model:$label")
    when=(--frame "$frame" --fps 24)
    [ -n "$seconds" ] && when=(--time-at "$seconds")
    look=("${when[@]}" --camera "orbit:$orbit" --fov 40 --environment none --ground none
        --no-denoise -t "$threads" -q)
    "$glint" "$gltf" "${look[@]}" --size "$size" --spp "$spp" -o "$out/glint_$stem.exr"
    "$glint" "$gltf" "${look[@]}" --size "$((k * w))x$((k * h))" --spp 1 --aov depth \
        -o "$out/mask_$stem.exr"
    cycles=cycles_${model}_$frame
    if [ ! -f "$out/$cycles.exr" ]; then
        blender -b --factory-startup --python "$here/anim_cycles.py" -- --gltf "$gltf" \
            --frame "$frame" --fps 24 --orbit "$orbit" --fovy 40 --size "$w" "$h" --spp "$spp" \
            --threads "$threads" --out "$out/$cycles.exr" >"$out/logs/$cycles.log" 2>&1 || {
            tail -20 "$out/logs/$cycles.log" >&2
            exit 1
        }
    fi
    [ "$cycles" = "cycles_$stem" ] || cp "$out/$cycles.exr" "$out/cycles_$stem.exr"
    grep -h "^anim_cycles.py: frame\|^CYCLES_RESULT" "$out/logs/$cycles.log"
done
blender -b --factory-startup --python "$here/silhouettes.py" -- --out "$out" \
    --png "$out/animation-cycles.png" --draw "$draw" "${names[@]}" >"$out/logs/silhouettes.log" 2>&1 || {
    tail -20 "$out/logs/silhouettes.log" >&2
    exit 1
}
grep -h "^SILHOUETTE\|^BETWEEN\|^silhouettes.py" "$out/logs/silhouettes.log" | tee "$out/iou.txt"
if [ -n "$docs" ]; then
    cp "$out/animation-cycles.png" "$docs/animation-cycles.png"
    echo "run.sh: copied the picture to $docs/animation-cycles.png"
fi
