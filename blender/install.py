"""Installs and enables the add-on in the user's Blender; `make blender` runs it:

    blender -b --python-exit-code 1 --python blender/install.py -- build/blender/glint_blender.zip
"""

import sys

import bpy

archive = sys.argv[sys.argv.index("--") + 1]
bpy.ops.preferences.addon_install(filepath=archive, overwrite=True)
bpy.ops.preferences.addon_enable(module="glint_blender")
bpy.ops.wm.save_userpref()
import glint_blender  # noqa: E402

print(f"glint: the Glint add-on is installed in {glint_blender.__path__[0]} and enabled; "
      f"choose Glint as the Render Engine (Render Properties), or blender -b FILE -E GLINT -f 1")
