"""Classes 2 and 4: finite numbers whose products overflow float (JSON has no NaN or Inf, so
a hostile file reaches them through arithmetic): cameras and transforms that give non-finite
rays, animation keys whose interpolation overflows, and light power that is not finite.

luxel-ref renders at --time 0, where an animation holds its first key; cases whose overflow
happens between keys ask ref for --time 0.5 (the sandbox's second frame is at t = 1/30 s).
"""

import struct

from . import case, kit

BIG = 3e38          # just below FLT_MAX (3.4028235e38)
MID_TIME = {"ref": ["--time", "0.5"]}


def cam(name, description, **kw):
    return case(name, "nonfinite-camera", description, **kw)


def rad(name, description, **kw):
    return case(name, "radiometry", description, **kw)


def camera_case(c, camera_node=None, camera_fields=None, parents=()):
    """The reference scene with its camera node's fields replaced, and optionally the camera
    nested under parent nodes (outermost first) carrying the given fields."""
    doc, ids = kit.basic(camera_fields=camera_fields)
    node = doc.j["nodes"][ids["camera_node"]]
    if camera_node is not None:
        node.clear()
        node.update(dict(camera_node, camera=ids["camera"], name="eye"))
    if parents:
        child = ids["camera_node"]
        for fields in reversed(parents):
            child = doc.node(children=[child], **fields)
        doc.j["scenes"][0]["nodes"] = [n for n in ids["roots"] if n != ids["camera_node"]] + [
            child]
    c.gltf(doc)


@cam("cam-zero-scale", "camera node with scale [0, 0, 0]")
def _(c):
    camera_case(c, {"translation": [0, 0, 3], "scale": [0, 0, 0]})


@cam("cam-parent-scale-1e30", "camera under a parent scaled by 1e30, itself at z = 3")
def _(c):
    camera_case(c, {"translation": [0, 0, 3]}, parents=[{"scale": [1e30, 1e30, 1e30]}])


@cam("cam-parent-scale-1e-30", "camera under a parent scaled by 1e-30 (denormal axes)")
def _(c):
    camera_case(c, {"translation": [0, 0, 3]}, parents=[{"scale": [1e-30, 1e-30, 1e-30]}])


@cam("cam-nested-scales", "camera under 8 parents each scaled by 1e10 (1e80 in all)")
def _(c):
    camera_case(c, {"translation": [0, 0, 3]}, parents=[{"scale": [1e10] * 3}] * 8)


@cam("cam-parent-translation-big", "camera under a parent translated by 3e38, camera at 3e38")
def _(c):
    camera_case(c, {"translation": [BIG, BIG, BIG]}, parents=[{"translation": [BIG, BIG, BIG]}])


@cam("cam-translation-big", "camera node translated to (3e38, 3e38, 3e38)")
def _(c):
    camera_case(c, {"translation": [BIG, -BIG, BIG]})


@cam("cam-matrix-huge", "camera node matrix with 3e38 rotation entries")
def _(c):
    camera_case(c, {"matrix": [BIG, 0, 0, 0, 0, BIG, 0, 0, 0, 0, BIG, 0, 0, 0, 3, 1]})


@cam("cam-matrix-zero", "camera node matrix of all zeros but the last row")
def _(c):
    camera_case(c, {"matrix": [0] * 15 + [1]})


@cam("cam-matrix-denormal", "camera node matrix of denormal (1e-40) axes")
def _(c):
    camera_case(c, {"matrix": [1e-40, 0, 0, 0, 0, 1e-40, 0, 0, 0, 0, 1e-40, 0, 0, 0, 3, 1]})


@cam("cam-rotation-huge", "camera rotation quaternion (3e38, 0, 0, 3e38): its length overflows")
def _(c):
    camera_case(c, {"translation": [0, 0, 3], "rotation": [BIG, 0, 0, BIG]})


@cam("cam-rotation-tiny", "camera rotation quaternion of 1e-20 components")
def _(c):
    camera_case(c, {"translation": [0, 0, 3], "rotation": [1e-20, 1e-20, 1e-20, 1e-20]})


