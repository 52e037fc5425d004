# luxel-prep corpus: boxes of many sizes and proportions, as Blender's cube primitive makes them
# (every face one quad of two triangles), under one lamp.
#   blender --background --factory-startup --python boxes.py -- OUT.glb
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_common as c  # noqa: E402

out = c.output_path("boxes.py")
wood = c.material("wood", (0.55, 0.4, 0.22))
grey = c.material("grey", (0.6, 0.6, 0.6))
c.plane("Ground", (8.0, 8.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), grey)
sizes = [(0.5, 0.5, 0.5), (1.0, 1.0, 1.0), (2.0, 1.0, 0.6), (0.4, 0.4, 1.6), (1.2, 0.8, 0.8),
         (3.0, 0.3, 1.0), (0.8, 0.8, 0.3), (1.5, 1.5, 1.5)]
for i, size in enumerate(sizes):
    c.box("Box %d" % i, size, (-3.0 + (i % 4) * 2.0, -1.5 + (i // 4) * 3.0, 0.0), wood,
          rotation=(0.0, 0.0, 0.15 * i))
c.point_light("Lamp", (0.0, 0.0, 4.0), 500.0)
c.export(out)
