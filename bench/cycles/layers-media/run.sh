#!/usr/bin/env bash
# Layers and media in Glint's path tracer against Blender Cycles 3.4 (issue 23; README.md
# here). Renders this folder's scenes in both through ../gltf/run.sh (its gltf_cycles.py
# builds each in Cycles) and compares them: the layered Khronos models at 512 spp, the media
# at 256 spp, Glint's fog at 1024 (Cycles' renders are kept in OUT_DIR and reused).
#
# Usage: bench/cycles/layers-media/run.sh [OPTIONS] BUILD_DIR [OUT_DIR]
#   BUILD_DIR  holds glint, imgdiff and tools/glint_make_smoke_vdb (make build)
#   OUT_DIR    default: cycles-layers-media-out beside the repository
#   OPTIONS    ../gltf/run.sh's, e.g. --docs docs/images (copies the side-by-side PNGs there
#              as cycles-ASSET.png), --threads N, --spp N (both sets)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
run=$here/../gltf/run.sh
"$run" --tests "$here" --docs-prefix cycles- --spp 512 \
    --assets "layers-clearcoat layers-sheen layers-sheen-v1 layers-specular" "$@"
"$run" --tests "$here" --docs-prefix cycles- --spp 256 \
    --assets "media-smoke media-sss" "$@"
# Glint's fog is noisier at equal samples (below), so it gets four times Cycles' 256.
"$run" --tests "$here" --docs-prefix cycles- --spp 1024 --cycles-spp 256 \
    --assets "media-fog" "$@"