for _name, _fields, _text in (
        ("cam-yfov-1e-30", {"yfov": 1e-30}, "yfov 1e-30"),
        ("cam-yfov-denormal", {"yfov": 1e-40}, "yfov 1e-40 (denormal)"),
        ("cam-yfov-pi", {"yfov": 3.14159265}, "yfov pi (tan(yfov/2) overflows)"),
        ("cam-yfov-big", {"yfov": BIG}, "yfov 3e38"),
        ("cam-yfov-zero", {"yfov": 0.0}, "yfov 0"),
        ("cam-yfov-negative", {"yfov": -1.0}, "yfov -1"),
        ("cam-znear-denormal", {"znear": 1e-40}, "znear 1e-40 (denormal)"),
        ("cam-znear-zero", {"znear": 0.0}, "znear 0"),
        ("cam-znear-gt-zfar", {"znear": 10.0, "zfar": 1.0}, "znear 10 > zfar 1"),
        ("cam-znear-eq-zfar", {"znear": 1.0, "zfar": 1.0}, "znear == zfar"),
        ("cam-zfar-big", {"znear": 1e-38, "zfar": BIG}, "znear 1e-38, zfar 3e38"),
        ("cam-aspect-tiny", {"aspectRatio": 1e-30}, "aspectRatio 1e-30"),
        ("cam-aspect-big", {"aspectRatio": BIG}, "aspectRatio 3e38"),
        ("cam-aspect-negative", {"aspectRatio": -1.0}, "aspectRatio -1"),
        ("cam-aspect-zero", {"aspectRatio": 0.0}, "aspectRatio 0 (tinygltf reads it as absent)")):
    def _make(fields):
        return lambda c: camera_case(c, camera_fields=fields)
    cam(_name, "perspective camera with " + _text)(_make(_fields))


def ortho_case(c, **ortho):
    doc, ids = kit.basic()
    values = {"xmag": 1.0, "ymag": 1.0, "znear": 0.05, "zfar": 100.0}
    values.update(ortho)
    doc.j["cameras"][ids["camera"]] = {"type": "orthographic", "orthographic": values}
    c.gltf(doc)


for _name, _fields in (("cam-ortho-ymag-zero", {"ymag": 0.0}),
                       ("cam-ortho-ymag-denormal", {"ymag": 1e-40}),
                       ("cam-ortho-ymag-big", {"ymag": BIG, "xmag": BIG}),
                       ("cam-ortho-znear-eq-zfar", {"znear": 5.0, "zfar": 5.0}),
                       ("cam-ortho-zfar-big", {"znear": -BIG, "zfar": BIG})):
    cam(_name, "orthographic camera with %s" % _fields)(
        (lambda f: lambda c: ortho_case(c, **f))(_fields))


# -- animation keys --------------------------------------------------------------------------

def animated(c, target, path, values, interpolation="LINEAR", times=(0.0, 1.0), type_="VEC3",
             lightmapped=False):
    """The reference scene with one channel on node `target` ('mesh', 'camera' or 'light')."""
    doc, ids = kit.basic(lightmapped=lightmapped)
    node = ids[target + "_node"]
    inp = doc.floats(list(times), "SCALAR", with_bounds=True, target=None)
    out = doc.floats(values, type_, target=None)
    doc.j["animations"] = [{"channels": [{"sampler": 0, "target": {"node": node, "path": path}}],
                            "samplers": [{"input": inp, "output": out,
                                          "interpolation": interpolation}]}]
    c.gltf(doc)


@cam("anim-camera-translation-overflow", "camera translation keys -3e38 -> 3e38 (LINEAR)",
     args=MID_TIME)
def _(c):
    animated(c, "camera", "translation", [(-BIG, 0, 3), (BIG, 0, 3)])


@cam("anim-mesh-translation-overflow", "mesh translation keys -3e38 -> 3e38 (LINEAR)",
     args=MID_TIME)
def _(c):
    animated(c, "mesh", "translation", [(-BIG, -BIG, 0), (BIG, BIG, 0)])


@cam("anim-lightmapped-translation-overflow",
     "light-mapped mesh translation keys -3e38 -> 3e38 (LINEAR)", args=MID_TIME)
def _(c):
    animated(c, "mesh", "translation", [(-BIG, -BIG, 0), (BIG, BIG, 0)], lightmapped=True)


