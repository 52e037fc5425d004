# Builds the tinted-glass level in Blender and writes it with Blender's own glTF exporter: tinted
# and absorbing glass as a level designer makes it (issue 21's tinted-glass checks).
#
#   blender --background --factory-startup --threads 1 --python \
#       tests/levels/blender/tinted-glass.py -- OUT.glb
#
# A closed room of 4 x 3 m, 2.6 m high, grey (albedo 0.6) walls, floor and ceiling but a light
# (albedo 0.85) back wall, lit by a 200 W point light under the ceiling. Against the back wall:
#   - "Amber block", a 0.6 m glass cube standing on the floor: Principled BSDF with transmission
#     1, IOR 1.5, base colour (0.95, 0.65, 0.3); a glTF Material Output group with Thickness 0.6
#     and a Volume Absorption of colour (0.9, 0.75, 0.5), density 1 / 0.6, which the exporter
#     writes as KHR_materials_volume (thicknessFactor 0.6, attenuationDistance 0.6,
#     attenuationColor (0.9, 0.75, 0.5));
#   - "Blue pane", a 0.8 x 0.8 m single-quad glass sheet standing upright: transmission 1, base
#     colour (0.45, 0.65, 0.95), no volume (glTF's thin wall).
#
# Blender is Z up; its exporter turns the level into glTF's Y up. In glTF coordinates the room
# spans x in [-2, 2], y in [0, 2.6], z in [-1.5, 1.5]; the block spans x in [-0.9, -0.3],
# y in [0, 0.6], z in [-0.8, -0.2]; the pane lies in the plane z = -0.5, x in [0.3, 1.1],
# y in [0.3, 1.1]; the camera stands at (0, 1.2, 1.4) looking at the two.
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "support"))
from blender_common import camera, export_level, material, output_path, plane  # noqa: E402

out_path = output_path("tinted-glass.py")

scene = bpy.context.scene
scene.render.resolution_x = 1600
scene.render.resolution_y = 1200


def glass(name, rgb):
    # Clear glass tinted by its base colour: Principled BSDF, transmission 1, smooth, IOR 1.5.
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (rgb[0], rgb[1], rgb[2], 1.0)
    bsdf.inputs["Transmission"].default_value = 1.0
    bsdf.inputs["Roughness"].default_value = 0.0
    bsdf.inputs["IOR"].default_value = 1.5
    return mat


def add_volume(mat, thickness, rgb, density):
    # What Blender's glTF exporter reads as KHR_materials_volume: the thickness from a node group
    # named "glTF Material Output" (the one its add-on offers in the Add menu), the attenuation
    # from a Volume Absorption linked to the material's Volume output.
    group = bpy.data.node_groups.get("glTF Material Output")
    if group is None:
        group = bpy.data.node_groups.new("glTF Material Output", "ShaderNodeTree")
        group.inputs.new("NodeSocketFloat", "Thickness")
    nodes = mat.node_tree.nodes
    settings = nodes.new("ShaderNodeGroup")
    settings.node_tree = group
    settings.inputs["Thickness"].default_value = thickness
    absorption = nodes.new("ShaderNodeVolumeAbsorption")
    absorption.inputs["Color"].default_value = (rgb[0], rgb[1], rgb[2], 1.0)
    absorption.inputs["Density"].default_value = density
    mat.node_tree.links.new(absorption.outputs["Volume"],
                            nodes["Material Output"].inputs["Volume"])


grey = material("grey plaster", (0.6, 0.6, 0.6))
light_wall = material("light plaster", (0.85, 0.85, 0.85))
amber = glass("amber glass", (0.95, 0.65, 0.3))
add_volume(amber, 0.6, (0.9, 0.75, 0.5), 1.0 / 0.6)
blue = glass("blue glass", (0.45, 0.65, 0.95))

half_pi = 1.5707963267948966
# Normals face into the room (the renderer draws single-sided faces from the front only).
plane("Floor", (4.0, 3.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), grey)
plane("Ceiling", (4.0, 3.0), (0.0, 0.0, 2.6), (2 * half_pi, 0.0, 0.0), grey)
plane("Back wall", (4.0, 2.6), (0.0, 1.5, 1.3), (half_pi, 0.0, 0.0), light_wall)
plane("Front wall", (4.0, 2.6), (0.0, -1.5, 1.3), (-half_pi, 0.0, 0.0), grey)
plane("Left wall", (2.6, 3.0), (-2.0, 0.0, 1.3), (0.0, half_pi, 0.0), grey)
plane("Right wall", (2.6, 3.0), (2.0, 0.0, 1.3), (0.0, -half_pi, 0.0), grey)

bpy.ops.mesh.primitive_cube_add(size=0.6, location=(-0.6, 0.5, 0.3))
block = bpy.context.active_object
block.name = "Amber block"
block.data.name = "Amber block"
block.data.materials.append(amber)

# Facing the camera (-y in Blender, +z in glTF), 0.3 m above the floor.
plane("Blue pane", (0.8, 0.8), (0.7, 0.5, 0.7), (half_pi, 0.0, 0.0), blue)

bpy.ops.object.light_add(type="POINT", location=(0.0, 0.0, 2.3))
lamp = bpy.context.active_object
lamp.name = "Lamp"
lamp.data.energy = 200.0
lamp.data.shadow_soft_size = 0.0

# Near the front wall, looking down at the glass.
camera((0.0, -1.4, 1.2), (half_pi - 0.35, 0.0, 0.0), 24.0, fit_horizontally=True)

export_level(out_path, lights=True, animations=False)
