"""Class 1: URIs that lead out of the level's folder, and data: URIs that must keep working.

Each escape target outside the folder is a per-case copy under _outside/<case>/ holding exactly
the bytes the level needs, so a loader that follows the link does not fail on a size mismatch
but loads and renders data it should never have read: the runner's open() log shows it.
"""

import os

from . import case, kit

OUT = "_outside/%s/"


def _outside(c, rel, data):
    full = os.path.join(c.outside, c.name, rel)
    os.makedirs(os.path.dirname(full), exist_ok=True)
    with open(full, "wb") as f:
        f.write(data)
    return full


def _buffer_doc():
    doc, _ = kit.basic()
    return doc


def _textured_doc(uri):
    """The reference scene with a base-colour texture whose image is `uri`."""
    doc, ids = kit.basic()
    texture = doc.image_texture({"uri": uri})
    doc.j["materials"][ids["material"]]["pbrMetallicRoughness"]["baseColorTexture"] = {
        "index": texture}
    return doc


def buffer_via(c, uri):
    doc = _buffer_doc()
    c.gltf_with_bin(doc, uri)
    return doc


def image_via(c, uri):
    c.gltf(_textured_doc(uri))


# -- symbolic links ---------------------------------------------------------------------------

def _reg(name, description, forbidden, expect="any"):
    return case(name, "escape", description, expect=expect, forbidden=forbidden)


@_reg("esc-symlink-buffer-passwd", "buffer uri data.bin is a symlink to /etc/passwd",
      ["/etc/passwd"])
def _(c):
    c.symlink("/etc/passwd", "data.bin")
    buffer_via(c, "data.bin")


@_reg("esc-symlink-buffer-outside", "buffer uri data.bin is an absolute symlink to a file "
      "outside the folder holding the right bytes", [OUT % "esc-symlink-buffer-outside"])
def _(c):
    doc = buffer_via(c, "data.bin")
    c.symlink(_outside(c, "data.bin", bytes(doc.bin)), "data.bin")


@_reg("esc-symlink-buffer-relative", "buffer uri data.bin is a relative symlink ../_outside/...",
      [OUT % "esc-symlink-buffer-relative"])
def _(c):
    doc = buffer_via(c, "data.bin")
    _outside(c, "data.bin", bytes(doc.bin))
    c.symlink("../_outside/%s/data.bin" % c.name, "data.bin")


@_reg("esc-symlink-image-outside", "image uri tex.png is a symlink to a PNG outside the folder",
      [OUT % "esc-symlink-image-outside"])
def _(c):
    c.symlink(_outside(c, "tex.png", kit.SMALL_PNG), "tex.png")
    image_via(c, "tex.png")


@_reg("esc-symlink-image-passwd", "image uri tex.png is a symlink to /etc/passwd", ["/etc/passwd"])
def _(c):
    c.symlink("/etc/passwd", "tex.png")
    image_via(c, "tex.png")


@_reg("esc-symlink-dir-buffer", "buffer uri sub/data.bin where sub is a symlink to a directory "
      "outside", [OUT % "esc-symlink-dir-buffer"])
def _(c):
    doc = buffer_via(c, "sub/data.bin")
    _outside(c, "data.bin", bytes(doc.bin))
    c.symlink(os.path.join(c.outside, c.name), "sub")


@_reg("esc-symlink-dir-image", "image uri sub/tex.png where sub is a symlink to a directory "
      "outside", [OUT % "esc-symlink-dir-image"])
def _(c):
    _outside(c, "tex.png", kit.SMALL_PNG)
    c.symlink(os.path.join(c.outside, c.name), "sub")
    image_via(c, "sub/tex.png")


@_reg("esc-symlink-dir-parent", "buffer uri up/_outside/... where up is a symlink to '..'",
      [OUT % "esc-symlink-dir-parent"])
def _(c):
    doc = buffer_via(c, "up/_outside/%s/data.bin" % c.name)
    _outside(c, "data.bin", bytes(doc.bin))
    c.symlink("..", "up")


@_reg("esc-symlink-dir-root", "buffer uri root/etc/passwd where root is a symlink to '/'",
      ["/etc/passwd"])
def _(c):
    c.symlink("/", "root")
    buffer_via(c, "root/etc/passwd")


@_reg("esc-symlink-chain", "data.bin -> hop.bin (inside) -> a file outside",
      [OUT % "esc-symlink-chain"])
def _(c):
    doc = buffer_via(c, "data.bin")
    c.symlink(_outside(c, "data.bin", bytes(doc.bin)), "hop.bin")
    c.symlink("hop.bin", "data.bin")


@_reg("esc-symlink-dangling", "buffer uri is a symlink to a missing file outside", [])
def _(c):
    c.symlink(os.path.join(c.outside, c.name, "missing.bin"), "data.bin")
    buffer_via(c, "data.bin")


