# Builds the skinned-figure level in Blender and writes it with Blender's own glTF exporter: a
# skinned character walking through a room, rigged and animated as a level designer would do it
# (skinning tests: a skinned mesh whose node sits under a moved and turned armature).
#
#   blender --background --factory-startup --threads 1 --python \
#       tests/levels/blender/skinned-figure.py -- OUT.glb
#
# A room of 4 x 4 m, 2.6 m high, open on the camera's side, lit by one point light under the
# ceiling. "Figure" is one low-poly mesh, 1.6 m tall, joined from primitives (a box for the
# torso, eight-sided cylinders for the head, legs and arms), skinned to "Figure rig", an
# armature of seven bones: hips (the root), spine, head, leg_l, leg_r, arm_l and arm_r. The
# weights are given by position: the top of each leg blends between hips and the leg, the waist
# between hips and spine, the neck between spine and head and the shoulders between spine and
# arm, so many vertices have two joints of weights below 1 (never more than two; the file holds
# JOINTS_0 and WEIGHTS_0 only).
#
# The rig is not at the origin: "Figure rig" stands at (0.8, -0.3, 0), turned 30 degrees about
# Blender's Z (up), and "Figure" is its child, 1.2 m behind it along the rig's own -x (in the
# world: at (-0.239, -0.9, 0), turned 30 degrees too). Blender's exporter writes the figure's
# vertices in world space with inverse bind matrices to match, and writes the skinned mesh's node
# without a transform of its own as a child of the armature's node, which carries the rig's
# transform. glTF ignores a skinned mesh node's transform (and its parents'): the joints alone
# place the vertices. A loader that applies the node's world transform anyway puts every vertex
# of the figure at least 0.8 m away from where it stands (1.2 to 1.4 m at rest, 0.8 to 1.5 m
# over the walk).
#
# One action, "Walk", 2 s at 30 fps (frames 1 to 61): the hips bone carries the figure 1 m along
# the rig's +x (the way the figure faces; in the world from about (-0.24, -0.9) to (0.63, -0.4))
# while the legs swing +-25 degrees and the arms +-20 degrees against them (a step every 0.5 s)
# and the spine twists +-6 degrees about itself.
#
# Blender is Z up; its exporter turns the level into glTF's Y up (+Y up, +Z towards the
# camera's side of the room).
import math
import os
import sys

import bmesh
import bpy
from mathutils import Matrix, Quaternion, Vector

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "support"))
from blender_common import camera, export_level, material, open_room, output_path  # noqa: E402

out_path = output_path("skinned-figure.py")

scene = bpy.context.scene
scene.render.fps = 30
scene.frame_start = 1
scene.frame_end = 61


grey = material("grey plaster", (0.6, 0.6, 0.6))
red = material("red paint", (0.7, 0.12, 0.1))
green = material("green paint", (0.12, 0.6, 0.15))
cloth = material("figure cloth", (0.25, 0.35, 0.6))

open_room(grey, red, green)


# The figure, built at the origin in its own frame: feet at z = 0, facing +x, its left on +y.
def ramp(value, zero_at, one_at):
    # 0 at zero_at, 1 at one_at, linear between, clamped.
    t = (value - zero_at) / (one_at - zero_at)
    return min(1.0, max(0.0, t))


def cut_lengthwise(obj, cuts):
    # Loop cuts across the primitive's local z (its length), so that it bends where it blends.
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    edges = [e for e in bm.edges if abs(e.verts[0].co.z - e.verts[1].co.z) > 1e-6]
    bmesh.ops.subdivide_edges(bm, edges=edges, cuts=cuts, use_grid_fill=True)
    bm.to_mesh(obj.data)
    bm.free()


def part(name, obj, weights):
    # Names the primitive, applies its transform (vertices in the figure's frame) and gives each
    # vertex the weights weights(co) returns: {bone name: weight}, summing to 1.
    obj.name = name
    obj.data.name = name
    bpy.ops.object.transform_apply(location=True, rotation=True, scale=True)
    groups = {}
    for v in obj.data.vertices:
        for bone, w in weights(v.co).items():
            if w <= 0.0:
                continue
            if bone not in groups:
                groups[bone] = obj.vertex_groups.new(name=bone)
            groups[bone].add([v.index], w, "REPLACE")
    return obj


def cylinder(name, radius, bottom, top, y, cuts, weights):
    bpy.ops.mesh.primitive_cylinder_add(vertices=8, radius=radius, depth=top - bottom,
                                        location=(0.0, y, 0.5 * (bottom + top)))
    obj = bpy.context.active_object
    cut_lengthwise(obj, cuts)
    return part(name, obj, weights)


def leg_weights(side):
    # The leg from the hip down; the top blends into the hips (z from 0.95 down to 0.75).
    def weights(co):
        t = ramp(co.z, 0.95, 0.75)
        return {"hips": 1.0 - t, "leg_" + side: t}
    return weights


def arm_weights(side):
    # The arm from the shoulder down; the shoulder blends into the spine (z from 1.38 to 1.26).
    def weights(co):
        t = ramp(co.z, 1.38, 1.26)
        return {"spine": 1.0 - t, "arm_" + side: t}
    return weights


def torso_weights(co):
    # Hips below the waist, spine above, blending from z 0.95 to 1.15.
    t = ramp(co.z, 0.95, 1.15)
    return {"hips": 1.0 - t, "spine": t}


def head_weights(co):
    # The neck (the bottom of the head) blends into the spine, z from 1.38 to 1.46.
    t = ramp(co.z, 1.38, 1.46)
    return {"spine": 1.0 - t, "head": t}


