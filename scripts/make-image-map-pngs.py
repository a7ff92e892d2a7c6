#!/usr/bin/env python3
"""Writes the small PNG images of scenes/parity/image_map.toml (the standard library only, so
the bytes do not depend on an imaging library's encoder). The images are this project's own,
CC0 (public domain dedication).

usage: scripts/make-image-map-pngs.py [OUTDIR]   (default scenes/parity)

image_map.png        32 x 16 RGB, 8 bits: a hue ramp across, light to dark down, a white grid
                     every 8 texels and a red corner mark at the top left (orientation)
image_map_alpha.png  16 x 16 RGBA, 8 bits: a blue-to-orange disc fading to clear at its rim
image_map_grey.png   16 x 8 grey, 8 bits: a ramp across with a dark bottom row

and for scenes/parity/image_map_png.toml, 8 x 8 texels each (a mixed pattern, see `texel`):

image_map_rgb16.png    RGB, 16 bits per sample
image_map_palette.png  an 8-colour palette with partial transparency (tRNS)
image_map_grey4.png    grey, 4 bits
image_map_gamma.png    RGB, 8 bits, with a gAMA chunk of 1/2.2 (a power law, not sRGB)
"""
import math
import os
import struct
import sys
import zlib


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def write_png(path, width, height, colour_type, rows, depth=8, extra=b""):
    """rows: a list of byte strings, one per row (samples packed as the depth says)."""
    raw = b"".join(b"\x00" + row for row in rows)
    header = struct.pack(">IIBBBBB", width, height, depth, colour_type, 0, 0, 0)
    data = (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + extra
        + chunk(b"IDAT", zlib.compress(raw, 9))
        + chunk(b"IEND", b"")
    )
    with open(path, "wb") as f:
        f.write(data)


def hue(h):
    """An RGB triple in [0, 1] for hue h in [0, 1)."""
    k = [(n + h * 6.0) % 6.0 for n in (5.0, 3.0, 1.0)]
    return [1.0 - max(0.0, min(k_, 4.0 - k_, 1.0)) for k_ in k]


def byte(v):
    return max(0, min(255, int(round(v * 255.0))))


def texel(x, y, c):
    """A deterministic 0..1 value for texel (x, y), channel c of an 8 x 8 image."""
    return ((x * 37 + y * 91 + c * 53 + x * y * 17) % 101) / 100.0


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes", "parity")
    rows = []
    for y in range(16):
        row = b""
        for x in range(32):
            r, g, b = hue(x / 32.0)
            shade = 1.0 - 0.6 * y / 15.0
            c = [0.15 + 0.85 * shade * v for v in (r, g, b)]
            if x % 8 == 0 or y % 8 == 0:
                c = [0.95, 0.95, 0.95]
            if x in (1, 2) and y in (1, 2):
                c = [0.9, 0.05, 0.05]
            row += bytes(byte(v) for v in c)
        rows.append(row)
    write_png(os.path.join(out, "image_map.png"), 32, 16, 2, rows)

    rows = []
    for y in range(16):
        row = b""
        for x in range(16):
            d = math.hypot(x - 7.5, y - 7.5) / 7.5
            t = min(1.0, d)
            c = [0.1 + 0.9 * t, 0.3 + 0.3 * t, 0.9 - 0.8 * t]
            alpha = 1.0 if d < 0.5 else max(0.0, 1.0 - (d - 0.5) / 0.5)
            row += bytes(byte(v) for v in c) + bytes([byte(alpha)])
        rows.append(row)
    write_png(os.path.join(out, "image_map_alpha.png"), 16, 16, 6, rows)

    rows = []
    for y in range(8):
        rows.append(bytes(byte(0.05 + 0.9 * x / 15.0) if y < 7 else 20 for x in range(16)))
    write_png(os.path.join(out, "image_map_grey.png"), 16, 8, 0, rows)

    rows = [b"".join(struct.pack(">H", int(texel(x, y, c) * 65535)) for x in range(8) for c in range(3)) for y in range(8)]
    write_png(os.path.join(out, "image_map_rgb16.png"), 8, 8, 2, rows, depth=16)

    palette = bytes(byte(texel(i, 3, c)) for i in range(8) for c in range(3))
    alphas = bytes([255, 128, 0, 200, 255, 64, 255, 255])
    rows = [bytes((x * 3 + y * 5 + (x * y) // 3) % 8 for x in range(8)) for y in range(8)]
    extra = chunk(b"PLTE", palette) + chunk(b"tRNS", alphas)
    write_png(os.path.join(out, "image_map_palette.png"), 8, 8, 3, rows, extra=extra)

    rows = []
    for y in range(8):
        levels = [int(texel(x, y, 0) * 15) for x in range(8)]
        rows.append(bytes((levels[i] << 4) | levels[i + 1] for i in range(0, 8, 2)))
    write_png(os.path.join(out, "image_map_grey4.png"), 8, 8, 0, rows, depth=4)

    rows = [bytes(byte(texel(x, y, c)) for x in range(8) for c in range(3)) for y in range(8)]
    extra = chunk(b"gAMA", struct.pack(">I", 45455))
    write_png(os.path.join(out, "image_map_gamma.png"), 8, 8, 2, rows, extra=extra)


if __name__ == "__main__":
    main()
