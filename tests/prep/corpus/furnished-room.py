# luxel-prep corpus: a furnished room: 6 x 5 x 3 m, walls, floor and ceiling one quad each (as
# Blender makes planes), a sofa, a table with chairs, a cabinet, a rug and a lamp.
#   blender --background --factory-startup --python furnished-room.py -- OUT.glb
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_common as c  # noqa: E402

out = c.output_path("furnished-room.py")
plaster = c.material("plaster", (0.7, 0.68, 0.62))
fabric = c.material("sofa fabric", (0.3, 0.35, 0.5))
wood = c.material("walnut", (0.4, 0.28, 0.18))
rug = c.material("rug", (0.6, 0.2, 0.2))
metal = c.material("steel", (0.5, 0.5, 0.5))
c.room(6.0, 5.0, 3.0, plaster)
# Sofa against the back wall.
c.box("Sofa base", (2.2, 0.9, 0.42), (0.0, 1.9, 0.0), fabric)
c.box("Sofa back", (2.2, 0.2, 0.45), (0.0, 2.25, 0.42), fabric)
c.box("Sofa arm L", (0.2, 0.9, 0.25), (-1.0, 1.9, 0.42), fabric)
c.box("Sofa arm R", (0.2, 0.9, 0.25), (1.0, 1.9, 0.42), fabric)
# Coffee table, rug.
c.box("Rug", (2.4, 1.6, 0.01), (0.0, 0.6, 0.0), rug)
c.box("Coffee table", (1.1, 0.6, 0.04), (0.0, 0.6, 0.4), wood)
for i, (dx, dy) in enumerate(((-0.5, -0.25), (0.5, -0.25), (-0.5, 0.25), (0.5, 0.25))):
    c.box("Coffee table leg %d" % i, (0.05, 0.05, 0.4), (dx, 0.6 + dy, 0.0), wood)
# Dining corner.
c.box("Dining table", (1.4, 0.8, 0.05), (-1.8, -1.3, 0.72), wood)
c.cylinder("Dining table pedestal", 0.08, 0.72, (-1.8, -1.3, 0.36), wood, vertices=24)
for i, x in enumerate((-2.3, -1.3)):
    c.box("Chair %d seat" % i, (0.45, 0.45, 0.04), (x, -0.6, 0.44), fabric)
    c.box("Chair %d back" % i, (0.45, 0.04, 0.5), (x, -0.4, 0.44), fabric)
    c.box("Chair %d legs" % i, (0.4, 0.4, 0.44), (x, -0.6, 0.0), wood)
# Cabinet and a floor lamp.
c.box("Cabinet", (1.2, 0.45, 0.9), (2.2, -1.9, 0.0), wood)
c.cylinder("Lamp stem", 0.02, 1.6, (2.5, 1.9, 0.8), metal, vertices=16)
c.cylinder("Lamp shade", 0.22, 0.3, (2.5, 1.9, 1.65), fabric, vertices=32)
c.point_light("Ceiling lamp", (0.0, 0.0, 2.7), 600.0)
c.export(out)
