# luxel-prep corpus: bevelled crates (Blender's bevel modifier, two segments: the thin strips
# along every edge a real prop has), stacked.
#   blender --background --factory-startup --python crates.py -- OUT.glb
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_common as c  # noqa: E402

out = c.output_path("crates.py")
wood = c.material("crate wood", (0.55, 0.4, 0.22))
for i in range(6):
    size = 0.6 + 0.2 * (i % 3)
    crate = c.box("Crate %d" % i, (size, size, size), ((i % 3) * 1.4, (i // 3) * 1.4, 0.0), wood)
    bevel = crate.modifiers.new("Bevel", "BEVEL")
    bevel.width = 0.03
    bevel.segments = 2
    bpy.context.view_layer.objects.active = crate
    bpy.ops.object.modifier_apply(modifier="Bevel")
c.point_light("Lamp", (1.4, 0.7, 3.0), 300.0)
c.export(out)
