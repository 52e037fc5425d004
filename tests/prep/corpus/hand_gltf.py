# Shared by the corpus files written by hand (tests/prep/corpus/hand-*.py, run with python3, no
# Blender): a minimal glTF 2.0 binary writer for triangle meshes, so that the corpus holds
# files no exporter would write (no TEXCOORD_0, extreme light values).
import json
import struct
import sys


def output_path(script):
    if len(sys.argv) != 2:
        sys.stderr.write("usage: python3 %s OUT.glb\n" % script)
        sys.exit(2)
    return sys.argv[1]


def box_faces(low, high):
    """The six faces of an axis-aligned box, outward, as (corners, normal) quads."""
    (x0, y0, z0), (x1, y1, z1) = low, high
    return [
        ([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)], (0, 0, 1)),
        ([(x0, y1, z0), (x1, y1, z0), (x1, y0, z0), (x0, y0, z0)], (0, 0, -1)),
        ([(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)], (1, 0, 0)),
        ([(x0, y0, z1), (x0, y1, z1), (x0, y1, z0), (x0, y0, z0)], (-1, 0, 0)),
        ([(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)], (0, 1, 0)),
        ([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)], (0, -1, 0)),
    ]


class Document:
    def __init__(self):
        self.gltf = {"asset": {"version": "2.0", "generator": "luxel tests/prep/corpus"},
                     "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                     "materials": [], "accessors": [], "bufferViews": []}
        self.binary = bytearray()

    def _view(self, data, target):
        while len(self.binary) % 4:
            self.binary.append(0)
        self.gltf["bufferViews"].append({"buffer": 0, "byteOffset": len(self.binary),
                                         "byteLength": len(data), "target": target})
        self.binary += data
        return len(self.gltf["bufferViews"]) - 1

    def _vec3(self, values):
        data = b"".join(struct.pack("<3f", *v) for v in values)
        accessor = {"bufferView": self._view(data, 34962), "componentType": 5126,
                    "count": len(values), "type": "VEC3",
                    "min": [min(v[i] for v in values) for i in range(3)],
                    "max": [max(v[i] for v in values) for i in range(3)]}
        self.gltf["accessors"].append(accessor)
        return len(self.gltf["accessors"]) - 1

    def material(self, name, rgb):
        self.gltf["materials"].append({"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": [rgb[0], rgb[1], rgb[2], 1.0], "metallicFactor": 0.0,
            "roughnessFactor": 1.0}})
        return len(self.gltf["materials"]) - 1

    def quad_mesh(self, name, quads, material):
        """A node with a mesh of quads (corners counter-clockwise seen from the normal's side),
        with POSITION and NORMAL and no TEXCOORD_0."""
        positions, normals, indices = [], [], []
        for corners, normal in quads:
            base = len(positions)
            positions += corners
            normals += [normal] * 4
            indices += [base, base + 1, base + 2, base, base + 2, base + 3]
        index_data = b"".join(struct.pack("<H", i) for i in indices)
        self.gltf["accessors"].append({"bufferView": self._view(index_data, 34963),
                                       "componentType": 5123, "count": len(indices),
                                       "type": "SCALAR"})
        index_accessor = len(self.gltf["accessors"]) - 1
        attributes = {"POSITION": self._vec3(positions), "NORMAL": self._vec3(normals)}
        self.gltf["meshes"].append({"name": name, "primitives": [
            {"attributes": attributes, "indices": index_accessor, "material": material}]})
        self.node({"name": name, "mesh": len(self.gltf["meshes"]) - 1})

    def node(self, node):
        self.gltf["nodes"].append(node)
        self.gltf["scenes"][0]["nodes"].append(len(self.gltf["nodes"]) - 1)

    def point_light(self, name, position, colour, intensity):
        extension = self.gltf.setdefault("extensions", {}).setdefault(
            "KHR_lights_punctual", {"lights": []})
        extension["lights"].append({"name": name, "type": "point", "color": colour,
                                    "intensity": intensity})
        self.gltf.setdefault("extensionsUsed", ["KHR_lights_punctual"])
        self.node({"name": name, "translation": position, "extensions": {
            "KHR_lights_punctual": {"light": len(extension["lights"]) - 1}}})

    def write(self, path):
        while len(self.binary) % 4:
            self.binary.append(0)
        self.gltf["buffers"] = [{"byteLength": len(self.binary)}]
        text = json.dumps(self.gltf, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        total = 12 + 8 + len(text) + 8 + len(self.binary)
        with open(path, "wb") as out:
            out.write(struct.pack("<III", 0x46546C67, 2, total))
            out.write(struct.pack("<II", len(text), 0x4E4F534A) + text)
            out.write(struct.pack("<II", len(self.binary), 0x004E4942) + bytes(self.binary))