@_reg("esc-symlink-loop", "buffer uri is a symlink to itself (ELOOP)", [])
def _(c):
    c.symlink("data.bin", "data.bin")
    buffer_via(c, "data.bin")


@_reg("esc-symlink-inside", "buffer uri is a symlink to a file inside the folder (allowed)", [],
      expect="success")
def _(c):
    doc = buffer_via(c, "data.bin")
    c.write("real/data.bin", bytes(doc.bin))
    c.symlink("real/data.bin", "data.bin")


@_reg("esc-symlink-glb-image", "GLB whose image uri tex.png is a symlink to a PNG outside",
      [OUT % "esc-symlink-glb-image"])
def _(c):
    c.symlink(_outside(c, "tex.png", kit.SMALL_PNG), "tex.png")
    c.glb(_textured_doc("tex.png"))


# -- '..', absolute and other spellings --------------------------------------------------------

@_reg("esc-dotdot-buffer", "buffer uri ../_outside/<case>/data.bin",
      [OUT % "esc-dotdot-buffer"])
def _(c):
    doc = buffer_via(c, "../_outside/%s/data.bin" % c.name)
    _outside(c, "data.bin", bytes(doc.bin))


@_reg("esc-dotdot-image", "image uri ../_outside/<case>/tex.png", [OUT % "esc-dotdot-image"])
def _(c):
    _outside(c, "tex.png", kit.SMALL_PNG)
    image_via(c, "../_outside/%s/tex.png" % c.name)


@_reg("esc-dotdot-through-subdir", "buffer uri sub/../../_outside/... through a real subfolder",
      [OUT % "esc-dotdot-through-subdir"])
def _(c):
    doc = buffer_via(c, "sub/../../_outside/%s/data.bin" % c.name)
    _outside(c, "data.bin", bytes(doc.bin))
    os.makedirs(c.path("sub"), exist_ok=True)


@_reg("esc-dotdot-many", "buffer uri ../../../../../../../../../../etc/passwd", ["/etc/passwd"])
def _(c):
    buffer_via(c, "../" * 10 + "etc/passwd")


@_reg("esc-dotdot-inside", "buffer uri sub/../<case>.bin stays inside (allowed)", [],
      expect="success")
def _(c):
    doc = buffer_via(c, "sub/../%s.bin" % c.name)
    c.write(c.name + ".bin", bytes(doc.bin))
    os.makedirs(c.path("sub"), exist_ok=True)


@_reg("esc-absolute-buffer", "buffer uri is the absolute path of a file outside",
      [OUT % "esc-absolute-buffer"])
def _(c):
    doc = _buffer_doc()
    c.gltf_with_bin(doc, _outside(c, "data.bin", bytes(doc.bin)))


@_reg("esc-absolute-passwd", "buffer uri /etc/passwd", ["/etc/passwd"])
def _(c):
    buffer_via(c, "/etc/passwd")


@_reg("esc-absolute-image", "image uri is the absolute path of a PNG outside",
      [OUT % "esc-absolute-image"])
def _(c):
    image_via(c, _outside(c, "tex.png", kit.SMALL_PNG))


@_reg("esc-absolute-proc-environ", "buffer uri /proc/self/environ", ["/proc/self/environ"])
def _(c):
    buffer_via(c, "/proc/self/environ")


@_reg("esc-file-uri-passwd", "buffer uri file:///etc/passwd", ["/etc/passwd"])
def _(c):
    buffer_via(c, "file:///etc/passwd")


@_reg("esc-file-uri-outside", "buffer uri file://<absolute path outside>",
      [OUT % "esc-file-uri-outside"])
def _(c):
    doc = _buffer_doc()
    c.gltf_with_bin(doc, "file://" + _outside(c, "data.bin", bytes(doc.bin)))


@_reg("esc-percent-slash", "buffer uri ..%2F_outside%2F<case>%2Fdata.bin (encoded '/')",
      [OUT % "esc-percent-slash"])
def _(c):
    doc = buffer_via(c, "..%%2F_outside%%2F%s%%2Fdata.bin" % c.name)
    _outside(c, "data.bin", bytes(doc.bin))


@_reg("esc-percent-slash-lower", "buffer uri ..%2f_outside%2f... (lower-case escape)",
      [OUT % "esc-percent-slash-lower"])
def _(c):
    doc = buffer_via(c, "..%%2f_outside%%2f%s%%2fdata.bin" % c.name)
    _outside(c, "data.bin", bytes(doc.bin))


@_reg("esc-percent-dots", "buffer uri %2E%2E/_outside/<case>/data.bin (encoded dots)",
      [OUT % "esc-percent-dots"])
