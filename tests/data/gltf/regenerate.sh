#!/usr/bin/env bash
# Re-renders the accepted image of the glTF golden scene (tests/render/gltf_golden_test.cpp).
# Run from the repository root after a deliberate change of behaviour, look at the image, and
# commit it with the change. (The glTF files themselves are written by make_gltf.py here.)
set -euo pipefail
glint=${1:-build/glint}
"$glint" tests/data/gltf/scene.glb --size 160x90 --seed 0 -q -o tests/data/gltf/scene.png
