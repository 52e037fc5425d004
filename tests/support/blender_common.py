# Shared by every Blender script that makes a test level (tests/levels/blender/*.py) or a
# luxel-prep corpus scene (tests/prep/corpus/corpus_common.py): a diffuse material and a plane,
# made as a user makes them in Blender, so Blender's own glTF exporter writes what it writes for
# anyone. Import it after putting tests/support on sys.path.
import sys

import bpy


def output_path(script):
    # The OUT.glb after "--" on the command line (usage and exit 2 without one), and an empty
    # factory scene to build in.
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 1:
        sys.stderr.write("usage: blender --background --factory-startup --python %s -- OUT.glb\n"
                         % script)
        sys.exit(2)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    return argv[0]


def material(name, rgb):
    # A Principled BSDF of base colour rgb, fully rough and without specular: diffuse.
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (rgb[0], rgb[1], rgb[2], 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    bsdf.inputs["Specular"].default_value = 0.0
    return mat


def plane(name, size, location, rotation, mat):
    # A size[0] x size[1] plane, turned and placed, with its transform applied (the exporter
    # then writes world-space vertices) and its material.
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.name = name
    obj.scale = (size[0], size[1], 1.0)
    bpy.ops.object.transform_apply(location=False, rotation=True, scale=True)
    obj.data.materials.append(mat)
    return obj


def open_room(floor_and_ceiling, left, right):
    # The 4 x 4 m room, 2.6 m high, open on the camera's side (Blender's -y), that
    # crate-footprint.py and skinned-figure.py share: floor, ceiling and back wall in the first
    # material, the left and right walls in theirs. Normals face into the room (the renderer
    # draws single-sided faces from the front only).
    half_pi = 1.5707963267948966
    plane("Floor", (4.0, 4.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), floor_and_ceiling)
    plane("Ceiling", (4.0, 4.0), (0.0, 0.0, 2.6), (2 * half_pi, 0.0, 0.0), floor_and_ceiling)
    plane("Back wall", (4.0, 2.6), (0.0, 2.0, 1.3), (half_pi, 0.0, 0.0), floor_and_ceiling)
    plane("Left wall", (2.6, 4.0), (-2.0, 0.0, 1.3), (0.0, half_pi, 0.0), left)
    plane("Right wall", (2.6, 4.0), (2.0, 0.0, 1.3), (0.0, -half_pi, 0.0), right)


def camera(location, rotation, lens, fit_horizontally=False):
    # The level's camera, named "Camera", made the scene's camera; fit_horizontally fits the
    # sensor's width to the image (the lens then sets the horizontal field of view).
    bpy.ops.object.camera_add(location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = "Camera"
    obj.data.lens = lens
    if fit_horizontally:
        obj.data.sensor_fit = "HORIZONTAL"
    bpy.context.scene.camera = obj
    return obj


def export_level(out_path, lights, animations=True, extras=False):
    # Blender's glTF exporter as every level script calls it: one .glb, transforms applied,
    # cameras, glTF's Y up.
    bpy.ops.export_scene.gltf(
        filepath=out_path,
        export_format="GLB",
        export_apply=True,
        export_animations=animations,
        export_cameras=True,
        export_lights=lights,
        export_extras=extras,
        export_yup=True,
    )
