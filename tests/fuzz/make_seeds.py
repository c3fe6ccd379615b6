#!/usr/bin/env python3
"""Writes the image and mesh fuzzers' seeds into a directory (run_fuzz.sh makes them at
every run, so no binary seed is kept in the repository):

    make_seeds.py image|mesh DIR

Each seed is one small valid file of a format the reader takes, preceded by the byte
that makes the fuzzer name it with that format's extension (fuzz_image.cpp,
fuzz_mesh.cpp).  Only the standard library: the formats are simple enough to write here.
"""

import struct
import sys
import zlib
from pathlib import Path

IMAGE = [".png", ".exr", ".hdr", ".pfm", ".tif", ".jpg", ".bmp", ".tga", ".ppm"]  # fuzz_image.cpp's order
MESH = [".obj", ".ply", ".off", ".stl"]  # fuzz_mesh.cpp's order

W, H = 4, 3
RGB8 = bytes((17 * x + 40 * y + 90 * c) % 256 for y in range(H) for x in range(W) for c in range(3))
RGBF = [((x + 1) * 0.25, (y + 1) * 0.3, (x + y) * 0.1) for y in range(H) for x in range(W)]


def png(depth=8, colour=2, rows=None):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
    if rows is None:
        rows = b"".join(b"\0" + bytes((x * 50 + y * 30 + c * 20) % 256 for x in range(W) for c in range(
            channels * depth // 8)) for y in range(H))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, depth, colour, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def pfm(values):
    body = b"".join(struct.pack("<3f", *values[y * W + x]) for y in reversed(range(H)) for x in range(W))
    return b"PF\n%d %d\n-1.0\n" % (W, H) + body


def ppm():
    return b"P6\n%d %d\n255\n" % (W, H) + RGB8


def bmp():
    row = lambda y: b"".join(bytes(reversed(RGB8[(y * W + x) * 3:(y * W + x) * 3 + 3])) for x in range(W))
    pad = b"\0" * ((4 - W * 3 % 4) % 4)
    pixels = b"".join(row(y) + pad for y in reversed(range(H)))
    info = struct.pack("<IiiHHIIiiII", 40, W, H, 1, 24, 0, len(pixels), 2835, 2835, 0, 0)
    return b"BM" + struct.pack("<IHHI", 14 + len(info) + len(pixels), 0, 0, 14 + len(info)) + info + pixels


def tga():
    header = struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, W, H, 24, 0)
    pixels = b"".join(bytes(reversed(RGB8[(y * W + x) * 3:(y * W + x) * 3 + 3])) for y in reversed(range(H))
                      for x in range(W))
    return header + pixels


def hdr():
    def rgbe(r, g, b):
        m = max(r, g, b)
        if m < 1e-32:
            return b"\0\0\0\0"
        import math
        e = math.frexp(m)[1]
        s = 256.0 / 2 ** e
        return bytes((int(r * s), int(g * s), int(b * s), e + 128))
    pixels = b"".join(rgbe(*RGBF[y * W + x]) for y in range(H) for x in range(W))
    return b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (H, W) + pixels


def exr():
    """An uncompressed scanline OpenEXR file of three float channels."""
    def attr(name, kind, data):
        return name + b"\0" + kind + b"\0" + struct.pack("<i", len(data)) + data
    channels = b"".join(c + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    box = struct.pack("<iiii", 0, 0, W - 1, H - 1)
    header = (attr(b"channels", b"chlist", channels) + attr(b"compression", b"compression", b"\0")
              + attr(b"dataWindow", b"box2i", box) + attr(b"displayWindow", b"box2i", box)
              + attr(b"lineOrder", b"lineOrder", b"\0") + attr(b"pixelAspectRatio", b"float", struct.pack("<f", 1))
              + attr(b"screenWindowCenter", b"v2f", struct.pack("<ff", 0, 0))
              + attr(b"screenWindowWidth", b"float", struct.pack("<f", 1)) + b"\0")
    start = 8 + len(header) + 8 * H
    lines, offsets = [], []
    for y in range(H):
        data = b"".join(struct.pack("<f", RGBF[y * W + x][c]) for c in (2, 1, 0) for x in range(W))
        offsets.append(start + sum(len(l) for l in lines))
        lines.append(struct.pack("<ii", y, len(data)) + data)
    return b"\x76\x2f\x31\x01" + struct.pack("<I", 2) + header + b"".join(struct.pack("<Q", o) for o in offsets) \
        + b"".join(lines)


def tiff():
    """A baseline little-endian TIFF, 8-bit RGB, one uncompressed strip."""
    entries = [(256, 3, 1, W), (257, 3, 1, H), (258, 3, 3, None), (259, 3, 1, 1), (262, 3, 1, 2),
               (273, 4, 1, None), (277, 3, 1, 3), (278, 3, 1, H), (279, 4, 1, len(RGB8))]
    ifd_size = 2 + 12 * len(entries) + 4
    bits_at = 8 + ifd_size
    pixels_at = bits_at + 6
    out = b"II*\0" + struct.pack("<I", 8) + struct.pack("<H", len(entries))
    for tag, kind, count, value in entries:
        if tag == 258:
            value = bits_at
        elif tag == 273:
            value = pixels_at
        field = struct.pack("<HHI", tag, kind, count)
        field += struct.pack("<HH", value, 0) if kind == 3 and count == 1 else struct.pack("<I", value)
        out += field
    return out + struct.pack("<I", 0) + struct.pack("<3H", 8, 8, 8) + RGB8


OBJ = b"""# a square pyramid with texture coordinates and normals
v 0 0 0
v 1 0 0
v 1 0 1
v 0 0 1
v 0.5 1.25 0.5
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 -1 0
f 1/1/1 2/2/1 3/3/1 4/4/1
f 2/1 1/2 5/3
f 3//1 2//1 5//1
f -2 -3 -1
f 1 4 5
"""

PLY = b"""ply
format ascii 1.0
comment a square pyramid
element vertex 5
property float x
property float y
property float z
element face 5
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
1 0 1
0 0 1
0.5 1.25 0.5
4 0 1 2 3
3 1 0 4
3 2 1 4
3 3 2 4
3 0 3 4
"""

PYRAMID = [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1), (0.5, 1.25, 0.5)]
FACES = [(0, 1, 2), (0, 2, 3), (1, 0, 4), (2, 1, 4), (3, 2, 4), (0, 3, 4)]


def ply_binary():
    header = (b"ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
              b"property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n")
    return header + b"".join(struct.pack("<3f", *p) for p in PYRAMID) + b"".join(
        struct.pack("<B3i", 3, *f) for f in FACES)


def off():
    return b"OFF\n5 6 0\n" + b"".join(b"%g %g %g\n" % p for p in PYRAMID) + b"".join(
        b"3 %d %d %d\n" % f for f in FACES)


def stl_text():
    out = b"solid pyramid\n"
    for f in FACES:
        out += b"facet normal 0 0 0\nouter loop\n" + b"".join(b"vertex %g %g %g\n" % PYRAMID[i] for i in f)
        out += b"endloop\nendfacet\n"
    return out + b"endsolid pyramid\n"


def stl_binary():
    return b"\0" * 80 + struct.pack("<I", len(FACES)) + b"".join(
        struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *PYRAMID[i]) for i in f) + b"\0\0" for f in FACES)


def seeds(kind):
    if kind == "image":
        nan = list(RGBF)
        nan[5] = (float("nan"), 0.5, 0.5)
        files = {".png": [png(), png(depth=16), png(colour=4), png(colour=0)], ".exr": [exr()], ".hdr": [hdr()],
                 ".pfm": [pfm(RGBF), pfm(nan)], ".tif": [tiff()], ".bmp": [bmp()], ".tga": [tga()], ".ppm": [ppm()]}
        order = IMAGE
    else:
        files = {".obj": [OBJ], ".ply": [PLY, ply_binary()], ".off": [off()], ".stl": [stl_text(), stl_binary()]}
        order = MESH
    for ext, contents in files.items():
        for i, data in enumerate(contents):
            yield "%s%d%s" % (kind, i, ext), bytes([order.index(ext)]) + data


def main():
    kind, directory = sys.argv[1], Path(sys.argv[2])
    directory.mkdir(parents=True, exist_ok=True)
    for name, data in seeds(kind):
        (directory / name).write_bytes(data)


if __name__ == "__main__":
    main()
