#!/usr/bin/env bash
# Re-renders the accepted image of the mesh golden scene (tests/render/mesh_golden_test.cpp).
# Run from the repository root after a deliberate change of behaviour, look at the image, and
# commit it with the change.
set -euo pipefail
glint=${1:-build/glint}
"$glint" tests/data/meshes/textured-scene.test --seed 0 -q -o tests/data/meshes/textured-scene.png
