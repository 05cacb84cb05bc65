"""Renders a .blend file with Cycles or Glint for a comparison (bench/blender/run.sh):

    blender -b FILE.blend --python bench/blender/render.py -- ENGINE SPP OUT.exr [THREADS]

Both engines as docs/performance.md compares them: no denoiser, no adaptive sampling, no
clamping, Cycles' default bounces (12, 4 diffuse and glossy, 12 transmission), a box pixel
filter one pixel wide, a fixed seed, linear 32-bit EXR (and its pixels as OUT.npy). Prints
"seconds N" (the render alone). The add-on comes from $GLINT_BLENDER_DIR (build/blender).
"""

import os
import sys
import time

import bpy
import numpy as np

engine, spp, out = sys.argv[sys.argv.index("--") + 1:][:3]
rest = sys.argv[sys.argv.index("--") + 4:]
threads = int(rest[0]) if rest else 2
if engine == "GLINT" and not hasattr(bpy.types.Scene, "glint"):
    sys.path.insert(0, os.environ.get("GLINT_BLENDER_DIR", "build/blender"))
    import glint_blender
    glint_blender.register()
sc = bpy.context.scene
sc.render.engine = engine
sc.render.threads_mode, sc.render.threads = "FIXED", threads
sc.view_settings.view_transform = "Standard"
sc.render.image_settings.file_format = "OPEN_EXR"
sc.render.image_settings.color_depth = "32"
sc.render.filepath = out
if engine == "CYCLES":
    c = sc.cycles
    c.device, c.samples = "CPU", int(spp)
    c.use_denoising = c.use_adaptive_sampling = False
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.pixel_filter_type, c.filter_width = "BOX", 1.0
    c.seed = 0
else:
    g = sc.glint
    g.samples, g.use_denoising, g.use_adaptive_sampling = int(spp), False, False
    g.clamp_indirect = 0.0
    g.seed = 0
t = time.perf_counter()
bpy.ops.render.render(write_still=True)
print(f"seconds {time.perf_counter() - t:.3f}")
# The pixels as NumPy (rows from the top, RGB) beside the EXR, for compare.py.
img = bpy.data.images.load(out)
px = np.empty(img.size[0] * img.size[1] * img.channels, np.float32)
img.pixels.foreach_get(px)
np.save(out[:-4] + ".npy", px.reshape(img.size[1], img.size[0], -1)[::-1, :, :3])
