"""Class 5: values of the wrong JSON type (and integers beyond 64 bits) in every place luxel
reads, and truncated or corrupt images behind a material's base-colour texture.

Each case is the reference scene with one value replaced, so any failure is that value's.
"""

import json
import struct
import zlib

from . import case, kit

BIG = 3e38


def types(name, description, **kw):
    return case(name, "types", description, **kw)


def patched(mutate, lightmapped=False):
    """A case function: the reference scene, mutate(doc.j, ids), written as .gltf."""
    def make(c):
        doc, ids = kit.basic(lightmapped=lightmapped)
        mutate(doc.j, ids)
        c.gltf(doc)
    return make


def on_node(key, value, node="mesh_node"):
    def mutate(j, ids):
        j["nodes"][ids[node]][key] = value
    return mutate


def luxel_extras(value, node="mesh_node"):
    return on_node("extras", {"luxel": value}, node)


_NODE_VALUES = [
    ("type-mesh-half", "mesh", 0.5),
    ("type-mesh-2pow64", "mesh", 18446744073709551616),
    ("type-mesh-2pow63", "mesh", 9223372036854775808),
    ("type-mesh-2pow32", "mesh", 4294967296),
    ("type-mesh-minus1", "mesh", -1),
    ("type-mesh-minus2", "mesh", -2),
    ("type-mesh-string", "mesh", "0"),
    ("type-mesh-bool", "mesh", True),
    ("type-mesh-null", "mesh", None),
    ("type-mesh-1e300", "mesh", 1e300),
    ("type-mesh-array", "mesh", [0]),
    ("type-children-string", "children", "a"),
    ("type-children-float", "children", [0.5]),
    ("type-children-negative", "children", [-1]),
    ("type-children-2pow64", "children", [18446744073709551616]),
    ("type-children-2pow32-plus1", "children", [4294967297]),
    ("type-children-object", "children", {}),
    ("type-extras-number", "extras", 5),
    ("type-extras-string", "extras", "x"),
    ("type-extras-array", "extras", []),
    ("type-translation-strings", "translation", ["a", "b", "c"]),
    ("type-translation-short", "translation", [1, 2]),
    ("type-translation-2pow64", "translation", [18446744073709551616, 0, 0]),
    ("type-rotation-object", "rotation", {"x": 0}),
    ("type-scale-string", "scale", "1"),
    ("type-matrix-short", "matrix", [1, 0, 0]),
    ("type-name-number", "name", 5),
    ("type-extensions-string", "extensions", "x"),
]
for _name, _key, _value in _NODE_VALUES:
    types(_name, "mesh node with %s = %s" % (_key, kit.dumps(_value)))(
        patched(on_node(_key, _value)))

types("type-camera-half", "camera node with camera = 0.5")(
    patched(on_node("camera", 0.5, "camera_node")))
types("type-camera-2pow64", "camera node with camera = 2^64")(
    patched(on_node("camera", 18446744073709551616, "camera_node")))

