# luxel-prep corpus: a terrain: a 24 x 24 m grid of 96 x 96 quads (18 432 triangles) displaced
# by a sum of sines (deterministic: no noise texture, so every export is the same file).
#   blender --background --factory-startup --python terrain.py -- OUT.glb
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_common as c  # noqa: E402

out = c.output_path("terrain.py")
grass = c.material("grass", (0.25, 0.45, 0.15))
bpy.ops.mesh.primitive_grid_add(x_subdivisions=96, y_subdivisions=96, size=24.0)
ground = bpy.context.active_object
for v in ground.data.vertices:
    x, y = v.co.x, v.co.y
    v.co.z = (1.2 * math.sin(0.35 * x) * math.cos(0.27 * y) + 0.5 * math.sin(0.9 * x + 0.4 * y)
              + 0.15 * math.cos(2.1 * y - 0.7 * x))
c.finish(ground, "Terrain", grass, smooth=True)
c.point_light("Sun lamp", (0.0, 0.0, 12.0), 20000.0)
c.export(out)
