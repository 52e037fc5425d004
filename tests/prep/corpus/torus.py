# luxel-prep corpus: a curved mesh: a smooth torus of 192 x 96 segments (36 864 triangles) on a
# ground plane.
#   blender --background --factory-startup --python torus.py -- OUT.glb
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_common as c  # noqa: E402

out = c.output_path("torus.py")
clay = c.material("clay", (0.7, 0.5, 0.4))
grey = c.material("grey", (0.6, 0.6, 0.6))
c.plane("Ground", (5.0, 5.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), grey)
bpy.ops.mesh.primitive_torus_add(major_segments=192, minor_segments=96, major_radius=1.0,
                                 minor_radius=0.35, location=(0.0, 0.0, 0.35))
c.finish(bpy.context.active_object, "Torus", clay, smooth=True)
c.point_light("Lamp", (1.0, -1.0, 3.0), 300.0)
c.export(out)