_LUXEL_VALUES = [
    ("type-luxel-number", 5, "mesh_node"),
    ("type-luxel-bounce-string", {"bounce": "high"}, "mesh_node"),
    ("type-luxel-bounce-height-string", {"bounce": {"height": "x"}}, "mesh_node"),
    ("type-luxel-bounce-period-zero", {"bounce": {"period": 0}}, "mesh_node"),
    ("type-luxel-bounce-period-denormal", {"bounce": {"period": 1e-45, "height": 1}},
     "mesh_node"),
    ("type-luxel-bounce-height-big", {"bounce": {"height": BIG, "period": 1}}, "mesh_node"),
    ("type-luxel-bounce-height-1e300", {"bounce": {"height": 1e300, "period": 1}}, "mesh_node"),
    ("type-luxel-bounce-array", {"bounce": [1, 2]}, "mesh_node"),
    ("type-luxel-dynamic-string", {"dynamic": "yes"}, "mesh_node"),
    ("type-luxel-enabled-number", {"enabled": 1}, "light_node"),
    ("type-luxel-switch-string", {"switch": "on"}, "light_node"),
    ("type-luxel-switch-period-string", {"switch": {"period": "2"}}, "light_node"),
    ("type-luxel-switch-period-tiny", {"switch": {"period": 1e-300, "on": 0.5}}, "light_node"),
    ("type-luxel-switch-phase-huge", {"switch": {"period": 1, "on": 0.5, "phase": 1e308}},
     "light_node"),
    ("type-luxel-switch-on-negative", {"switch": {"period": 1, "on": -1e308}}, "light_node"),
    ("type-luxel-wave-big", {"wave": {"amplitude": BIG, "wavelength": 1e-45, "speed": BIG,
                                      "direction": [BIG, BIG]}}, "mesh_node"),
    ("type-luxel-wave-string", {"wave": "calm"}, "mesh_node"),
    ("type-luxel-lightmap-number", {"lightmap": 5}, "mesh_node"),
    ("type-luxel-lightmap-page-string", {"lightmap": {"texel_size": 0.1, "page_size": "16",
                                                      "surfaces": []}}, "mesh_node"),
    ("type-luxel-lightmap-page-2pow64", {"lightmap": {"texel_size": 0.1,
                                                      "page_size": 18446744073709551616,
                                                      "surfaces": []}}, "mesh_node"),
    ("type-luxel-lightmap-surfaces-object", {"lightmap": {"texel_size": 0.1, "page_size": 16,
                                                          "surfaces": {}}}, "mesh_node"),
    ("type-luxel-lightmap-rect-floats", {"lightmap": kit.lightmap(16, [dict(
        kit.surface(), rect=[0.5, 0.5, 1.5, 1.5])])}, "mesh_node"),
    ("type-luxel-lightmap-id-2pow64", {"lightmap": kit.lightmap(16, [dict(
        kit.surface(), id=18446744073709551616)])}, "mesh_node"),
    ("type-luxel-lightmap-texels-string", {"lightmap": kit.lightmap(16, [dict(
        kit.surface(), texels="many")])}, "mesh_node"),
    ("type-luxel-lightmap-no-texcoord1", {"lightmap": kit.lightmap()}, "mesh_node"),
]
for _name, _value, _node in _LUXEL_VALUES:
    types(_name, "%s with extras.luxel = %s" % (_node.split("_")[0], kit.dumps(_value)[:120]))(
        patched(luxel_extras(_value, _node)))


def sky_extras(value):
    def mutate(j, ids):
        j["scenes"][0]["extras"] = {"luxel": {"sky": value}}
    return mutate


# The scene's sky (docs/LEVELS.md, "Sky"): a wrong one fails the load with the field's name; a
# valid one at the edge of float loads, and its radiance stays finite.
_SKY_VALUES = [
    ("type-sky-number", 5, "error"),
    ("type-sky-kind-missing", {"radiance": [1, 1, 1]}, "error"),
    ("type-sky-kind-unknown", {"kind": "map", "file": "../../../etc/passwd"}, "error"),
    ("type-sky-radiance-string", {"kind": "uniform", "radiance": "blue"}, "error"),
    ("type-sky-radiance-two", {"kind": "uniform", "radiance": [1, 2]}, "error"),
    ("type-sky-radiance-negative", {"kind": "uniform", "radiance": [1, -1e308, 1]}, "error"),
    ("type-sky-radiance-1e300", {"kind": "uniform", "radiance": [1e300, 1, 1]}, "error"),
    ("type-sky-turbidity-null", {"kind": "daylight", "turbidity": None}, "error"),
    ("type-sky-radiance-big", {"kind": "uniform", "radiance": [BIG, BIG, BIG], "scale": BIG},
     "success"),
    ("type-sky-daylight-big", {"kind": "daylight", "irradiance": BIG, "turbidity": BIG},
     "success"),
    ("type-sky-daylight-zero", {"kind": "daylight", "irradiance": 0, "turbidity": 0}, "success"),
]
for _name, _value, _expect in _SKY_VALUES:
    types(_name, "scene with extras.luxel.sky = %s" % kit.dumps(_value)[:120], expect=_expect)(
        patched(sky_extras(_value), lightmapped=True))


@types("type-luxel-lightmap-primitive-missing", "light map surface naming primitive 7 of a "
       "one-primitive mesh")
def _(c):
    def mutate(j, ids):
        j["nodes"][ids["mesh_node"]]["extras"]["luxel"]["lightmap"]["surfaces"][0][
            "primitive"] = 7
    patched(mutate, lightmapped=True)(c)


def set_path(path, value):
    """mutate() setting j[path...] = value; path steps may name ids keys with '@'."""
    def mutate(j, ids):
        target = j
        for step in path[:-1]:
            target = target[ids[step[1:]] if isinstance(step, str) and step[0] == "@" else step]
        last = path[-1]
        target[ids[last[1:]] if isinstance(last, str) and last[0] == "@" else last] = value
    return mutate


