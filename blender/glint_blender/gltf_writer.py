"""A glTF 2.0 document built in memory and written as a .gltf file with one .bin buffer.

The add-on hands Glint the scene as glTF, the richest format Glint reads: meshes placed by
nodes (one mesh placed many times is stored once and instanced), metallic-roughness materials
with their extensions, textures, punctual lights and cameras. Blender knows nothing of this
file: it is written to a temporary folder for each render and read back by `glint.load`.
"""

from __future__ import annotations

import json
import os

import numpy as np

# glTF's component types and accessor types.
_COMPONENT = {np.dtype(np.float32): 5126, np.dtype(np.uint32): 5125, np.dtype(np.uint16): 5123}
_TYPE = {1: "SCALAR", 2: "VEC2", 3: "VEC3", 4: "VEC4"}


class GltfWriter:
    """Collects a glTF document: `add_*` return the index of what they add."""

    def __init__(self) -> None:
        self.doc: dict = {
            "asset": {"version": "2.0", "generator": "Glint's Blender add-on"},
            "scene": 0,
            "scenes": [{"nodes": []}],
            "nodes": [],
        }
        self._chunks: list[bytes] = []
        self._length = 0
        self._extensions: set[str] = set()

    def _list(self, key: str) -> list:
        return self.doc.setdefault(key, [])

    def use_extension(self, name: str) -> None:
        self._extensions.add(name)

    def accessor(self, array: np.ndarray, *, target: int | None = None, bounds: bool = False) -> int:
        """An accessor of a C-contiguous array of rows (N x k) or of scalars (N)."""
        array = np.ascontiguousarray(array)
        width = 1 if array.ndim == 1 else array.shape[1]
        data = array.tobytes()
        pad = (-self._length) % 4
        if pad:
            self._chunks.append(b"\0" * pad)
            self._length += pad
        view = {"buffer": 0, "byteOffset": self._length, "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        self._chunks.append(data)
        self._length += len(data)
        views = self._list("bufferViews")
        views.append(view)
        acc = {
            "bufferView": len(views) - 1,
            "componentType": _COMPONENT[array.dtype],
            "count": int(array.shape[0]),
            "type": _TYPE[width],
        }
        if bounds and len(array):
            rows = array.reshape(len(array), width)
            acc["min"] = [float(v) for v in rows.min(axis=0)]
            acc["max"] = [float(v) for v in rows.max(axis=0)]
        accessors = self._list("accessors")
        accessors.append(acc)
        return len(accessors) - 1

    def add(self, key: str, item: dict) -> int:
        items = self._list(key)
        items.append(item)
        return len(items) - 1

    def add_node(self, node: dict, *, root: bool = False) -> int:
        index = self.add("nodes", node)
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def add_light(self, light: dict) -> int:
        self.use_extension("KHR_lights_punctual")
        lights = self.doc.setdefault("extensions", {}).setdefault(
            "KHR_lights_punctual", {"lights": []})["lights"]
        lights.append(light)
        return len(lights) - 1

    def write(self, folder: str, stem: str = "scene") -> str:
        """Writes stem.gltf and stem.bin in folder; returns the .gltf file's path."""
        os.makedirs(folder, exist_ok=True)
        doc = dict(self.doc)
        if self._length:
            doc["buffers"] = [{"uri": stem + ".bin", "byteLength": self._length}]
            with open(os.path.join(folder, stem + ".bin"), "wb") as f:
                for chunk in self._chunks:
                    f.write(chunk)
        if self._extensions:
            doc["extensionsUsed"] = sorted(self._extensions)
        path = os.path.join(folder, stem + ".gltf")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(doc, f)
        return path
