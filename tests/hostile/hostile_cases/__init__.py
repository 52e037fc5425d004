"""The hostile-input corpus: every case is a function that writes one level (and whatever it
names) into its own folder, registered with the class it belongs to and what is expected.

A case's folder is the "level's folder": a tool may open files there and nowhere else outside
its own installation. Files a case deliberately points at outside its folder live in the
corpus's shared `_outside/` folder (or are system files such as /etc/passwd) and are listed in
the case's `forbidden` entry, so the runner can say exactly which escape happened.
"""

import json
import os

from . import kit

TOOLS = ("prep", "sandbox", "ref")

# The classes of issue 25, in report order.
CLASSES = {
    "escape": "1. escape from the level's folder (symlinks, '..', absolute and encoded URIs)",
    "nonfinite-camera": "2. non-finite rays and cameras (scales, projections, animation keys)",
    "alloc": "3. unbounded allocation from small files",
    "radiometry": "4. non-finite radiometry (light power, emissive strength)",
    "types": "5. wrong JSON types and truncated images",
    "quadratic": "6. quadratic loading",
    "regression": "7. classes already handled (regression)",
    "control": "valid files that must load and render",
}

REGISTRY = []


class Case:
    """What a case function gets: its folder and helpers that write the level into it."""

    def __init__(self, name, root):
        self.name = name
        self.root = root
        self.dir = os.path.join(root, name)
        self.outside = os.path.join(root, "_outside")
        self.main = None

    def path(self, rel):
        return os.path.join(self.dir, rel)

    def write(self, rel, data):
        full = self.path(rel)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "wb") as f:
            f.write(data if isinstance(data, (bytes, bytearray)) else data.encode())
        return rel

    def symlink(self, target, rel):
        full = self.path(rel)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        os.symlink(target, full)
        return rel

    # The level file itself is named after the case, so an error message that names it is
    # recognisable and cannot be confused with another case's file.
    def level_bytes(self, data, ext):
        self.main = self.write(self.name + ext, data)
        return self.main

    def gltf(self, doc_or_text):
        if isinstance(doc_or_text, kit.Doc):
            data = doc_or_text.gltf_embedded()
        elif isinstance(doc_or_text, (bytes, bytearray, str)):
            data = doc_or_text
        else:
            data = kit.dumps(doc_or_text)
        return self.level_bytes(data, ".gltf")

    def gltf_with_bin(self, doc, bin_name=None):
        """The doc as .gltf with its buffer in a file beside it (or wherever bin_name says)."""
        if bin_name is None:
            bin_name = self.name + ".bin"
            self.write(bin_name, bytes(doc.bin))
        return self.level_bytes(doc.gltf_external(bin_name), ".gltf")

    def glb(self, doc_or_bytes):
        data = doc_or_bytes.glb() if isinstance(doc_or_bytes, kit.Doc) else doc_or_bytes
        return self.level_bytes(data, ".glb")


def case(name, cls, description, tools=TOOLS, expect="any", forbidden=(), args=None,
         big=False):
    """Registers a case. expect: "success" (must exit 0), "error" (must exit 1) or "any".
    forbidden: paths outside the folder that this case points at (opened = escape; relative
    ones are taken inside the corpus). args: extra arguments per tool."""
    assert cls in CLASSES, cls

    def register(fn):
        REGISTRY.append({"name": name, "class": cls, "description": description,
                         "tools": list(tools), "expect": expect, "forbidden": list(forbidden),
                         "args": dict(args or {}), "big": big, "fn": fn})
        return fn

    return register


def load_all():
    # Imported for their registrations; the order fixes the manifest's order.
    from . import cases_escape, cases_numeric, cases_alloc, cases_types, cases_regression  # noqa
    from . import cases_skins  # noqa


def write_outside(root):
    """The files cases point at from outside their folders."""
    out = os.path.join(root, "_outside")
    os.makedirs(os.path.join(out, "dir"), exist_ok=True)
    secret = b"LUXEL-HOSTILE-SECRET" * 64  # 1280 bytes: enough for any small buffer
    for rel, data in (("secret.bin", secret), ("dir/secret.bin", secret),
                      ("secret.png", kit.SMALL_PNG), ("dir/secret.png", kit.SMALL_PNG)):
        with open(os.path.join(out, rel), "wb") as f:
            f.write(data)


def manifest_entry(entry, case_obj):
    item = {k: v for k, v in entry.items() if k != "fn"}
    item["file"] = os.path.join(entry["name"], case_obj.main)
    return item


def save_manifest(root, items):
    with open(os.path.join(root, "manifest.json"), "w") as f:
        json.dump({"version": 1, "classes": CLASSES, "cases": items}, f, indent=1,
                  sort_keys=True)
        f.write("\n")
