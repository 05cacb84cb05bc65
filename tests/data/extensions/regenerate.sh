#!/usr/bin/env bash
# Re-renders the accepted images of the extension example scenes (see
# tests/render/extensions_golden_test.cpp). Run from the repository root after a deliberate
# change of behaviour, look at every image, and commit them with the change.
set -euo pipefail
glint=${1:-build/glint}
for scene in shapes glass arealight dof antialias cornell; do
    "$glint" "scenes/$scene.test" --size 160x90 --seed 0 -q -o "tests/data/extensions/$scene.png"
done