LIGHT_EXT = ("nodes", "@light_node", "extensions", "KHR_lights_punctual")
LIGHTS = ("extensions", "KHR_lights_punctual", "lights", 0)
_PATH_VALUES = [
    ("type-light-ref-half", LIGHT_EXT + ("light",), 0.5),
    ("type-light-ref-string", LIGHT_EXT + ("light",), "0"),
    ("type-light-ref-2pow64", LIGHT_EXT + ("light",), 18446744073709551616),
    ("type-light-ext-number", LIGHT_EXT, 0),
    ("type-light-type-number", LIGHTS + ("type",), 5),
    ("type-light-type-unknown", LIGHTS + ("type",), "area"),
    ("type-light-color-string", LIGHTS + ("color",), "white"),
    ("type-light-color-short", LIGHTS + ("color",), [1, 1]),
    ("type-light-intensity-string", LIGHTS + ("intensity",), "bright"),
    ("type-lights-object", ("extensions", "KHR_lights_punctual", "lights"), {}),
    ("type-scene-string", ("scene",), "0"),
    ("type-scene-2pow64", ("scene",), 18446744073709551616),
    ("type-scenes-object", ("scenes",), {}),
    ("type-scene-nodes-string", ("scenes", 0, "nodes"), "all"),
    ("type-nodes-object", ("nodes",), {}),
    ("type-accessors-number", ("accessors",), 5),
    ("type-accessor-count-string", ("accessors", 0, "count"), "4"),
    ("type-accessor-count-2pow64", ("accessors", 0, "count"), 18446744073709551616),
    ("type-accessor-component-double", ("accessors", 0, "componentType"), 5130),
    ("type-accessor-type-vec5", ("accessors", 0, "type"), "VEC5"),
    ("type-accessor-normalized-float", ("accessors", 0, "normalized"), True),
    ("type-bufferview-offset-2pow64", ("bufferViews", 0, "byteOffset"), 18446744073709551616),
    ("type-asset-version-number", ("asset", "version"), 2),
    ("type-asset-version-1", ("asset", "version"), "1.0"),
    ("type-asset-string", ("asset",), "2.0"),
    ("type-buffer-length-string", ("buffers",), [{"byteLength": "big"}]),
    ("type-material-index-half", ("meshes", 0, "primitives", 0, "material"), 0.5),
    ("type-primitive-mode-2pow32", ("meshes", 0, "primitives", 0, "mode"), 4294967300),
    ("type-attributes-array", ("meshes", 0, "primitives", 0, "attributes"), [0]),
    ("type-base-color-string", ("materials", 0, "pbrMetallicRoughness", "baseColorFactor"),
     "red"),
    ("type-emissive-strength-string", ("materials", 0, "extensions"),
     {"KHR_materials_emissive_strength": {"emissiveStrength": "hot"}}),
    ("type-transmission-object", ("materials", 0, "extensions"),
     {"KHR_materials_transmission": {"transmissionFactor": {}}}),
    ("type-extensions-required-string", ("extensionsRequired",), "KHR_lights_punctual"),
    ("type-camera-yfov-string", ("cameras", 0, "perspective", "yfov"), "wide"),
    ("type-camera-type-number", ("cameras", 0, "type"), 1),
]


for _name, _path, _value in _PATH_VALUES:
    types(_name, "%s = %s" % ("/".join(str(p) for p in _path), kit.dumps(_value)[:80]))(
        (lambda p, v: lambda c: _write_patched(c, p, v))(_path, _value))


def _write_patched(c, path, value):
    # Patched after the buffer entry exists, so buffers and bufferViews can be bent too.
    doc, ids = kit.basic()
    text = doc.gltf_embedded()
    j = json.loads(text)
    set_path(path, value)(j, ids)
    c.gltf(j)


# -- truncated and corrupt images behind a material ---------------------------------------------

def image_case(c, data, ext="png", mime=None):
    """The light-mapped reference quad textured by `data` (as a file beside the level), so
    the sandbox uploads it and luxel-ref averages it for the surface's albedo."""
    name = c.write("tex." + ext, data)
    doc, ids = kit.basic(lightmapped=True)
    fields = {"uri": name}
    if mime:
        fields["mimeType"] = mime
    texture = doc.image_texture(fields)
    doc.j["materials"][ids["material"]]["pbrMetallicRoughness"]["baseColorTexture"] = {
        "index": texture}
    c.gltf(doc)


