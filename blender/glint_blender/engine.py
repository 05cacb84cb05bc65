"""The render engine Blender calls: F12, `blender -b FILE -E GLINT -f N`, and `-a`.

A render translates the evaluated depsgraph (export.py), loads it with the `glint` module and
renders it in rounds of samples (1, 1, 2, 4, ...), each shown in the Render Result as it
comes, until the samples or the time limit are reached or Esc is pressed (the rounds done are
kept). The denoiser runs on the whole once the rounds are done. With adaptive sampling on,
after a first round the rest is one adaptive render of Glint's (its per-pixel stopping rule).
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
import time

import bpy
import numpy as np

from . import glint_module
from .export import Exporter, render_size

# Blender's pass names and channels, and Glint's pass for each.
_PASSES = {
    "Depth": (1, "Z", "VALUE", "depth"),
    "Denoising Normal": (3, "XYZ", "VECTOR", "normal"),
    "Denoising Albedo": (3, "RGB", "COLOR", "albedo"),
}


# Samples per pixel after which rounds no longer compute the passes.
_PASS_SAMPLES = 16


class _Stopped(Exception):
    """Raised in the progress callback when Blender asks the render to stop."""


def bounce_limits(s) -> str:
    """Cycles' Light Paths as Glint's --max-bounces (Glint counts the camera's hit: +1)."""
    return ",".join(f"{k}={min(max(v + 1, 1), 64)}" for k, v in (
        ("total", s.max_bounces), ("diffuse", s.diffuse_bounces), ("glossy", s.glossy_bounces),
        ("transmission", s.transmission_bounces), ("volume", s.volume_bounces)))


def _arg(value) -> str:
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, tuple):
        return "x".join(str(v) for v in value)
    return str(value)


def render_threads(scene) -> int:
    r = scene.render
    return int(r.threads) if r.threads_mode == "FIXED" else 0


