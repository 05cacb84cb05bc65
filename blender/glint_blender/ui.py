"""Glint's panels in the Render Properties, and Blender's own panels (output, format, material
nodes, lights, world) opened to the Glint engine."""

import bpy


class _GlintPanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {"GLINT"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def column(self):
        """The panel's one column, labels beside their fields, as Blender's own panels."""
        col = self.layout.column()
        col.use_property_split = True
        return col


class GLINT_PT_sampling(_GlintPanel, bpy.types.Panel):
    bl_label = "Sampling"

    def draw(self, context):
        s = context.scene.glint
        col = self.column()
        col.prop(s, "samples")
        col.prop(s, "time_limit")
        col.prop(s, "use_adaptive_sampling")
        sub = col.column()
        sub.active = s.use_adaptive_sampling
        sub.prop(s, "adaptive_threshold")
        sub.prop(s, "adaptive_min_samples")
        col.prop(s, "use_denoising")
        sub = col.column()
        sub.active = s.use_denoising
        sub.prop(s, "denoiser")
        col.prop(s, "seed")
        col.prop(s, "use_animated_seed")


class GLINT_PT_light_paths(_GlintPanel, bpy.types.Panel):
    bl_label = "Light Paths"

    def draw(self, context):
        s = context.scene.glint
        col = self.column()
        for name in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces",
                     "volume_bounces", "clamp_indirect", "caustics"):
            col.prop(s, name)


class GLINT_PT_passes(_GlintPanel, bpy.types.Panel):
    bl_label = "Passes"
    bl_context = "view_layer"

    def draw(self, context):
        col = self.column()
        col.prop(context.view_layer, "use_pass_z")
        col.prop(context.scene.glint, "denoising_passes")


_panels = (GLINT_PT_sampling, GLINT_PT_light_paths, GLINT_PT_passes)
# Cycles' panels that edit what Glint reads (node materials, lights, the world).
_CYCLES_PREFIXES = ("CYCLES_MATERIAL_PT_", "CYCLES_LIGHT_PT_", "CYCLES_WORLD_PT_")
_opened: list = []


def _panel_classes():
    for cls in bpy.types.Panel.__subclasses__():
        engines = getattr(cls, "COMPAT_ENGINES", None)
        if not isinstance(engines, set):
            continue
        if "BLENDER_RENDER" in engines or cls.__name__.startswith(_CYCLES_PREFIXES):
            yield cls


def register():
    for cls in _panels:
        bpy.utils.register_class(cls)
    for cls in _panel_classes():
        if "GLINT" not in cls.COMPAT_ENGINES:
            cls.COMPAT_ENGINES.add("GLINT")
            _opened.append(cls)


def unregister():
    for cls in _opened:
        cls.COMPAT_ENGINES.discard("GLINT")
    _opened.clear()
    for cls in reversed(_panels):
        bpy.utils.unregister_class(cls)
