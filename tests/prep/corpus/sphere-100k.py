# luxel-prep corpus: the 100k-triangle curved mesh: a smooth UV sphere of 320 segments and 160
# rings (101 760 triangles). Its .glb is over 3 MB, so it is not committed: the corpus test
# exports it at test time into its own folder (check-exports.sh skips it).
#   blender --background --factory-startup --python sphere-100k.py -- OUT.glb
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_common as c  # noqa: E402

out = c.output_path("sphere-100k.py")
clay = c.material("clay", (0.7, 0.5, 0.4))
bpy.ops.mesh.primitive_uv_sphere_add(segments=320, ring_count=160, radius=1.0,
                                     location=(0.0, 0.0, 1.0))
c.finish(bpy.context.active_object, "Sphere", clay, smooth=True)
c.point_light("Lamp", (2.0, -2.0, 3.0), 300.0)
c.export(out)
