#!/bin/bash
# bench/model_budget.sh OLD_GLINT NEW_GLINT REPS: the model mode's default render time (the
# "render" of --stats, seconds) and mean samples per pixel of four shared models, each run REPS
# times, for two builds in turn. Run it once idle and once beside a load (docs/performance.md
# section 21: two "yes > /dev/null" on the 2 cores).
X=$(cd "$(dirname "$0")/.." && pwd)/../shared/real-world
models="$(ls $X/gltf-ext/ToyCar/glTF*/ToyCar.gltf) $(ls $X/gltf/DamagedHelmet/glTF*/*.gltf|head -1) $(ls $X/gltf-ext/SheenChair/glTF*/*.gltf|head -1) $(ls $X/gltf-ext/GlassVaseFlowers/glTF*/*.gltf|head -1)"
for m in $models; do for b in $1 $2; do ts=""; for i in $(seq $3); do
  out=$($b $m -o "${TMPDIR:-/tmp}/model_budget.png" --stats 2>&1); r=$(echo "$out" | grep "^Time" | sed 's/.*render \([0-9.]*\) s.*/\1/'); s=$(echo "$out" | grep "adaptive sampling" | sed 's/.*: \([0-9.]*\) samples per pixel on average.*/\1/'); ts="$ts $r/$s"; done
  echo "$(basename $m .gltf) $(basename $b):$ts"; done; done