@cam("anim-light-translation-overflow", "light translation keys -3e38 -> 3e38 (LINEAR)",
     args=MID_TIME)
def _(c):
    animated(c, "light", "translation", [(-BIG, 0, 1), (BIG, 0, 1)])


@cam("anim-mesh-scale-overflow", "mesh scale keys 3e38 -> -3e38 (LINEAR)", args=MID_TIME)
def _(c):
    animated(c, "mesh", "scale", [(BIG, BIG, BIG), (-BIG, -BIG, -BIG)])


@cam("anim-mesh-scale-zero", "mesh scale keys 0 -> 0 (a collapsed mesh)", args=MID_TIME)
def _(c):
    animated(c, "mesh", "scale", [(0, 0, 0), (0, 0, 0)])


@cam("anim-camera-cubic-tangent", "camera CUBICSPLINE translation with 3e38 tangents",
     args=MID_TIME)
def _(c):
    animated(c, "camera", "translation",
             [(BIG, BIG, BIG), (0, 0, 3), (BIG, BIG, BIG)] * 2, interpolation="CUBICSPLINE")


@cam("anim-camera-cubic-rotation", "camera CUBICSPLINE rotation with 3e38 tangents",
     args=MID_TIME)
def _(c):
    animated(c, "camera", "rotation",
             [(BIG, BIG, BIG, BIG), (0, 0, 0, 1), (BIG, -BIG, BIG, -BIG)] * 2,
             interpolation="CUBICSPLINE", type_="VEC4")


@cam("anim-light-cubic-tangent", "light CUBICSPLINE translation with 3e38 tangents",
     args=MID_TIME)
def _(c):
    animated(c, "light", "translation", [(BIG,) * 3, (0, 0, 1), (-BIG,) * 3] * 2,
             interpolation="CUBICSPLINE")


@cam("anim-times-huge", "keys at t = 0 and 3e38 (a near-infinite duration)", args=MID_TIME)
def _(c):
    animated(c, "mesh", "translation", [(0, 0, 0), (1, 0, 0)], times=(0.0, BIG))


@cam("anim-times-denormal", "keys at t = 0 and 1e-40 (a denormal interval)", args=MID_TIME)
def _(c):
    animated(c, "camera", "translation", [(0, 0, 3), (BIG, 0, 3)], times=(0.0, 1e-40))


# -- geometry far from the origin --------------------------------------------------------------

@cam("geom-positions-huge", "quad with vertices at +-3e38 (areas and normals overflow)")
def _(c):
    doc, _ = kit.basic(positions=[(-BIG, -BIG, 0), (BIG, -BIG, 0), (BIG, BIG, 0), (-BIG, BIG, 0)])
    c.gltf(doc)


@cam("geom-mesh-scale-1e30", "quad node scaled by 1e30 (world positions overflow)")
def _(c):
    doc, _ = kit.basic(mesh_node_fields={"scale": [1e30, 1e30, 1e30]})
    c.gltf(doc)


@cam("geom-lightmapped-scale-1e30", "light-mapped quad node scaled by 1e30")
def _(c):
    doc, _ = kit.basic(lightmapped=True, mesh_node_fields={"scale": [1e30, 1e30, 1e30]})
    c.gltf(doc)


@cam("geom-light-far", "point light at (3e38, 3e38, 3e38)")
def _(c):
    doc, ids = kit.basic()
    doc.j["nodes"][ids["light_node"]]["translation"] = [BIG, BIG, BIG]
    c.gltf(doc)


@cam("geom-positions-denormal", "quad with denormal-sized vertices (1e-40)")
def _(c):
    doc, _ = kit.basic(positions=[(-1e-40, -1e-40, 0), (1e-40, -1e-40, 0), (1e-40, 1e-40, 0),
                                  (-1e-40, 1e-40, 0)])
    c.gltf(doc)


# -- class 4: light power and emission ----------------------------------------------------------

def light_case(c, lightmapped=True, **fields):
    doc, _ = kit.basic(light_fields=fields, lightmapped=lightmapped)
    c.gltf(doc)


