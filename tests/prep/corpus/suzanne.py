# luxel-prep corpus: an organic curved prop: Blender's Suzanne, subdivided twice (Catmull-Clark,
# about 15 700 triangles), on a ground plane.
#   blender --background --factory-startup --python suzanne.py -- OUT.glb
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_common as c  # noqa: E402

out = c.output_path("suzanne.py")
clay = c.material("clay", (0.7, 0.5, 0.4))
grey = c.material("grey", (0.6, 0.6, 0.6))
c.plane("Ground", (4.0, 4.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), grey)
bpy.ops.mesh.primitive_monkey_add(size=1.5, location=(0.0, 0.0, 0.9))
monkey = bpy.context.active_object
subdivision = monkey.modifiers.new("Subdivision", "SUBSURF")
subdivision.levels = 2
bpy.ops.object.modifier_apply(modifier="Subdivision")
c.finish(monkey, "Suzanne", clay, smooth=True)
c.point_light("Lamp", (1.0, -2.0, 3.0), 300.0)
c.export(out)
