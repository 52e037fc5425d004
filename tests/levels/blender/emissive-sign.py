# Builds the emissive-sign level in Blender and writes it with Blender's own glTF exporter: a
# level lit only by an emissive texture, with an image-textured floor, as a level designer would
# make it (issue 21's emissive-texture tests).
#
#   blender --background --factory-startup --threads 1 --python \
#       tests/levels/blender/emissive-sign.py -- OUT.glb
#
# A closed room of 4 x 3 m, 2.6 m high, grey (albedo 0.6) walls and ceiling, no punctual light.
# The floor's base colour is a 16 x 16 checker image of linear greys 0.3 and 0.7. On the middle
# of the back wall hangs "Sign", a 1.2 x 0.6 m quad 2 cm off the wall facing into the room, UVs
# covering [0, 1]^2, black base colour, emission from a 64 x 64 image (nearest filtering) at
# emissiveFactor [1, 1, 1] and KHR_materials_emissive_strength 4. The image is black except two
# patches, in glTF image convention (column x from the left, row y from the top: row 0 is v = 0):
#
#   warm white, sRGB bytes (255, 230, 179): columns [8, 24), rows [16, 48)
#       u in [0.125, 0.375), v in [0.25, 0.75)
#   pure red, sRGB bytes (255, 0, 0):       columns [40, 56), rows [24, 40)
#       u in [0.625, 0.875), v in [0.375, 0.625)
#
# (both row ranges are symmetric about the middle, so they are the same counted from the bottom).
# Seen from the room the image is upright: u runs along glTF +x, v = 0 is the sign's top edge.
#
# Blender is Z up; its exporter turns the level into glTF's Y up. In glTF coordinates the room
# spans x in [-2, 2], y in [0, 2.6], z in [-1.5, 1.5]; the sign lies in the plane z = -1.48,
# x in [-0.6, 0.6], y in [1.0, 1.6], facing +z; the camera stands at (0, 1.75, 1.4).
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "support"))
from blender_common import camera, export_level, material, output_path, plane  # noqa: E402

out_path = output_path("emissive-sign.py")

scene = bpy.context.scene
scene.render.resolution_x = 1920
scene.render.resolution_y = 1080


def srgb_byte(linear):
    # The sRGB byte whose decoded value is nearest to a linear value.
    s = 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1.0 / 2.4) - 0.055
    return int(round(s * 255.0))


def byte_image(name, width, height, texel):
    # An 8-bit sRGB image whose texels are texel(x, y) -> (r, g, b) bytes, x from the left and
    # y from the top (glTF's convention; Blender's pixel rows run from the bottom), packed so
    # that the exporter embeds its PNG bytes as they are.
    image = bpy.data.images.new(name, width, height, alpha=False, float_buffer=False)
    image.colorspace_settings.name = "sRGB"
    pixels = []
    for row in range(height):
        y = height - 1 - row
        for x in range(width):
            r, g, b = texel(x, y)
            pixels += [r / 255.0, g / 255.0, b / 255.0, 1.0]
    image.pixels = pixels
    image.pack()
    return image


def image_node(mat, image, interpolation):
    node = mat.node_tree.nodes.new("ShaderNodeTexImage")
    node.image = image
    node.interpolation = interpolation
    return node


grey = material("grey plaster", (0.6, 0.6, 0.6))

dark, light = srgb_byte(0.3), srgb_byte(0.7)
checker = byte_image(
    "floor checker", 16, 16,
    lambda x, y: (dark,) * 3 if (x + y) % 2 == 0 else (light,) * 3)
floor = material("checker floor", (1.0, 1.0, 1.0))
floor_tex = image_node(floor, checker, "Linear")
floor.node_tree.links.new(floor_tex.outputs["Color"],
                          floor.node_tree.nodes["Principled BSDF"].inputs["Base Color"])


def sign_texel(x, y):
    if 8 <= x < 24 and 16 <= y < 48:
        return (255, 230, 179)
    if 40 <= x < 56 and 24 <= y < 40:
        return (255, 0, 0)
    return (0, 0, 0)


sign_image = byte_image("sign emission", 64, 64, sign_texel)
sign = material("sign", (0.0, 0.0, 0.0))
sign_tex = image_node(sign, sign_image, "Closest")
sign_bsdf = sign.node_tree.nodes["Principled BSDF"]
sign.node_tree.links.new(sign_tex.outputs["Color"], sign_bsdf.inputs["Emission"])
sign_bsdf.inputs["Emission Strength"].default_value = 4.0

half_pi = 1.5707963267948966
# Normals face into the room (the renderer draws single-sided faces from the front only).
plane("Floor", (4.0, 3.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), floor)
plane("Ceiling", (4.0, 3.0), (0.0, 0.0, 2.6), (2 * half_pi, 0.0, 0.0), grey)
plane("Back wall", (4.0, 2.6), (0.0, 1.5, 1.3), (half_pi, 0.0, 0.0), grey)
plane("Front wall", (4.0, 2.6), (0.0, -1.5, 1.3), (-half_pi, 0.0, 0.0), grey)
plane("Left wall", (2.6, 3.0), (-2.0, 0.0, 1.3), (0.0, half_pi, 0.0), grey)
plane("Right wall", (2.6, 3.0), (2.0, 0.0, 1.3), (0.0, -half_pi, 0.0), grey)
# Plane x runs along +x (u), plane y turns to +z (Blender v up, so glTF v = 0 at the top).
plane("Sign", (1.2, 0.6), (0.0, 1.48, 1.3), (half_pi, 0.0, 0.0), sign)

# Near the front wall, 2.9 m from the sign, looking slightly down at it.
camera((0.0, -1.4, 1.75), (half_pi - 0.155, 0.0, 0.0), 24.0, fit_horizontally=True)

export_level(out_path, lights=False, animations=False)