class GlintRenderEngine(bpy.types.RenderEngine):
    bl_idname = "GLINT"
    bl_label = "Glint"
    bl_use_preview = False
    bl_use_postprocess = True
    bl_use_eevee_viewport = True

    def update_render_passes(self, scene=None, renderlayer=None):
        self.register_pass(scene, renderlayer, "Combined", 4, "RGBA", "COLOR")
        for name, (channels, ids, kind, _) in _PASSES.items():
            if name == "Depth" and not renderlayer.use_pass_z:
                continue
            if name != "Depth" and not scene.glint.denoising_passes:
                continue
            self.register_pass(scene, renderlayer, name, channels, ids, kind)

    def should_stop(self) -> bool:
        """Esc in Blender (a method of ours, which tests can replace)."""
        return self.test_break()

    # ---- messages ---------------------------------------------------------------------------

    def _warn(self, text: str) -> None:
        print(f"glint: warning: {text}", file=sys.stderr)
        self.report({"WARNING"}, f"Glint: {text}")

    # ---- the render -----------------------------------------------------------------------

    def render(self, depsgraph):
        scene = depsgraph.scene
        glint = glint_module()
        keep = os.environ.get("GLINT_BLENDER_KEEP", "")
        with tempfile.TemporaryDirectory(prefix="glint-blender-") as scratch:
            # GLINT_BLENDER_KEEP=DIR keeps the translation there (glint DIR/scene.gltf renders it).
            folder = os.path.join(keep, f"frame{scene.frame_current:04d}") if keep else scratch
            if keep:
                os.makedirs(folder, exist_ok=True)
                for name in os.listdir(folder):
                    os.remove(os.path.join(folder, name))
            t0 = time.perf_counter()
            self.update_stats("", "Glint | translating the scene")
            exported = Exporter(depsgraph, folder, self._warn).run()
            s = scene.glint
            options = dict(integrator="path", environment="none", ground="none",
                           camera=exported.camera or "none", size=exported.size,
                           max_bounces=bounce_limits(s), caustics=s.caustics)
            if s.clamp_indirect > 0:
                options["clamp_indirect"] = s.clamp_indirect
            try:
                gs = glint.load(exported.path, **options)
                if exported.environment is not None:
                    e = exported.environment
                    gs.environment(e.pixels, e.strength, e.rotation)
                    if keep:
                        glint.write(os.path.join(folder, "environment.exr"),
                                    e.pixels * np.float32(e.strength))
                if exported.lens is not None:
                    gs.camera = dict(aperture=exported.lens.aperture, focus=exported.lens.focus)
            except (glint.SceneError, glint.RenderError, ValueError) as e:
                self.report({"ERROR"}, f"Glint: {e}")
                print(f"glint: error: {e}", file=sys.stderr)
                return
            translate = time.perf_counter() - t0
            if keep:
                with open(os.path.join(folder, "options.txt"), "w") as f:
                    f.write(" ".join(f"--{k.replace('_', '-')} {_arg(v)}" for k, v in
                                     options.items()) + "\n")
            print(f"glint: translated {exported.triangles} triangles, {exported.meshes} meshes "
                  f"placed {exported.instances} times in {translate:.2f} s", file=sys.stderr)
            self._render_rounds(scene, gs, glint, exported.size)

    def _render_rounds(self, scene, gs, glint, size) -> None:
        s = scene.glint
        w, h = size
        layer_name = bpy.context.view_layer.name if bpy.context.view_layer else ""
        view_layer = scene.view_layers.get(layer_name) or scene.view_layers[0]
        # The passes (the denoiser's guides, Depth) settle within a few samples: they are
        # taken from the rounds up to _PASS_SAMPLES, which cost more with them.
        want = ["albedo", "normal", "depth"]
        pass_weight = 0.0
        threads = render_threads(scene)
        seed = s.seed + (scene.frame_current if s.use_animated_seed else 0)
        total = max(1, s.samples)
        limit = s.time_limit if s.time_limit > 0 else math.inf
        start = time.perf_counter()
        result = self.begin_result(0, 0, w, h, layer=view_layer.name)
        acc = None
        acc_passes: dict = {}
        done = 0
        rounds = 0
        stopped = False
        while done < total:
            # Rounds double what was done; with adaptive sampling, the rest is one render.
            adaptive = s.use_adaptive_sampling and rounds > 0
            n = total - done if adaptive else min(max(1, done), total - done)
            base = done

            def progress(fraction, seconds, base=base, n=n):
                if self.should_stop():
                    raise _Stopped()
                self.update_progress(min((base + fraction * n) / total, 1.0))
                self.update_stats("", f"Glint | Sample {base + int(fraction * n)}/{total}")

            with_passes = done < _PASS_SAMPLES
            opts = dict(spp=n, seed=seed * 65537 + rounds, denoise=False, progress=progress)
            if with_passes:
                opts["aov"] = want
            if threads > 0:
                opts["threads"] = threads
            if adaptive:
                opts["noise_threshold"] = s.adaptive_threshold
                if s.adaptive_min_samples > 0:
                    opts["min_spp"] = s.adaptive_min_samples
            try:
                image = gs.render(**opts)
            except _Stopped:
                stopped = True
                break
            rounds += 1
            weight = float(n)
            acc = np.asarray(image, np.float64) * weight + (0 if acc is None else acc)
            if with_passes:
                for k, v in image.passes.items():
                    acc_passes[k] = np.asarray(v, np.float64) * weight + acc_passes.get(k, 0)
                pass_weight += weight
            done += n
            if done < total:
                self._write(scene, result, acc / done,
                            {k: v / pass_weight for k, v in acc_passes.items()})
                self.update_result(result)
            if time.perf_counter() - start >= limit:
                break
        if acc is None:
            self.end_result(result, cancel=False)
            return
        image = (acc / done).astype(np.float32)
        passes = {k: (v / pass_weight).astype(np.float32) for k, v in acc_passes.items()}
        if s.use_denoising and not stopped:
            self.update_stats("", "Glint | denoising")
            denoised = glint.denoise(image, passes=passes, denoiser=s.denoiser.lower(),
                                     threads=threads)
            image = np.asarray(denoised)
        self._write(scene, result, image, passes)
        self.update_progress(1.0)
        self.end_result(result)
        seconds = time.perf_counter() - start
        print(f"glint: rendered {done} samples per pixel in {seconds:.2f} s"
              + (" (stopped)" if stopped else ""), file=sys.stderr)

    def _write(self, scene, result, image, passes) -> None:
        """The image (rows x columns x 3, row 0 at the top) and its passes into the result."""
        layer = result.layers[0]
        h, w = image.shape[:2]
        rgba = np.ones((h, w, 4), np.float32)
        rgba[:, :, :3] = image
        depth = passes.get("depth")
        if scene.render.film_transparent and depth is not None:
            covered = (depth > 0).astype(np.float32)
            rgba[:, :, :3] *= covered[:, :, None]
            rgba[:, :, 3] = covered
        _set(layer.passes["Combined"], rgba)
        for name, (channels, _, _, glint_name) in _PASSES.items():
            target = layer.passes.get(name)
            value = passes.get(glint_name)
            if target is None or value is None:
                continue
            if glint_name == "depth":
                value = np.where(value > 0, value, 1e10).astype(np.float32)
            elif glint_name == "normal":  # Glint's y-up to Blender's z-up
                value = np.stack([value[..., 0], -value[..., 2], value[..., 1]], -1)
            _set(target, np.asarray(value, np.float32).reshape(h, w, channels))


def _set(render_pass, pixels: np.ndarray) -> None:
    """Blender's passes run from the bottom row up."""
    flat = np.ascontiguousarray(pixels[::-1]).reshape(-1)
    try:
        render_pass.rect.foreach_set(flat)
    except (AttributeError, TypeError):
        render_pass.rect = flat.reshape(-1, pixels.shape[-1]).tolist()
