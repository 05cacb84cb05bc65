# Makes blender-monkey.gltf with Debian's Blender (3.4.1):
#   blender -b --python make_blender_monkey.py -- blender-monkey.gltf
# Suzanne with Blender's uv layout, shaded smooth, triangulated (so that Blender's MikkTSpace
# sees the triangles a glTF reader sees: on quads it would choose diagonals of its own), its
# texture mirrored on the left half (u -> 1 - u), and a material with a normal map, exported
# with TANGENT: the tangents of Blender's MikkTSpace, the reference of
# GltfAttributes.GeneratedTangentsMatchBlendersMikkTSpace.
import sys

import bpy

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_monkey_add(size=2, calc_uvs=True)
m = bpy.context.object
bpy.ops.object.shade_smooth()
mod = m.modifiers.new("triangulate", 'TRIANGULATE')
bpy.ops.object.modifier_apply(modifier=mod.name)
uv = m.data.uv_layers.active.data
for poly in m.data.polygons:
    if poly.center.x < 0:
        for li in poly.loop_indices:
            uv[li].uv.x = 1 - uv[li].uv.x
mat = bpy.data.materials.new("normalmapped")
mat.use_nodes = True
nt = mat.node_tree
img = bpy.data.images.new("normal", 4, 4)
img.generated_color = (0.5, 0.5, 1, 1)
img.filepath_raw = "//normal.png"
img.file_format = 'PNG'
tex = nt.nodes.new("ShaderNodeTexImage")
tex.image = img
nm = nt.nodes.new("ShaderNodeNormalMap")
nt.links.new(tex.outputs["Color"], nm.inputs["Color"])
nt.links.new(nm.outputs["Normal"], nt.nodes["Principled BSDF"].inputs["Normal"])
m.data.materials.append(mat)
bpy.ops.export_scene.gltf(filepath=sys.argv[-1], export_format='GLTF_EMBEDDED',
                          export_tangents=True, export_animations=False)
