# Builds the sky-window level in Blender and writes it with Blender's own glTF exporter: a room
# lit only from outside, through one window, by a sun and a clear daylight sky (issue 20).
#
#   blender --background --factory-startup --python tests/levels/blender/sky-window.py -- OUT.glb
#
# A closed room of 4 x 4 m, 2.6 m high, with a 1.2 x 1.0 m window in its back wall, 1 m above
# the floor. The sun (3 W/m^2) shines in through the window, down at 39 degrees; the sky is a
# scene custom property, {"luxel": {"sky": {"kind": "daylight", "irradiance": 1.0}}}, which the
# exporter writes into the glTF scene's extras (docs/LEVELS.md, "Sky"). Every wall, the floor
# and the ceiling is one-sided, facing into the room: light from outside reaches the inside only
# through the window, which a portal fills (the sky's photons start on it). The camera stands
# inside, looking at the window.
#
# Blender is Z up; its exporter turns the level into glTF's Y up (the window's wall faces -Z in
# glTF, the camera looks along -Z).
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "support"))
from blender_common import camera, export_level, material, output_path, plane  # noqa: E402

out_path = output_path("sky-window.py")

scene = bpy.context.scene
# The sky: a custom property of the scene, as a level designer adds one in the Scene panel.
scene["luxel"] = {"sky": {"kind": "daylight", "irradiance": 1.0, "turbidity": 3.0}}

plaster = material("white plaster", (0.7, 0.7, 0.68))
floor_wood = material("floor wood", (0.45, 0.32, 0.2))
blue = material("blue paint", (0.15, 0.25, 0.6))

half_pi = 1.5707963267948966
# Normals face into the room.
plane("Floor", (4.0, 4.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), floor_wood)
plane("Ceiling", (4.0, 4.0), (0.0, 0.0, 2.6), (2 * half_pi, 0.0, 0.0), plaster)
plane("Front wall", (4.0, 2.6), (0.0, -2.0, 1.3), (-half_pi, 0.0, 0.0), plaster)
plane("Left wall", (2.6, 4.0), (-2.0, 0.0, 1.3), (0.0, half_pi, 0.0), blue)
plane("Right wall", (2.6, 4.0), (2.0, 0.0, 1.3), (0.0, -half_pi, 0.0), plaster)
# The back wall around the window (x in [-0.6, 0.6], z in [1.0, 2.0]).
plane("Back wall below", (4.0, 1.0), (0.0, 2.0, 0.5), (half_pi, 0.0, 0.0), plaster)
plane("Back wall above", (4.0, 0.6), (0.0, 2.0, 2.3), (half_pi, 0.0, 0.0), plaster)
plane("Back wall left", (1.4, 1.0), (-1.3, 2.0, 1.5), (half_pi, 0.0, 0.0), plaster)
plane("Back wall right", (1.4, 1.0), (1.3, 2.0, 1.5), (half_pi, 0.0, 0.0), plaster)
# The window's portal: a plane filling the opening, marked with a custom property that the
# exporter writes into the node's extras, {"luxel": {"portal": true}}. luxel neither draws nor
# traces it; the sky's photons start on it, so they all go through the window.
portal = plane("Window portal", (1.2, 1.0), (0.0, 2.0, 1.5), (half_pi, 0.0, 0.0), plaster)
portal["luxel"] = {"portal": True}

# The sun behind the window, shining in along (0, -1, -0.8) (down 39 degrees): its -Z axis
# turned about X.
bpy.ops.object.light_add(type="SUN", rotation=(-0.8960553845713439, 0.0, 0.0))
sun = bpy.context.active_object
sun.name = "Sun"
sun.data.energy = 3.0
sun.data.angle = 0.0

# Inside by the front wall, looking at the window a little upwards.
camera((0.0, -1.8, 1.3), (1.65, 0.0, 0.0), 20.0)

export_level(out_path, lights=True, extras=True)
