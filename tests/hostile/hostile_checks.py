"""What run_hostile.py checks in a tool's output and its open() log: non-finite values in
OpenEXR frames, in a written GLB's float accessors and in JSON (luxel's JSON writer turns NaN
and infinity into null), and the files a traced process opened.

Standard library only, so the test needs nothing beyond the interpreter.
"""

import json
import math
import os
import re
import struct
import zlib

# -- OpenEXR ---------------------------------------------------------------------------------

_LINES_PER_BLOCK = {0: 1, 1: 1, 2: 1, 3: 16}  # NONE, RLE, ZIPS, ZIP


def _exr_attributes(data):
    if data[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("not an OpenEXR file")
    at = 8
    attrs = {}
    while data[at] != 0:
        name_end = data.index(b"\0", at)
        type_end = data.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", data, type_end + 1)[0]
        value_at = type_end + 5
        attrs[data[at:name_end].decode()] = (data[name_end + 1:type_end].decode(),
                                             data[value_at:value_at + size])
        at = value_at + size
    return attrs, at + 1


def _channels(raw):
    out = []
    at = 0
    while raw[at] != 0:
        end = raw.index(b"\0", at)
        pixel_type = struct.unpack_from("<i", raw, end + 1)[0]
        out.append((raw[at:end].decode(), pixel_type))
        at = end + 17  # pixel type, pLinear + 3 reserved, x and y sampling
    return out


def _unzip(block):
    t = bytearray(zlib.decompress(block))
    for i in range(1, len(t)):  # undo the predictor
        t[i] = (t[i - 1] + t[i] - 128) & 0xFF
    half = (len(t) + 1) // 2
    out = bytearray(len(t))
    out[0::2] = t[:half]  # undo the interleaving of even and odd bytes
    out[1::2] = t[half:]
    return bytes(out)


def _unrle(block):
    out = bytearray()
    at = 0
    while at < len(block):
        n = struct.unpack_from("<b", block, at)[0]
        if n < 0:
            out += block[at + 1:at - n + 1]
            at += 1 - n
        else:
            out += block[at + 1:at + 2] * (n + 1)
            at += 2
    t = out
    for i in range(1, len(t)):
        t[i] = (t[i - 1] + t[i] - 128) & 0xFF
    half = (len(t) + 1) // 2
    res = bytearray(len(t))
    res[0::2] = t[:half]
    res[1::2] = t[half:]
    return bytes(res)


def scan_exr(path):
    """{'pixels', 'nonfinite', 'black', 'checked'}; checked is False (with 'why') for a
    compression this reader does not know (PIZ, PXR24, B44, DWA)."""
    with open(path, "rb") as f:
        data = f.read()
    attrs, at = _exr_attributes(data)
    compression = attrs["compression"][1][0]
    if compression not in _LINES_PER_BLOCK:
        return {"checked": False, "why": "compression %d not read" % compression}
    x0, y0, x1, y1 = struct.unpack("<iiii", attrs["dataWindow"][1])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    channels = _channels(attrs["channels"][1])
    lines = _LINES_PER_BLOCK[compression]
    blocks = (height + lines - 1) // lines
    offsets = struct.unpack_from("<%dQ" % blocks, data, at)
    nonfinite = 0
    nonzero = 0
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        block = data[offset + 8:offset + 8 + size]
        rows = min(lines, y1 - y + 1)
        expected = rows * width * sum(2 if t == 1 else 4 for _, t in channels)
        if size < expected:
            block = _unzip(block) if compression in (2, 3) else _unrle(block)
        at_px = 0
        for _ in range(rows):
            for name, pixel_type in channels:
                fmt, step = ("e", 2) if pixel_type == 1 else ("f", 4) if pixel_type == 2 else (
                    "I", 4)
                values = struct.unpack_from("<%d%s" % (width, fmt), block, at_px)
                at_px += width * step
                if pixel_type == 0:
                    continue
                nonfinite += sum(1 for v in values if not math.isfinite(v))
                if name in ("R", "G", "B"):
                    nonzero += sum(1 for v in values if v != 0.0)
    return {"checked": True, "pixels": width * height, "nonfinite": nonfinite,
            "black": nonzero == 0}


# -- GLB and JSON ------------------------------------------------------------------------------

def json_nulls(value, path="$", found=None, limit=5):
    """Paths of null values (NaN or infinity as luxel's JSON writer spells them)."""
    found = [] if found is None else found
    if len(found) >= limit:
        return found
    if value is None:
        found.append(path)
    elif isinstance(value, dict):
        for k, v in value.items():
            json_nulls(v, "%s.%s" % (path, k), found, limit)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            json_nulls(v, "%s[%d]" % (path, i), found, limit)
    elif isinstance(value, float) and not math.isfinite(value):
        found.append(path)
    return found


def scan_glb(path):
    """Non-finite floats in the GLB's JSON and in its FLOAT accessors."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"glTF":
        return {"checked": False, "why": "not a GLB"}
    json_len = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + json_len])
    bin_at = 20 + json_len + 8
    problems = ["JSON %s is null" % p for p in json_nulls(doc)]
    sizes = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
    for i, acc in enumerate(doc.get("accessors", [])):
        if acc.get("componentType") != 5126 or "bufferView" not in acc:
            continue
        view = doc["bufferViews"][acc["bufferView"]]
        n = sizes.get(acc.get("type"), 1)
        stride = view.get("byteStride", 4 * n)
        start = bin_at + view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        bad = 0
        for e in range(acc["count"]):
            values = struct.unpack_from("<%df" % n, data, start + e * stride)
            bad += sum(1 for v in values if not math.isfinite(v))
        if bad:
            problems.append("accessor %d: %d non-finite floats" % (i, bad))
    return {"checked": True, "problems": problems}


def scan_json_file(path):
    with open(path) as f:
        return ["%s is null or non-finite" % p for p in json_nulls(json.load(f))]


# -- the open() log ------------------------------------------------------------------------------

_CALL = re.compile(r"^(\d+)\s+(open|openat|openat2|creat|execve)\((.*)$")
_RESUMED = re.compile(r"^(\d+)\s+<\.\.\. (open|openat|openat2|creat|execve) resumed>(.*)$")
_STRING = re.compile(r'"((?:[^"\\]|\\.)*)"')
_RESULT = re.compile(r"=\s+(-?\d+)(?:<(.*)>)?")
_ESCAPES = re.compile(r"\\(x[0-9a-fA-F]{2}|[0-7]{1,3}|.)")


def _unescape(text):
    """strace's C-style escapes (octal or hex bytes) back into the path, read as UTF-8."""
    out = bytearray()
    pos = 0
    for m in _ESCAPES.finditer(text):
        out += text[pos:m.start()].encode("utf-8", "surrogateescape")
        e = m.group(1)
        if e[0] == "x":
            out.append(int(e[1:], 16))
        elif e[0].isdigit():
            out.append(int(e, 8) & 0xFF)
        else:
            out += {"n": "\n", "t": "\t", "r": "\r", "v": "\v", "f": "\f"}.get(e, e).encode()
        pos = m.end()
    out += text[pos:].encode("utf-8", "surrogateescape")
    return out.decode("utf-8", "surrogateescape")


def _dirfd_path(args):
    # With -y a directory fd prints as 3</some/dir>, the working directory as AT_FDCWD</dir>.
    m = re.match(r"\s*(?:\d+|AT_FDCWD)<(.*?)>,", args)
    return _unescape(m.group(1)) if m else None


def parse_strace(log_path, cwd):
    """[(call, requested path, opened real path or None, ok)] from `strace -f -y -o`."""
    events = []
    pending = {}
    if not os.path.exists(log_path):
        return events
    with open(log_path, errors="replace") as f:
        for line in f:
            line = line.rstrip("\n")
            m = _CALL.match(line)
            if m:
                pid, call, rest = m.groups()
                s = _STRING.search(rest)
                if not s:
                    continue
                requested = _unescape(s.group(1))
                base = _dirfd_path(rest) if call in ("openat", "openat2") else None
                if not os.path.isabs(requested):
                    requested = os.path.join(base or cwd, requested)
                if "<unfinished ...>" in rest:
                    pending[pid] = (call, requested)
                    continue
                events.append(_event(call, requested, rest[s.end():]))
                continue
            m = _RESUMED.match(line)
            if m and m.group(1) in pending:
                call, requested = pending.pop(m.group(1))
                events.append(_event(call, requested, m.group(3)))
    # A call still unfinished when the process died was blocked in it (a FIFO, a device):
    # the open was attempted and got as far as the kernel.
    for call, requested in pending.values():
        events.append((call, requested, None, True))
    return events


def _event(call, requested, tail):
    r = _RESULT.search(tail)
    if not r:
        return (call, requested, None, False)
    ok = int(r.group(1)) >= 0
    real = _unescape(r.group(2)) if ok and r.group(2) else None
    return (call, requested, real, ok)


def inside(path, folder):
    folder = folder.rstrip("/")
    return path == folder or path.startswith(folder + "/")
