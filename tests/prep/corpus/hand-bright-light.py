# luxel-prep corpus, written by hand (python3, no Blender): one box under a point light whose
# intensity is the largest float (3.4e38 cd): finite on its own, but beyond what luxel loads,
# and far beyond what colour times intensity can hold as a float (issue 22: luxel-prep once
# wrote such a light as "intensity": null).
#   python3 hand-bright-light.py OUT.glb
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hand_gltf  # noqa: E402

out = hand_gltf.output_path("hand-bright-light.py")
doc = hand_gltf.Document()
wood = doc.material("wood", (0.55, 0.4, 0.22))
doc.quad_mesh("Box", hand_gltf.box_faces((-0.5, 0.0, -0.5), (0.5, 1.0, 0.5)), wood)
doc.point_light("Blinding lamp", [0.0, 2.0, 0.0], [1.0, 1.0, 1.0], 3.4028234663852886e38)
doc.write(out)
