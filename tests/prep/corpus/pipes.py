# luxel-prep corpus: a cylinder-rich prop: a rack of pipes, barrels and a tank (32 to 64 sides,
# smooth shaded), on a base plate.
#   blender --background --factory-startup --python pipes.py -- OUT.glb
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_common as c  # noqa: E402

out = c.output_path("pipes.py")
steel = c.material("steel", (0.45, 0.45, 0.48))
rust = c.material("rust", (0.5, 0.25, 0.1))
c.box("Base plate", (6.0, 3.0, 0.1), (0.0, 0.0, 0.0), steel)
for i in range(6):
    c.cylinder("Pipe %d" % i, 0.08 + 0.02 * i, 5.0, (0.0, -1.2 + 0.45 * i, 0.4 + 0.1 * i), steel,
               vertices=32, rotation=(0.0, 0.5 * math.pi, 0.0))
for i in range(4):
    c.cylinder("Upright %d" % i, 0.06, 1.2, (-2.4 + 1.6 * i, -1.4, 0.7), steel, vertices=24)
for i in range(3):
    c.cylinder("Barrel %d" % i, 0.3, 0.9, (-2.0 + 0.7 * i, 1.0, 0.55), rust, vertices=48)
c.cylinder("Tank", 0.6, 1.6, (1.8, 0.6, 0.9), steel, vertices=64)
c.point_light("Lamp", (0.0, -2.0, 3.0), 400.0)
c.export(out)
