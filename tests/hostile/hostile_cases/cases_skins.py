"""Skins (issue 29): the reference quad skinned to two joints, one of them animated, and the ways
a skin can be malformed or push its vertices towards overflow. A skinned mesh is posed on the
CPU every frame its joints move, so every product of joint and inverse bind matrix must stay
finite, and everything malformed must be refused at load, naming the file.
"""

import struct

from . import case, kit

BIG = 3e38
IDENTITY = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]


def skinned_quad(c, joints=None, weights=None, inverse_bind=None, joint_nodes=None,
                 joint_fields=None, extra_attributes=None, animate=True):
    """The reference scene whose quad is skinned to joints 'left' and 'right' (vertices 0 and 3
    to the left one, 1 and 2 to the right one, unless `joints`/`weights` say otherwise); the
    right joint turns a quarter turn over a second."""
    doc, ids = kit.basic()
    left = doc.node(name="left", translation=[-1, 0, 0], **(joint_fields or {}))
    right = doc.node(name="right", translation=[1, 0, 0])
    rows_j = joints or [(0, 0, 0, 0), (1, 0, 0, 0), (1, 0, 0, 0), (0, 0, 0, 0)]
    rows_w = weights or [(1, 0, 0, 0)] * 4
    primitive = doc.j["meshes"][ids["mesh"]]["primitives"][0]
    data = struct.pack("<%dB" % (4 * len(rows_j)), *[v for row in rows_j for v in row])
    primitive["attributes"]["JOINTS_0"] = doc.accessor(doc.view(data, kit.ARRAY_BUFFER), kit.U8,
                                                       "VEC4", len(rows_j))
    primitive["attributes"]["WEIGHTS_0"] = doc.floats(rows_w, "VEC4")
    for name, attribute in (extra_attributes or {}).items():
        primitive["attributes"][name] = primitive["attributes"][attribute]
    matrices = inverse_bind or (IDENTITY[:12] + [1.0, 0, 0, 1.0]) + (IDENTITY[:12] + [-1.0, 0, 0, 1.0])
    ibm = doc.accessor(doc.view(struct.pack("<%df" % len(matrices), *matrices)), kit.FLOAT,
                       "MAT4", len(matrices) // 16)
    doc.add("skins", {"joints": joint_nodes or [left, right], "inverseBindMatrices": ibm})
    doc.j["nodes"][ids["mesh_node"]]["skin"] = 0
    doc.j["scenes"][0]["nodes"] += [left, right]
    if animate:
        times = doc.floats([0.0, 1.0], "SCALAR", with_bounds=True)
        turn = doc.floats([(0, 0, 0, 1), (0, 0, 0.7071068, 0.7071068)], "VEC4")
        doc.add("animations", {"samplers": [{"input": times, "output": turn}],
                               "channels": [{"sampler": 0,
                                             "target": {"node": right, "path": "rotation"}}]})
    c.gltf(doc)


def skin(name, description, **kw):
    return case(name, "types", description, **kw)


@case("ctl-skinned", "control", "a quad skinned to two joints, one turning", expect="success",
      args={"ref": ["--time", "0.5"]})
def _(c):
    skinned_quad(c)


@skin("skin-joints-1", "a second set of joints and weights (JOINTS_1, WEIGHTS_1)", expect="error")
def _(c):
    skinned_quad(c, extra_attributes={"JOINTS_1": "JOINTS_0", "WEIGHTS_1": "WEIGHTS_0"})


@skin("skin-joint-index-beyond", "a vertex naming joint 200 of a skin of two", expect="error")
def _(c):
    skinned_quad(c, joints=[(0, 0, 0, 0), (200, 0, 0, 0), (1, 0, 0, 0), (0, 0, 0, 0)])


@skin("skin-weights-zero", "a vertex whose weights are all 0", expect="error")
def _(c):
    skinned_quad(c, weights=[(1, 0, 0, 0), (0, 0, 0, 0), (1, 0, 0, 0), (1, 0, 0, 0)])


@skin("skin-weights-big", "weights of 3e38 each (their sum overflows)", expect="any")
def _(c):
    skinned_quad(c, weights=[(BIG, BIG, BIG, BIG)] * 4)


@skin("skin-weights-denormal", "weights of 1e-40 (denormal; their sum may flush to 0)",
      expect="any")
def _(c):
    skinned_quad(c, weights=[(1e-40, 0, 0, 0)] * 4)


@case("skin-ibm-1e30", "nonfinite-camera", "inverse bind matrices scaling by 1e30",
      expect="error")
def _(c):
    big = [1e30, 0, 0, 0, 0, 1e30, 0, 0, 0, 0, 1e30, 0, 0, 0, 0, 1.0]
    skinned_quad(c, inverse_bind=big + big)


@case("skin-joint-scale-1e5", "nonfinite-camera",
      "a joint scaled by 1e5 and an inverse bind matrix by 1e6 (vertices 1e11 m out)",
      expect="any", args={"ref": ["--time", "0.5"]})
def _(c):
    ibm = [1e6, 0, 0, 0, 0, 1e6, 0, 0, 0, 0, 1e6, 0, 0, 0, 0, 1.0]
    skinned_quad(c, inverse_bind=ibm + ibm, joint_fields={"scale": [1e5, 1e5, 1e5]})


@case("skin-joints-10000", "alloc", "a skin of 10,000 joints, one node each", expect="any")
def _(c):
    doc, ids = kit.basic()
    first = len(doc.j["nodes"])
    joints = [doc.node(name="j%d" % k) for k in range(10000)]
    primitive = doc.j["meshes"][ids["mesh"]]["primitives"][0]
    data = struct.pack("<16H", *([9999, 0, 0, 0] * 4))
    primitive["attributes"]["JOINTS_0"] = doc.accessor(doc.view(data, kit.ARRAY_BUFFER), kit.U16,
                                                       "VEC4", 4)
    primitive["attributes"]["WEIGHTS_0"] = doc.floats([(1, 0, 0, 0)] * 4, "VEC4")
    doc.add("skins", {"joints": joints})
    doc.j["nodes"][ids["mesh_node"]]["skin"] = 0
    doc.j["scenes"][0]["nodes"] += list(range(first, first + 10000))
    c.gltf(doc)