def _(c):
    doc = buffer_via(c, "%%2E%%2E/_outside/%s/data.bin" % c.name)
    _outside(c, "data.bin", bytes(doc.bin))


@_reg("esc-percent-absolute", "buffer uri %2Fetc%2Fpasswd", ["/etc/passwd"])
def _(c):
    buffer_via(c, "%2Fetc%2Fpasswd")


@_reg("esc-percent-double", "buffer uri ..%252F... (encoded twice: one decode leaves %2F)",
      [OUT % "esc-percent-double"])
def _(c):
    doc = buffer_via(c, "..%%252F_outside%%252F%s%%252Fdata.bin" % c.name)
    _outside(c, "data.bin", bytes(doc.bin))


@_reg("esc-percent-image", "image uri ..%2F_outside%2F<case>%2Ftex.png",
      [OUT % "esc-percent-image"])
def _(c):
    _outside(c, "tex.png", kit.SMALL_PNG)
    image_via(c, "..%%2F_outside%%2F%s%%2Ftex.png" % c.name)


@_reg("esc-backslash", "buffer uri ..\\_outside\\<case>\\data.bin (Windows separators)",
      [OUT % "esc-backslash"])
def _(c):
    doc = buffer_via(c, "..\\_outside\\%s\\data.bin" % c.name)
    _outside(c, "data.bin", bytes(doc.bin))


@_reg("esc-nul-in-uri", "buffer uri data.bin\\u0000/../../../etc/passwd (embedded NUL)",
      ["/etc/passwd"])
def _(c):
    doc = buffer_via(c, "data.bin\u0000/../../../etc/passwd")
    c.write("data.bin", bytes(doc.bin))


@_reg("esc-tilde", "buffer uri ~/.profile (no shell expansion may happen)", ["~/.profile"])
def _(c):
    buffer_via(c, "~/.profile")


@_reg("esc-shell-expansion", "buffer uri $HOME/.profile and $(...) (wordexp must not run)",
      ["~/.profile"])
def _(c):
    buffer_via(c, "$HOME/.profile")


@_reg("esc-command-substitution", "image uri `$(touch pwned)`.png (wordexp must not run)", [])
def _(c):
    image_via(c, "$(touch pwned).png")


@_reg("esc-query-string", "buffer uri data.bin?../../etc/passwd", ["/etc/passwd"])
def _(c):
    doc = buffer_via(c, "data.bin?../../../etc/passwd")
    c.write("data.bin", bytes(doc.bin))


@_reg("esc-http-uri", "buffer uri http://127.0.0.1/data.bin (no network, no file)", [])
def _(c):
    buffer_via(c, "http://127.0.0.1/data.bin")


@_reg("esc-uri-directory", "buffer uri names a directory inside the folder", [])
def _(c):
    os.makedirs(c.path("sub"), exist_ok=True)
    buffer_via(c, "sub")


@_reg("esc-uri-empty", "buffer uri is the empty string", [])
def _(c):
    buffer_via(c, "")


@_reg("esc-uri-level-itself", "buffer uri is the level file itself (inside; wrong size)", [])
def _(c):
    buffer_via(c, c.name + ".gltf")


# -- data: URIs -----------------------------------------------------------------------------

@_reg("esc-data-uri-buffer", "embedded base64 buffer (valid)", [], expect="success")
def _(c):
    c.gltf(_buffer_doc())


@_reg("esc-data-uri-png", "base-colour texture from a PNG data: URI (valid)", [],
      expect="success")
def _(c):
    image_via(c, kit.data_uri("image/png", kit.SMALL_PNG))


@_reg("esc-data-uri-jpeg", "base-colour texture from a JPEG data: URI (valid)", [],
      expect="success")
def _(c):
    image_via(c, kit.data_uri("image/jpeg", kit.jpeg()))


@_reg("esc-data-uri-bad-base64", "buffer data: URI with characters outside base64", [])
def _(c):
    buffer_via(c, "data:application/octet-stream;base64,!!!!@@@@****")


@_reg("esc-data-uri-short", "buffer data: URI decoding to fewer bytes than byteLength", [])
def _(c):
    buffer_via(c, "data:application/octet-stream;base64,AAAA")


@_reg("esc-data-uri-text-mime", "buffer data: URI of mime type text/plain", [])
def _(c):
    doc = _buffer_doc()
    c.gltf_with_bin(doc, kit.data_uri("text/plain", bytes(doc.bin)))


@_reg("esc-data-uri-not-base64", "buffer data: URI without ;base64", [])
def _(c):
    buffer_via(c, "data:application/octet-stream,AAAAAAAA")


@_reg("esc-data-uri-image-passwd-name", "image data: URI whose payload is not an image", [])
def _(c):
    image_via(c, kit.data_uri("image/png", b"root:x:0:0:root:/root:/bin/sh\n" * 4))
