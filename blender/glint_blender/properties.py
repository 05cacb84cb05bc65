"""Glint's render settings, kept in the .blend file as scene.glint. The defaults are Cycles'
(128 samples, 12 bounces, 4 diffuse and glossy, 12 transmission, 0 volume, clamp indirect 10),
so that a scene set up for Cycles renders alike."""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty


class GlintSceneSettings(bpy.types.PropertyGroup):
    samples: IntProperty(name="Samples", description="Samples per pixel", default=128, min=1,
                         max=65536)
    time_limit: FloatProperty(name="Time Limit", description="Stop after this many seconds "
                              "(0: no limit)", default=0.0, min=0.0, subtype="TIME_ABSOLUTE")
    seed: IntProperty(name="Seed", default=0, min=0)
    use_animated_seed: BoolProperty(name="Animate Seed", description="Add the frame number "
                                    "to the seed", default=False)
    use_adaptive_sampling: BoolProperty(name="Adaptive Sampling", description="Stop sampling "
                                        "each pixel once its noise is below the threshold",
                                        default=False)
    adaptive_threshold: FloatProperty(name="Noise Threshold", default=0.01, min=0.001,
                                      max=1.0, precision=3)
    adaptive_min_samples: IntProperty(name="Min Samples", description="0: Glint's choice",
                                      default=0, min=0, max=4096)
    use_denoising: BoolProperty(name="Denoise", default=True)
    denoiser: EnumProperty(name="Denoiser", items=[
        ("AUTO", "Automatic", "Open Image Denoise's network where this build has its weights, "
         "else the non-local-means filter"),
        ("OIDN", "Open Image Denoise", "Open Image Denoise's published network, run by Glint"),
        ("NLM", "Non-Local Means", "Glint's filter")], default="AUTO")
    denoising_passes: BoolProperty(name="Denoising Data", description="Write the Denoising "
                                   "Albedo and Normal passes", default=False)
    max_bounces: IntProperty(name="Total", default=12, min=0, max=63)
    diffuse_bounces: IntProperty(name="Diffuse", default=4, min=0, max=63)
    glossy_bounces: IntProperty(name="Glossy", default=4, min=0, max=63)
    transmission_bounces: IntProperty(name="Transmission", default=12, min=0, max=63)
    volume_bounces: IntProperty(name="Volume", default=0, min=0, max=63)
    clamp_indirect: FloatProperty(name="Clamp Indirect", description="0: no clamping",
                                  default=10.0, min=0.0)
    caustics: BoolProperty(name="Caustics", description="Trace the light that glass and "
                           "mirrors focus (Glint's light pass)", default=True)


def register():
    bpy.utils.register_class(GlintSceneSettings)
    bpy.types.Scene.glint = PointerProperty(type=GlintSceneSettings)


def unregister():
    del bpy.types.Scene.glint
    bpy.utils.unregister_class(GlintSceneSettings)