def _rows(width, height, channels=3):
    return b"".join(b"\0" + bytes((x * 37 + y * 11) % 256 for x in range(width * channels))
                    for y in range(height))


GOOD_PNG = kit.png(64, 64, rows=_rows(64, 64))
GOOD_JPEG = kit.jpeg(64, 64)
_idat_at = GOOD_PNG.index(b"IDAT")


def _bad_crc(png):
    i = png.index(b"IDAT")
    length = struct.unpack(">I", png[i - 4:i])[0]
    crc_at = i + 4 + length
    return png[:crc_at] + bytes(b ^ 0xFF for b in png[crc_at:crc_at + 4]) + png[crc_at + 4:]


_IMAGES = [
    ("img-png-truncated", GOOD_PNG[:_idat_at + 200], "png", "64x64 PNG cut inside its IDAT"),
    ("img-png-ihdr-only", kit.png_header(64, 64), "png", "PNG signature and IHDR, nothing else"),
    ("img-png-signature-only", GOOD_PNG[:8], "png", "the 8-byte PNG signature alone"),
    ("img-png-bad-crc", _bad_crc(GOOD_PNG), "png", "PNG whose IDAT CRC is wrong"),
    ("img-png-bad-zlib", kit.png_header(64, 64) + kit.png_chunk(b"IDAT", b"\x78\x9c" +
                                                                b"\xff" * 64) +
     kit.png_chunk(b"IEND", b""), "png", "PNG whose IDAT is not a zlib stream"),
    ("img-png-short-rows", kit.png_header(64, 64) + kit.png_chunk(
        b"IDAT", zlib.compress(_rows(64, 3))) + kit.png_chunk(b"IEND", b""), "png",
     "64x64 PNG whose IDAT holds 3 rows"),
    ("img-png-palette-no-plte", b"\x89PNG\r\n\x1a\n" + kit.png_chunk(
        b"IHDR", struct.pack(">IIBBBBB", 8, 8, 8, 3, 0, 0, 0)) + kit.png_chunk(
        b"IDAT", zlib.compress(b"\0" * 72)) + kit.png_chunk(b"IEND", b""), "png",
     "palette PNG without a PLTE chunk"),
    ("img-png-width-zero", kit.png_header(0, 64) + kit.png_chunk(b"IEND", b""), "png",
     "PNG IHDR of width 0"),
    ("img-jpeg-truncated", GOOD_JPEG[:len(GOOD_JPEG) // 2], "jpg",
     "64x64 JPEG cut in half"),
    ("img-jpeg-before-scan", GOOD_JPEG[:GOOD_JPEG.index(b"\xff\xda")], "jpg",
     "JPEG cut just before its scan"),
    ("img-jpeg-soi-only", b"\xff\xd8\xff", "jpg", "the JPEG start marker alone"),
    ("img-jpeg-sof-bigger", kit.jpeg(8, 8, 4096, 4096), "jpg",
     "JPEG whose frame header claims 4096x4096 but holds one block"),
    ("img-jpeg-sof-65500", kit.jpeg(8, 8, 65500, 65500), "jpg",
     "JPEG whose frame header claims 65500x65500"),
    ("img-gif", b"GIF89a\x01\x00\x01\x00\x00\x00\x00;", "gif", "a GIF (not allowed by glTF)"),
    ("img-bmp", b"BM" + b"\0" * 60, "bmp", "a BMP (not allowed by glTF)"),
    ("img-empty-file", b"", "png", "a 0-byte image file"),
    ("img-png-as-jpeg-mime", kit.SMALL_PNG, "jpg", "a PNG declared image/jpeg (harmless)"),
]
for _name, _data, _ext, _text in _IMAGES:
    types(_name, "base-colour texture: " + _text)(
        (lambda d, e: lambda c: image_case(c, d, e, "image/jpeg" if e == "jpg" else None))(
            _data, _ext))


@types("img-glb-bufferview-truncated", "GLB image in a bufferView holding half a PNG")
def _(c):
    doc, ids = kit.basic(lightmapped=True)
    view = doc.view(GOOD_PNG[:len(GOOD_PNG) // 2])
    texture = doc.image_texture({"bufferView": view, "mimeType": "image/png"})
    doc.j["materials"][ids["material"]]["pbrMetallicRoughness"]["baseColorTexture"] = {
        "index": texture}
    c.glb(doc)
