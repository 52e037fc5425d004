# luxel-prep corpus: a staircase of twelve box steps with a cylinder railing (posts and a
# sloping handrail) against a wall of one quad.
#   blender --background --factory-startup --python stairs.py -- OUT.glb
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_common as c  # noqa: E402

out = c.output_path("stairs.py")
stone = c.material("stone", (0.55, 0.55, 0.5))
metal = c.material("iron", (0.3, 0.3, 0.32))
c.plane("Wall", (4.0, 3.5), (0.0, 0.65, 1.75), (0.5 * math.pi, 0.0, 0.0), stone)
c.plane("Landing floor", (4.0, 3.0), (0.0, -1.0, 0.0), (0.0, 0.0, 0.0), stone)
for i in range(12):
    c.box("Step %d" % i, (0.28, 1.2, 0.18), (-1.6 + 0.28 * i, 0.0, 0.18 * i), stone)
for i in range(7):
    c.cylinder("Post %d" % i, 0.02, 0.9, (-1.6 + 0.56 * i, -0.55, 0.18 * 2 * i + 0.45), metal,
               vertices=16)
rise = math.atan2(0.18, 0.28)
length = math.hypot(12 * 0.28, 12 * 0.18)
c.cylinder("Handrail", 0.03, length, (-0.2, -0.55, 0.9 + 0.18 * 6), metal, vertices=24,
           rotation=(0.0, 0.5 * math.pi - rise, 0.0))
c.point_light("Stair lamp", (0.0, -1.0, 3.0), 300.0)
c.export(out)
