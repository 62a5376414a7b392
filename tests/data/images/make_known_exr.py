#!/usr/bin/env python3
"""Writes known-float.exr, known-half.exr and known-half-typed.exr: 3x2 OpenEXR images with known
linear values, made without OpenEXR or tinyexr, straight from the file layout
in the OpenEXR specification ("OpenEXR File Layout", openexr.com): magic and
version, the required header attributes, a line offset table and one
uncompressed scanline block per row, channels in alphabetical order (B, G, R),
little-endian. ImageLoaderTest reads them through OpenEXR, so the EXR reader
is checked against a writer that is not our own. Run from this directory:
    python3 make_known_exr.py
known-half-typed.exr is known-half.exr with the optional "type" attribute
("scanlineimage"), which ImageLoaderTest edits to check that a contradictory
or unknown type is one error.
The files were checked with `exrheader` (Debian package openexr 3.1.5).
"""
import struct

# Rows top to bottom, (R, G, B) per pixel. Each value is exact in float16 too.
PIXELS = [
    [(1.0, 0.5, 0.25), (2.0, 0.0, 0.125), (0.0, 0.0, 0.0)],
    [(4.0, 8.0, 16.0), (0.75, 0.375, 1.5), (1024.0, 0.0625, 3.0)],
]
WIDTH, HEIGHT = 3, 2


def attribute(name, type_name, value):
    return name.encode() + b"\0" + type_name.encode() + b"\0" + struct.pack("<i", len(value)) + value


def write(path, pixel_type, extra=b""):  # pixel_type: 1 = HALF, 2 = FLOAT; extra: more attributes
    channels = b""
    for name in ("B", "G", "R"):
        channels += name.encode() + b"\0" + struct.pack("<iB3xii", pixel_type, 0, 1, 1)
    channels += b"\0"
    header = b"\x76\x2f\x31\x01" + struct.pack("<i", 2)
    header += attribute("channels", "chlist", channels)
    header += attribute("compression", "compression", b"\0")  # NO_COMPRESSION
    header += attribute("dataWindow", "box2i", struct.pack("<iiii", 0, 0, WIDTH - 1, HEIGHT - 1))
    header += attribute("displayWindow", "box2i", struct.pack("<iiii", 0, 0, WIDTH - 1, HEIGHT - 1))
    header += attribute("lineOrder", "lineOrder", b"\0")  # INCREASING_Y
    header += attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
    header += attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
    header += attribute("screenWindowWidth", "float", struct.pack("<f", 1.0))
    header += extra
    header += b"\0"

    value_format = "<e" if pixel_type == 1 else "<f"
    blocks = []
    for y, row in enumerate(PIXELS):
        data = b""
        for channel in (2, 1, 0):  # B, G, R
            for pixel in row:
                data += struct.pack(value_format, pixel[channel])
        blocks.append(struct.pack("<ii", y, len(data)) + data)

    offset = len(header) + 8 * HEIGHT
    table = b""
    for block in blocks:
        table += struct.pack("<Q", offset)
        offset += len(block)
    with open(path, "wb") as f:
        f.write(header + table + b"".join(blocks))


write("known-float.exr", 2)
write("known-half.exr", 1)
write("known-half-typed.exr", 1, attribute("type", "string", b"scanlineimage"))
