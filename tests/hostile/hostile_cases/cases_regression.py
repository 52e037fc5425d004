"""Class 7 (what the loader already refuses, kept as regression cases) and the controls: small
valid levels that every tool must load and render, so a runner that sees only errors notices
when the tools themselves are broken.
"""

import json
import os
import struct

from . import case, kit


def reg(name, description, **kw):
    return case(name, "regression", description, **kw)


def ctl(name, description, **kw):
    return case(name, "control", description, expect="success", **kw)


def _glb_parts():
    doc, _ = kit.basic()
    data = doc.glb()
    json_len = struct.unpack("<I", data[12:16])[0]
    return data, json_len


VALID_GLB, JSON_LEN = _glb_parts()
JSON_CHUNK = VALID_GLB[20:20 + JSON_LEN]
BIN_CHUNK = VALID_GLB[28 + JSON_LEN:]


def u32(v):
    return struct.pack("<I", v)


def header(length, version=2, magic=b"glTF"):
    return magic + u32(version) + u32(length)


def with_length(body):
    return header(12 + len(body)) + body


_GLB = [
    ("glb-bad-magic", b"glTX" + VALID_GLB[4:], "magic glTX"),
    ("glb-magic-only", b"glTF", "the 4-byte magic alone"),
    ("glb-11-bytes", VALID_GLB[:11], "11 bytes: the header cut short"),
    ("glb-header-only", header(12), "a 12-byte header declaring 12 bytes, no chunks"),
    ("glb-version-1", header(len(VALID_GLB), 1) + VALID_GLB[12:], "version 1"),
    ("glb-version-max", header(len(VALID_GLB), 0xFFFFFFFF) + VALID_GLB[12:], "version 2^32-1"),
    ("glb-length-larger", header(len(VALID_GLB) + 100) + VALID_GLB[12:],
     "header length 100 bytes beyond the file"),
    ("glb-length-smaller", header(len(VALID_GLB) - 4) + VALID_GLB[12:],
     "header length 4 bytes short of the file"),
    ("glb-length-zero", header(0) + VALID_GLB[12:], "header length 0"),
    ("glb-chunk-beyond", with_length(u32(JSON_LEN + 4096) + b"JSON" + JSON_CHUNK),
     "JSON chunk length beyond the file"),
    ("glb-chunk-length-max", with_length(u32(0xFFFFFFFC) + b"JSON" + JSON_CHUNK),
     "JSON chunk length 2^32-4"),
    ("glb-chunk-unaligned", with_length(u32(JSON_LEN - 1) + b"JSON" + JSON_CHUNK[:-1]),
     "JSON chunk length not a multiple of 4"),
    ("glb-first-chunk-bin", with_length(u32(len(BIN_CHUNK) - 8) + b"BIN\0" + BIN_CHUNK[8:]),
     "first chunk is BIN"),
    ("glb-json-chunk-empty", with_length(u32(0) + b"JSON"), "JSON chunk of length 0"),
    ("glb-no-json", with_length(BIN_CHUNK), "header and a BIN chunk only"),
    ("glb-bin-misaligned", with_length(u32(JSON_LEN) + b"JSON" + JSON_CHUNK + u32(3) + b"BIN\0" +
                                       b"abc"), "BIN chunk of 3 bytes (misaligned)"),
    ("glb-two-json", with_length((u32(JSON_LEN) + b"JSON" + JSON_CHUNK) * 2), "two JSON chunks"),
    ("glb-two-bin", with_length(u32(JSON_LEN) + b"JSON" + JSON_CHUNK + BIN_CHUNK * 2),
     "two BIN chunks"),
    ("glb-unknown-chunk", with_length(u32(JSON_LEN) + b"JSON" + JSON_CHUNK + u32(8) + b"XTRA" +
                                      b"\0" * 8), "JSON and an unknown chunk, no BIN"),
    ("glb-bin-short", with_length(u32(JSON_LEN) + b"JSON" + JSON_CHUNK + u32(8) + b"BIN\0" +
                                  BIN_CHUNK[8:16]), "BIN chunk shorter than the buffer"),
    ("glb-json-invalid-utf8", with_length(u32(8) + b"JSON" + b'{"\xff\xfe":1}'),
     "JSON chunk that is not UTF-8"),
    ("glb-cut-in-half", VALID_GLB[:len(VALID_GLB) // 2], "a valid GLB cut in half"),
]
for _name, _data, _text in _GLB:
    reg(_name, "GLB container: " + _text)((lambda d: lambda c: c.glb(d))(_data))

VALID_JSON = kit.basic()[0].gltf_embedded()
_JSON = [
    ("json-deep-arrays", b"[" * 100000, "100000 nested '['"),
    ("json-deep-objects", b'{"a":' * 100000, "100000 nested objects"),
    ("json-deep-extras", VALID_JSON[:-1] + b',"extras":' + b"[" * 300 + b"]" * 300 + b"}",
     "300 nested arrays inside extras, closed"),
    ("json-truncated", VALID_JSON[:len(VALID_JSON) // 2], "valid JSON cut in half"),
    ("json-empty-file", b"", "a 0-byte .gltf"),
    ("json-whitespace", b" \n\t " * 100, "whitespace only"),
    ("json-null", b"null", "the JSON value null"),
    ("json-array", b"[]", "an empty array"),
    ("json-number", b"0", "the number 0"),
    ("json-bom", b"\xef\xbb\xbf" + VALID_JSON, "a UTF-8 byte-order mark before valid JSON"),
    ("json-trailing-garbage", VALID_JSON + b"}}}garbage", "valid JSON followed by garbage"),
    ("json-invalid-utf8-name", VALID_JSON[:-1] + b',"extras":{"n":"\xc3\x28"}}',
     "an invalid UTF-8 sequence in a string"),
    ("json-nan-token", VALID_JSON.replace(b'"intensity":10.0', b'"intensity":NaN'),
     "a NaN token (not JSON)"),
    ("json-1e999", VALID_JSON.replace(b'"intensity":10.0', b'"intensity":1e999'),
     "intensity 1e999 (beyond double)"),
]
for _name, _data, _text in _JSON:
    reg(_name, "JSON: " + _text)((lambda d: lambda c: c.gltf(d))(_data))


def patched_text(mutate, glb=False):
    """The reference scene's JSON (buffer included) bent by mutate(j)."""
    def make(c):
        doc, ids = kit.basic()
        j = json.loads(doc.gltf_embedded())
        mutate(j, ids)
        if glb:
            j["buffers"][0].pop("uri", None)
            c.glb(kit.glb(kit.dumps(j).encode(), bytes(doc.bin)))
        else:
            c.gltf(j)
    return make


def setter(*path_value):
    *path, value = path_value

    def mutate(j, ids):
        target = j
        for step in path[:-1]:
            target = target[ids[step[1:]] if isinstance(step, str) and step[:1] == "@" else step]
        target[path[-1]] = value
    return mutate


PRIM = ("meshes", 0, "primitives", 0)
_SETS = [
    ("acc-offset-beyond", ("accessors", 0, "byteOffset", 1 << 20), "accessor byteOffset 1 MiB"),
    ("acc-count-beyond", ("accessors", 0, "count", 1000), "POSITION count 1000 of 4"),
    ("acc-count-2pow32", ("accessors", 0, "count", 1 << 32), "POSITION count 2^32"),
    ("acc-count-2pow62", ("accessors", 3, "count", 1 << 62), "indices count 2^62"),
    ("acc-count-zero", ("accessors", 0, "count", 0), "POSITION count 0"),
    ("view-offset-beyond", ("bufferViews", 0, "byteOffset", 1 << 30), "bufferView offset 1 GiB"),
    ("view-length-beyond", ("bufferViews", 0, "byteLength", 1 << 30), "bufferView length 1 GiB"),
    ("view-stride-small", ("bufferViews", 0, "byteStride", 4), "byteStride 4 for VEC3 floats"),
    ("view-stride-253", ("bufferViews", 0, "byteStride", 253), "byteStride 253"),
    ("view-stride-unaligned", ("bufferViews", 0, "byteStride", 13), "byteStride 13"),
    ("view-buffer-out-of-range", ("bufferViews", 0, "buffer", 5), "bufferView buffer 5"),
    ("acc-view-out-of-range", ("accessors", 0, "bufferView", 99), "accessor bufferView 99"),
    ("prim-indices-out-of-range", PRIM + ("indices", 99), "primitive indices accessor 99"),
    ("prim-position-out-of-range", PRIM + ("attributes", "POSITION", 99), "POSITION accessor 99"),
    ("prim-indices-float", ("accessors", 3, "componentType", 5126), "indices of FLOAT type"),
    ("prim-indices-vec3", ("accessors", 3, "type", "VEC3"), "indices of type VEC3"),
    ("prim-normal-count", ("accessors", 1, "count", 3), "NORMAL count 3, POSITION 4"),
    ("acc-sparse-out-of-range", ("accessors", 0, "sparse",
                                 {"count": 1000, "indices": {"bufferView": 3, "componentType":
                                                             5123}, "values": {"bufferView": 0}}),
     "sparse accessor of 1000 entries beyond its views"),
    ("acc-sparse-huge-count", ("accessors", 0, "sparse",
                               {"count": 1 << 40, "indices": {"bufferView": 3, "componentType":
                                                              5125}, "values": {"bufferView": 0}}),
     "sparse accessor count 2^40"),
    ("buffer-zero-length", ("buffers", [{"byteLength": 0}]), "buffer of byteLength 0"),
    ("buffer-length-huge", ("buffers", 0, "byteLength", 1 << 40), "buffer byteLength 2^40"),
    ("scene-out-of-range", ("scene", 5), "default scene 5 of 1"),
    ("scene-node-out-of-range", ("scenes", 0, "nodes", [0, 99]), "scene lists node 99"),
    ("scene-root-twice", ("scenes", 0, "nodes", [0, 0, 1]), "scene lists node 0 twice"),
    ("material-out-of-range", PRIM + ("material", 9), "primitive material 9"),
    ("texture-out-of-range", ("materials", 0, "pbrMetallicRoughness", "baseColorTexture",
                              {"index": 9}), "baseColorTexture 9 (no textures)"),
    ("camera-out-of-range", ("nodes", "@camera_node", "camera", 9), "node camera 9"),
    ("light-out-of-range", ("nodes", "@light_node", "extensions",
                            {"KHR_lights_punctual": {"light": 9}}), "node light 9"),
    ("node-self-child", ("nodes", 0, "children", [0]), "a node its own child"),
    ("extension-required-unknown", ("extensionsRequired", ["EXT_hostile_unknown"]),
     "extensionsRequired names an unknown extension"),
    ("skin-reference", ("nodes", 0, "skin", 0), "a node naming a skin (none exist)"),
]
for _name, _path_value, _text in _SETS:
    reg(_name, _text)(patched_text(setter(*_path_value)))


@reg("texture-source-out-of-range", "texture source 9, sampler 9")
def _(c):
    def mutate(j, ids):
        j["textures"] = [{"source": 9, "sampler": 9}]
        j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    patched_text(mutate)(c)


@reg("prim-index-beyond-vertices", "index value 60000 for 4 vertices")
def _(c):
    doc, _ = kit.basic(indices=[0, 1, 60000])
    c.gltf(doc)


def hierarchy(c, children, roots):
    doc, ids = kit.basic()
    for parent, kids in children.items():
        while len(doc.j["nodes"]) <= max([parent] + kids):
            doc.node()
        doc.j["nodes"][parent]["children"] = kids
    doc.scene(roots)
    c.gltf(doc)


reg("node-cycle-ab", "nodes 3 -> 4 -> 3")(lambda c: hierarchy(c, {3: [4], 4: [3]}, [0]))
reg("node-cycle-abc", "nodes 3 -> 4 -> 5 -> 3")(
    lambda c: hierarchy(c, {3: [4], 4: [5], 5: [3]}, [0]))
reg("node-two-parents", "node 5 child of nodes 3 and 4")(
    lambda c: hierarchy(c, {3: [5], 4: [5]}, [0, 3, 4]))
reg("node-root-has-parent", "scene root 1 is node 0's child")(
    lambda c: hierarchy(c, {0: [1]}, [0, 1]))


def chain(c, depth):
    doc, ids = kit.basic()
    first = len(doc.j["nodes"])
    for i in range(depth):
        doc.node(children=[first + i + 1] if i + 1 < depth else [])
    doc.scene(ids["roots"] + [first])
    c.gltf(doc)


reg("node-chain-100k", "a 100000-deep node hierarchy")(lambda c: chain(c, 100_000))
reg("node-chain-1025", "a 1025-deep node hierarchy (one beyond the limit)")(
    lambda c: chain(c, 1025))
reg("node-chain-1024", "a 1024-deep node hierarchy (at the limit)")(lambda c: chain(c, 1024))


def anim(c, sampler=None, channel=None, times=(0.0, 1.0), values=((0, 0, 0), (1, 0, 0))):
    doc, ids = kit.basic()
    inp = doc.floats(list(times), "SCALAR", target=None)
    out = doc.floats(list(values), "VEC3", target=None)
    s = dict({"input": inp, "output": out, "interpolation": "LINEAR"}, **(sampler or {}))
    ch = dict({"sampler": 0, "target": {"node": 0, "path": "translation"}}, **(channel or {}))
    doc.j["animations"] = [{"samplers": [s], "channels": [ch]}]
    c.gltf(doc)


reg("anim-sampler-out-of-range", "channel sampler 9")(lambda c: anim(c, channel={"sampler": 9}))
reg("anim-target-out-of-range", "channel target node 99")(
    lambda c: anim(c, channel={"target": {"node": 99, "path": "translation"}}))
reg("anim-times-decreasing", "keyframe times 1, 0")(lambda c: anim(c, times=(1.0, 0.0)))
reg("anim-times-negative", "keyframe times -1, 0")(lambda c: anim(c, times=(-1.0, 0.0)))
reg("anim-output-count", "3 output values for 2 keys")(
    lambda c: anim(c, values=((0, 0, 0), (1, 0, 0), (2, 0, 0))))
reg("anim-interpolation-unknown", "interpolation 'BOUNCY'")(
    lambda c: anim(c, sampler={"interpolation": "BOUNCY"}))


def bomb(c, width, height):
    data = kit.png_header(width, height) + kit.png_chunk(b"IDAT", b"\x78\x9c\x03\x00\x00\x00\x00"
                                                         b"\x01") + kit.png_chunk(b"IEND", b"")
    doc, ids = kit.basic(lightmapped=True)
    texture = doc.image_texture({"uri": c.write("bomb.png", data)})
    doc.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": texture}
    c.gltf(doc)


reg("img-ihdr-100000", "PNG IHDR claiming 100000x100000")(lambda c: bomb(c, 100000, 100000))
reg("img-ihdr-65535", "PNG IHDR claiming 65535x65535")(lambda c: bomb(c, 65535, 65535))
reg("img-ihdr-2pow31", "PNG IHDR claiming 2^31-1 x 1")(lambda c: bomb(c, 0x7FFFFFFF, 1))


def buffer_uri(c, uri):
    doc, _ = kit.basic()
    c.gltf_with_bin(doc, uri)


reg("uri-dev-zero", "buffer uri /dev/zero", forbidden=["/dev/zero"])(
    lambda c: buffer_uri(c, "/dev/zero"))


@reg("uri-symlink-dev-zero", "buffer uri data.bin, a symlink to /dev/zero",
     forbidden=["/dev/zero"])
def _(c):
    c.symlink("/dev/zero", "data.bin")
    buffer_uri(c, "data.bin")


@reg("uri-symlink-dev-urandom-image", "image uri tex.png, a symlink to /dev/urandom")
def _(c):
    c.symlink("/dev/urandom", "tex.png")
    doc, _ = kit.basic()
    texture = doc.image_texture({"uri": "tex.png"})
    doc.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": texture}
    c.gltf(doc)


@reg("uri-fifo", "buffer uri pipe.bin, a FIFO in the folder (opening it would block)")
def _(c):
    os.makedirs(c.dir, exist_ok=True)
    os.mkfifo(c.path("pipe.bin"))
    buffer_uri(c, "pipe.bin")


@reg("uri-fifo-image", "image uri pipe.png, a FIFO in the folder")
def _(c):
    os.makedirs(c.dir, exist_ok=True)
    os.mkfifo(c.path("pipe.png"))
    doc, _ = kit.basic()
    texture = doc.image_texture({"uri": "pipe.png"})
    doc.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": texture}
    c.gltf(doc)


reg("uri-missing", "buffer uri missing.bin (no such file)")(lambda c: buffer_uri(c, "missing.bin"))


@reg("uri-empty-file", "buffer uri empty.bin, a 0-byte file")
def _(c):
    c.write("empty.bin", b"")
    buffer_uri(c, "empty.bin")


reg("empty-level-glb", "a 0-byte .glb")(lambda c: c.glb(b""))


# -- controls: must succeed in every tool -------------------------------------------------------

ctl("ctl-quad", "lit quad, point light, camera; embedded buffer")(lambda c: c.gltf(kit.basic()[0]))
ctl("ctl-quad-glb", "the same as GLB")(lambda c: c.glb(kit.basic()[0]))
ctl("ctl-quad-external-bin", "the same with its buffer in a .bin beside it")(
    lambda c: c.gltf_with_bin(kit.basic()[0]))
ctl("ctl-lightmapped", "the quad with a forged 16-texel light map")(
    lambda c: c.gltf(kit.basic(lightmapped=True)[0]))
ctl("ctl-lightmapped-glb", "the light-mapped quad as GLB")(
    lambda c: c.glb(kit.basic(lightmapped=True)[0]))


@ctl("ctl-textured", "the light-mapped quad with a PNG texture beside it")
def _(c):
    doc, ids = kit.basic(lightmapped=True)
    texture = doc.image_texture({"uri": c.write("tex.png", kit.SMALL_PNG)})
    doc.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": texture}
    c.gltf(doc)


@ctl("ctl-spot-and-sun", "the light-mapped quad lit by a spot and a directional light")
def _(c):
    doc, ids = kit.basic(lightmapped=True, light_fields={
        "type": "spot", "intensity": 20.0, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}})
    sun = doc.light(type="directional", intensity=2.0)
    ids["roots"].append(doc.light_node(sun, rotation=[0.0, 0.0, 0.0, 1.0]))
    doc.scene(ids["roots"])
    c.gltf(doc)


@ctl("ctl-animated", "the quad sliding along x (LINEAR), rendered mid-way", args={
    "ref": ["--time", "0.5"]})
def _(c):
    anim(c, values=((0, 0, 0), (0.5, 0, 0)))


@ctl("ctl-emissive", "an emissive light-mapped quad (emissiveStrength 5)")
def _(c):
    doc, _ = kit.basic(lightmapped=True, material_fields={
        "emissiveFactor": [1, 1, 1],
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 5.0}}})
    doc.use_extension("KHR_materials_emissive_strength")
    c.gltf(doc)
