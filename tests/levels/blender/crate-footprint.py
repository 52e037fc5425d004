# Builds the crate-footprint level in Blender and writes it with Blender's own glTF exporter:
# a level luxel did not write, made as a level designer would make it (issue 19's reproduction).
#
#   blender --background --factory-startup --python tests/levels/blender/crate-footprint.py \
#       -- OUT.glb
#
# A room of 4 x 4 m, 2.6 m high, open on the camera's side, lit by one point light under the
# ceiling. A 0.5 m crate rests on the floor when the level loads; its animation keeps it there
# for one second and then slides it 1.2 m along x over half a second. Where it stood, the floor
# must be lit in the indirect light within frames (tests/stability/footprint_test.cpp).
#
# Blender is Z up; its exporter turns the level into glTF's Y up (+Y up, +Z towards the
# camera's side of the room), so the crate slides along glTF +x.
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "support"))
from blender_common import camera, export_level, material, open_room, output_path  # noqa: E402

out_path = output_path("crate-footprint.py")

scene = bpy.context.scene
scene.render.fps = 30
scene.frame_start = 1
scene.frame_end = 46


grey = material("grey plaster", (0.6, 0.6, 0.6))
red = material("red paint", (0.7, 0.12, 0.1))
green = material("green paint", (0.12, 0.6, 0.15))
wood = material("crate wood", (0.55, 0.4, 0.22))

open_room(grey, red, green)

bpy.ops.mesh.primitive_cube_add(size=0.5, location=(-0.6, 0.4, 0.25))
crate = bpy.context.active_object
crate.name = "Crate"
crate.data.name = "Crate"
crate.data.materials.append(wood)
# Rests for one second, then slides 1.2 m along x over half a second (ease-in-out, as Blender's
# default Bezier keys give).
for frame, x in ((1, -0.6), (31, -0.6), (46, 0.6)):
    crate.location.x = x
    crate.keyframe_insert(data_path="location", frame=frame)

# 60 W of light; Blender's exporter writes the point light's intensity in candela.
bpy.ops.object.light_add(type="POINT", location=(0.3, -0.2, 2.3))
lamp = bpy.context.active_object
lamp.name = "Ceiling lamp"
lamp.data.energy = 60.0
lamp.data.shadow_soft_size = 0.0

# From the open side, looking at the floor where the crate stands.
camera((0.0, -5.2, 2.1), (1.26, 0.0, 0.0), 24.0)

export_level(out_path, lights=True)
