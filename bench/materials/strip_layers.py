#!/usr/bin/env python3
"""Writes a copy of a glTF file without its layer extensions (clearcoat, sheen, specular,
anisotropy, iridescence, dispersion, diffuse transmission), so that bench/materials/layers.sh
can time the same model with and without the layers:  strip_layers.py IN.gltf OUT.gltf
(OUT beside IN's buffers and images: layers.sh copies the model's folder first)."""
import json
import sys

LAYERS = {
    "KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular",
    "KHR_materials_anisotropy", "KHR_materials_iridescence", "KHR_materials_dispersion",
    "KHR_materials_diffuse_transmission",
}


def main():
    src, dst = sys.argv[1], sys.argv[2]
    with open(src) as f:
        gltf = json.load(f)
    for m in gltf.get("materials", []):
        ext = m.get("extensions", {})
        for name in list(ext):
            if name in LAYERS:
                del ext[name]
    for key in ("extensionsUsed", "extensionsRequired"):
        if key in gltf:
            gltf[key] = [e for e in gltf[key] if e not in LAYERS]
    with open(dst, "w") as f:
        json.dump(gltf, f)


if __name__ == "__main__":
    main()