parts = [
    cylinder("Leg L", 0.07, 0.0, 0.9, 0.1, 9, leg_weights("l")),
    cylinder("Leg R", 0.07, 0.0, 0.9, -0.1, 9, leg_weights("r")),
    cylinder("Arm L", 0.05, 0.78, 1.38, 0.24, 6, arm_weights("l")),
    cylinder("Arm R", 0.05, 0.78, 1.38, -0.24, 6, arm_weights("r")),
]
bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, 1.11))
torso = bpy.context.active_object
torso.scale = (0.2, 0.36, 0.58)
cut_lengthwise(torso, 5)
parts.append(part("Torso", torso, torso_weights))
# Not a UV sphere: Blender 3.4 orders a UV sphere's faces differently from one run to the next,
# and the exporter writes the triangles in the mesh's face order.
parts.append(cylinder("Head", 0.1, 1.38, 1.6, 0.0, 3, head_weights))

bpy.ops.object.select_all(action="DESELECT")
for obj in parts:
    obj.select_set(True)
bpy.context.view_layer.objects.active = parts[0]
bpy.ops.object.join()
figure = bpy.context.active_object
figure.name = "Figure"
figure.data.name = "Figure"
figure.data.materials.append(cloth)


# The rig, moved and turned; in its own frame the figure stands 1.2 m back along -x.
rig_location = Vector((0.8, -0.3, 0.0))
rig_turn = math.radians(30.0)
figure_offset = Vector((-1.2, 0.0, 0.0))

rig = bpy.data.objects.new("Figure rig", bpy.data.armatures.new("Figure rig"))
scene.collection.objects.link(rig)
rig.location = rig_location
rig.rotation_euler = (0.0, 0.0, rig_turn)
bpy.ops.object.select_all(action="DESELECT")
rig.select_set(True)
bpy.context.view_layer.objects.active = rig
bpy.ops.object.mode_set(mode="EDIT")
bones = {}
for name, head, tail, parent in (
        ("hips", (0.0, 0.0, 0.85), (0.0, 0.0, 1.0), None),
        ("spine", (0.0, 0.0, 1.0), (0.0, 0.0, 1.38), "hips"),
        ("head", (0.0, 0.0, 1.38), (0.0, 0.0, 1.6), "spine"),
        ("leg_l", (0.0, 0.1, 0.85), (0.0, 0.1, 0.05), "hips"),
        ("leg_r", (0.0, -0.1, 0.85), (0.0, -0.1, 0.05), "hips"),
        ("arm_l", (0.0, 0.24, 1.36), (0.0, 0.24, 0.8), "spine"),
        ("arm_r", (0.0, -0.24, 1.36), (0.0, -0.24, 0.8), "spine")):
    bone = rig.data.edit_bones.new(name)
    bone.head = figure_offset + Vector(head)
    bone.tail = figure_offset + Vector(tail)
    if parent is not None:
        bone.parent = bones[parent]
        bone.use_connect = False
    bones[name] = bone
bpy.ops.object.mode_set(mode="OBJECT")

# The figure is the rig's child, offset in the rig's frame, and deformed by its Armature modifier
# (what Ctrl P > With Empty Groups makes, with the groups already filled).
figure.parent = rig
figure.matrix_parent_inverse = Matrix.Identity(4)
figure.location = figure_offset
modifier = figure.modifiers.new("Armature", "ARMATURE")
modifier.object = rig


# The walk: pose-bone keys are in each bone's rest frame, so directions in the rig's frame are
# turned into it first.
def in_bone_frame(bone_name, direction):
    return rig.data.bones[bone_name].matrix_local.to_3x3().inverted() @ Vector(direction)


rig.animation_data_create()
rig.animation_data.action = bpy.data.actions.new("Walk")
pose = rig.pose.bones
for frame in range(1, 62, 5):
    phase = 2.0 * math.pi * (frame - 1) / 30.0
    walked = (frame - 1) / 60.0
    pose["hips"].location = in_bone_frame("hips", (walked, 0.0, 0.0))
    pose["hips"].keyframe_insert(data_path="location", frame=frame)
    swing = math.radians(25.0) * math.sin(phase)
    arm_swing = math.radians(20.0) * math.sin(phase)
    for bone, angle in (("leg_l", swing), ("leg_r", -swing), ("arm_l", -arm_swing),
                        ("arm_r", arm_swing)):
        # Positive turns about the rig's -y carry the foot or hand towards +x (forwards).
        pose[bone].rotation_quaternion = Quaternion(in_bone_frame(bone, (0.0, -1.0, 0.0)),
                                                    angle)
        pose[bone].keyframe_insert(data_path="rotation_quaternion", frame=frame)
    twist = math.radians(6.0) * math.sin(phase)
    pose["spine"].rotation_quaternion = Quaternion(in_bone_frame("spine", (0.0, 0.0, 1.0)),
                                                   twist)
    pose["spine"].keyframe_insert(data_path="rotation_quaternion", frame=frame)
scene.frame_set(1)

# 60 W of light; Blender's exporter writes the point light's intensity in candela.
bpy.ops.object.light_add(type="POINT", location=(0.3, -0.2, 2.3))
lamp = bpy.context.active_object
lamp.name = "Ceiling lamp"
lamp.data.energy = 60.0
lamp.data.shadow_soft_size = 0.0

# From the open side, looking at the floor the figure walks over.
camera((0.2, -4.6, 1.9), (1.3, 0.0, 0.0), 24.0)

# export_level's exporter call exports skins and the armature's animation with the exporter's
# defaults (export_skins, all bones not only deforming ones as export_def_bones is off, at most
# four joints a vertex as export_all_influences is off, the action sampled every frame as
# export_force_sampling is on); export_apply keeps the Armature modifier out of the applied mesh
# while skins are exported, so the vertices are the rest pose's.
export_level(out_path, lights=True)
