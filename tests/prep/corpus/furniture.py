# luxel-prep corpus: props of boxes and cylinders: a table, four chairs, a shelf with books and
# a floor lamp (a 40 cm stem is the prop issue 22 saw).
#   blender --background --factory-startup --python furniture.py -- OUT.glb
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_common as c  # noqa: E402

out = c.output_path("furniture.py")
wood = c.material("oak", (0.6, 0.45, 0.3))
paint = c.material("blue paint", (0.15, 0.25, 0.6))
metal = c.material("brushed steel", (0.5, 0.5, 0.5))


def table(x, y):
    c.box("Table top", (1.6, 0.9, 0.05), (x, y, 0.72), wood)
    for i, (dx, dy) in enumerate(((-0.7, -0.37), (0.7, -0.37), (-0.7, 0.37), (0.7, 0.37))):
        c.box("Table leg %d" % i, (0.07, 0.07, 0.72), (x + dx, y + dy, 0.0), wood)


def chair(name, x, y, turn):
    c.box(name + " seat", (0.45, 0.45, 0.04), (x, y, 0.44), paint, rotation=(0, 0, turn))
    back_x = x - 0.2 * math.cos(turn)
    back_y = y - 0.2 * math.sin(turn)
    c.box(name + " back", (0.04, 0.45, 0.45), (back_x, back_y, 0.48), paint,
          rotation=(0, 0, turn))
    for i in range(4):
        ox = (-0.19 if i % 2 == 0 else 0.19)
        oy = (-0.19 if i < 2 else 0.19)
        lx = x + ox * math.cos(turn) - oy * math.sin(turn)
        ly = y + ox * math.sin(turn) + oy * math.cos(turn)
        c.cylinder(name + " leg %d" % i, 0.02, 0.44, (lx, ly, 0.22), metal, vertices=12)


table(0.0, 0.0)
for i, (x, y, turn) in enumerate(((-1.1, 0.0, 0.0), (1.1, 0.0, math.pi), (0.0, -0.8, 0.5 * math.pi),
                                  (0.0, 0.8, -0.5 * math.pi))):
    chair("Chair %d" % i, x, y, turn)
c.box("Shelf side L", (0.03, 0.35, 1.8), (2.0, 1.5, 0.0), wood)
c.box("Shelf side R", (0.03, 0.35, 1.8), (2.9, 1.5, 0.0), wood)
for i in range(5):
    c.box("Shelf board %d" % i, (0.87, 0.35, 0.025), (2.45, 1.5, 0.05 + 0.42 * i), wood)
    for b in range(6):
        c.box("Book %d-%d" % (i, b), (0.05 + 0.01 * (b % 3), 0.22, 0.22 + 0.03 * (b % 4)),
              (2.1 + 0.13 * b, 1.45, 0.075 + 0.42 * i), paint)
c.cylinder("Lamp base", 0.15, 0.03, (-2.0, 1.5, 0.015), metal, vertices=32)
c.cylinder("Lamp stem", 0.015, 1.5, (-2.0, 1.5, 0.78), metal, vertices=16)
c.cylinder("Lamp shade", 0.2, 0.25, (-2.0, 1.5, 1.6), paint, vertices=32)
c.point_light("Ceiling lamp", (0.0, 0.0, 2.6), 400.0)
c.export(out)
