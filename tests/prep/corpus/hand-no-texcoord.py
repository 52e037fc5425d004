# luxel-prep corpus, written by hand (python3, no Blender): a room of 5 x 4 x 2.5 m (walls
# facing in) with two boxes, every primitive with POSITION and NORMAL but no TEXCOORD_0, and
# a point light. luxel-prep must write TEXCOORD_1 without TEXCOORD_0 and still pass the
# validator (issue 22: MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY).
#   python3 hand-no-texcoord.py OUT.glb
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hand_gltf  # noqa: E402

out = hand_gltf.output_path("hand-no-texcoord.py")
doc = hand_gltf.Document()
plaster = doc.material("plaster", (0.7, 0.7, 0.7))
wood = doc.material("wood", (0.55, 0.4, 0.22))
# The room is a box seen from inside: each face with its corners reversed and normal flipped.
room = [(list(reversed(corners)), tuple(-n for n in normal))
        for corners, normal in hand_gltf.box_faces((-2.5, 0.0, -2.0), (2.5, 2.5, 2.0))]
doc.quad_mesh("Room", room, plaster)
doc.quad_mesh("Box", hand_gltf.box_faces((-1.5, 0.0, -1.0), (-0.5, 0.8, 0.0)), wood)
doc.quad_mesh("Tall box", hand_gltf.box_faces((0.6, 0.0, -0.4), (1.2, 1.6, 0.2)), wood)
doc.point_light("Lamp", [0.0, 2.3, 0.0], [1.0, 0.9, 0.8], 40.0)
doc.write(out)