for _name, _fields, _text in (
        ("rad-point-color-intensity-1e20",
         {"type": "point", "color": [1e20] * 3, "intensity": 1e20}, "point colour 1e20 x 1e20"),
        ("rad-spot-color-intensity-1e20",
         {"type": "spot", "color": [1e20] * 3, "intensity": 1e20,
          "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}}, "spot colour 1e20 x 1e20"),
        ("rad-sun-color-intensity-1e20",
         {"type": "directional", "color": [1e20] * 3, "intensity": 1e20},
         "directional colour 1e20 x 1e20"),
        ("rad-point-intensity-big", {"type": "point", "intensity": BIG}, "point intensity 3e38"),
        ("rad-spot-intensity-big",
         {"type": "spot", "intensity": BIG, "spot": {"outerConeAngle": 0.7}},
         "spot intensity 3e38"),
        ("rad-sun-intensity-big", {"type": "directional", "intensity": BIG},
         "directional intensity 3e38"),
        ("rad-color-big", {"type": "point", "color": [BIG] * 3, "intensity": 1.0},
         "point colour 3e38"),
        ("rad-intensity-denormal", {"type": "point", "intensity": 1e-45},
         "point intensity 1e-45 (denormal)"),
        ("rad-spot-cone-tiny",
         {"type": "spot", "intensity": 1e30, "spot": {"innerConeAngle": 0.0,
                                                      "outerConeAngle": 1e-30}},
         "spot 1e30 cd into a 1e-30 rad cone"),
        ("rad-range-tiny", {"type": "point", "intensity": 10.0, "range": 1e-30},
         "point range 1e-30"),
        ("rad-range-big", {"type": "point", "intensity": 10.0, "range": BIG},
         "point range 3e38")):
    rad(_name, "light with " + _text)((lambda f: lambda c: light_case(c, **f))(_fields))


@rad("rad-many-big-lights", "ten point lights of 3e38 cd at one spot (their sum overflows)")
def _(c):
    doc, ids = kit.basic(lightmapped=True, light_fields={"type": "point", "intensity": BIG})
    for _ in range(9):
        ids["roots"].append(doc.light_node(ids["light"], translation=[0, 0, 1.5]))
    doc.scene(ids["roots"])
    c.gltf(doc)


def emissive_case(c, strength, factor=(1, 1, 1), lightmapped=True, positions=None):
    doc, _ = kit.basic(lightmapped=lightmapped, positions=positions, material_fields={
        "emissiveFactor": list(factor),
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}})
    doc.use_extension("KHR_materials_emissive_strength")
    c.gltf(doc)


rad("rad-emissive-strength-big", "emissiveStrength 3e38 with emissiveFactor 1")(
    lambda c: emissive_case(c, BIG))
rad("rad-emissive-strength-1e20", "emissiveStrength 1e20, unlit scene otherwise")(
    lambda c: emissive_case(c, 1e20))
rad("rad-emissive-strength-unmapped", "emissiveStrength 3e38 on a mesh without a light map")(
    lambda c: emissive_case(c, BIG, lightmapped=False))
rad("rad-emissive-strength-denormal", "emissiveStrength 1e-45")(
    lambda c: emissive_case(c, 1e-45))
rad("rad-emissive-huge-area", "emissiveStrength 1e20 on a quad of 1e18 m sides")(
    lambda c: emissive_case(c, 1e20, lightmapped=False,
                            positions=[(-1e18, -1e18, 0), (1e18, -1e18, 0), (1e18, 1e18, 0),
                                       (-1e18, 1e18, 0)]))


def ior_case(c, ior, transmission=1.0):
    doc, _ = kit.basic(lightmapped=True, material_fields={
        "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0.0,
                                 "roughnessFactor": 0.0},
        "extensions": {"KHR_materials_ior": {"ior": ior},
                       "KHR_materials_transmission": {"transmissionFactor": transmission}}})
    doc.use_extension("KHR_materials_ior")
    doc.use_extension("KHR_materials_transmission")
    c.gltf(doc)


rad("rad-ior-big", "transmissive material with ior 3e38")(lambda c: ior_case(c, BIG))
rad("rad-ior-1e20", "transmissive material with ior 1e20")(lambda c: ior_case(c, 1e20))
rad("rad-ior-one", "transmissive material with ior exactly 1")(lambda c: ior_case(c, 1.0))

assert struct.unpack("<f", struct.pack("<f", BIG))[0] < 3.5e38  # BIG is a finite float
