# Shared by the Blender scripts of luxel-prep's corpus (tests/prep/corpus/*.py): the command
# line, an empty scene, materials and the primitives the scenes are made of, and the export.
# Each scene is made as a user would make it in Blender and written by Blender's own glTF
# exporter, so luxel-prep is tested on meshes luxel did not write.
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "support"))
from blender_common import material, output_path  # noqa: E402,F401


def finish(obj, name, mat, smooth=False):
    obj.name = name
    obj.data.name = name
    obj.data.materials.append(mat)
    if smooth:
        bpy.ops.object.shade_smooth()
    return obj


def box(name, size, location, mat, rotation=(0.0, 0.0, 0.0)):
    """A box of size (x, y, z) metres standing on `location` (its bottom centre)."""
    bpy.ops.mesh.primitive_cube_add(size=1.0, rotation=rotation,
                                    location=(location[0], location[1],
                                              location[2] + size[2] / 2))
    obj = bpy.context.active_object
    obj.scale = size
    bpy.ops.object.transform_apply(location=False, rotation=True, scale=True)
    return finish(obj, name, mat)


def cylinder(name, radius, height, location, mat, vertices=32, rotation=(0.0, 0.0, 0.0)):
    bpy.ops.mesh.primitive_cylinder_add(vertices=vertices, radius=radius, depth=height,
                                        location=location, rotation=rotation)
    return finish(bpy.context.active_object, name, mat, smooth=True)


def plane(name, size, location, rotation, mat):
    """A plane of size (x, y) metres; Blender's default plane faces +Z before `rotation`."""
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.scale = (size[0], size[1], 1.0)
    bpy.ops.object.transform_apply(location=False, rotation=True, scale=True)
    return finish(obj, name, mat)


def room(width, depth, height, mat):
    """Floor, ceiling and four walls facing in, each one quad as Blender makes a plane."""
    half_pi = math.pi / 2
    plane("Floor", (width, depth), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), mat)
    plane("Ceiling", (width, depth), (0.0, 0.0, height), (math.pi, 0.0, 0.0), mat)
    plane("Back wall", (width, height), (0.0, depth / 2, height / 2), (half_pi, 0.0, 0.0), mat)
    plane("Front wall", (width, height), (0.0, -depth / 2, height / 2), (-half_pi, 0.0, 0.0),
          mat)
    plane("Left wall", (height, depth), (-width / 2, 0.0, height / 2), (0.0, half_pi, 0.0), mat)
    plane("Right wall", (height, depth), (width / 2, 0.0, height / 2), (0.0, -half_pi, 0.0),
          mat)


def point_light(name, location, watts):
    bpy.ops.object.light_add(type="POINT", location=location)
    lamp = bpy.context.active_object
    lamp.name = name
    lamp.data.energy = watts
    lamp.data.shadow_soft_size = 0.0
    return lamp


def export(out_path):
    bpy.ops.export_scene.gltf(
        filepath=out_path,
        export_format="GLB",
        export_apply=True,
        export_cameras=True,
        export_lights=True,
        export_yup=True,
    )
