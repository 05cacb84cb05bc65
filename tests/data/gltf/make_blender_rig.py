# Makes blender-rig.glb with Debian's Blender (3.4.1):
#   blender -b --python make_blender_rig.py -- blender-rig.glb
# An upright figure 1.85 m tall (a subdivided box, Z-up as Blender works), rigged as FBX imports
# come: the armature object scaled 0.01, its two bones and the mesh in centimetres, the mesh
# parented to the armature with automatic weights; the upper bone ("chest") posed 40 degrees
# about x, and the file exported as glTF (+Y up) in that pose ("use current frame"). Its skinned
# node (Body) sits under the Armature node's 0.01 scale: placed by that node it would be 1.85 cm
# tall. Blender's own glTF importer, posing the file, puts the figure's vertices within
# (-0.2, 0, -0.12569) .. (0.2, 1.73149, 0.64212) (glTF axes): the reference of
# GltfSkins.ABlenderExportedRigStandsAsBlendersImporterPosesIt.
import math
import sys

import bpy

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_cube_add(size=1)
body = bpy.context.object
body.name = "Body"
body.scale = (40, 25, 185)
body.location = (0, 0, 92.5)
bpy.ops.object.transform_apply(location=True, rotation=False, scale=True)
bpy.ops.object.mode_set(mode='EDIT')
bpy.ops.mesh.subdivide(number_cuts=3)
bpy.ops.object.mode_set(mode='OBJECT')
bpy.ops.object.armature_add(location=(0, 0, 0))
arm = bpy.context.object
arm.name = "Armature"
bpy.ops.object.mode_set(mode='EDIT')
hips = arm.data.edit_bones[0]
hips.name = "hips"
hips.head, hips.tail = (0, 0, 0), (0, 0, 100)
chest = arm.data.edit_bones.new("chest")
chest.head, chest.tail = (0, 0, 100), (0, 0, 185)
chest.parent = hips
bpy.ops.object.mode_set(mode='OBJECT')
bpy.ops.object.select_all(action='DESELECT')
body.select_set(True)
arm.select_set(True)
bpy.context.view_layer.objects.active = arm
bpy.ops.object.parent_set(type='ARMATURE_AUTO')
arm.scale = (0.01, 0.01, 0.01)
bpy.ops.object.mode_set(mode='POSE')
arm.pose.bones["chest"].rotation_mode = 'XYZ'
arm.pose.bones["chest"].rotation_euler = (math.radians(40), 0, 0)
bpy.ops.object.mode_set(mode='OBJECT')
bpy.context.view_layer.update()
bpy.ops.export_scene.gltf(filepath=sys.argv[-1], export_format='GLB', export_animations=False,
                          export_current_frame=True)

# The reference bounds were measured by importing the file back (Blender 3.4's importer needs
# `numpy.bool = bool` with Debian's numpy), evaluating the depsgraph and taking the world-space
# bounds of the mesh's vertices, Blender's (x, y, z) being glTF's (x, -z, y).
