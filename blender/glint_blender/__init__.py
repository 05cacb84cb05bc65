"""Glint as a Blender render engine (docs/blender.md).

Thin over Glint's Python module: the add-on translates Blender's evaluated scene into what the
module loads (a glTF file, an environment, a lens) and shows what it renders. No rendering is
done here. The `glint` module is the one bundled beside this file by `make blender`, else the
one Python finds (pip install, PYTHONPATH).
"""

bl_info = {
    "name": "Glint",
    "author": "Glint's developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Render Properties > Render Engine > Glint",
    "description": "Renders with Glint, a fast path tracer",
    "category": "Render",
}

import importlib  # noqa: E402

_glint = None


def glint_module():
    """The glint module: bundled with the add-on (make blender), else installed."""
    global _glint
    if _glint is None:
        try:
            _glint = importlib.import_module(__name__ + ".glint")
        except ImportError:
            _glint = importlib.import_module("glint")
    return _glint


from . import engine, properties, ui  # noqa: E402

_classes = (engine.GlintRenderEngine,)


def register():
    import bpy

    properties.register()
    for cls in _classes:
        bpy.utils.register_class(cls)
    ui.register()


def unregister():
    import bpy

    ui.unregister()
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
    properties.unregister()
