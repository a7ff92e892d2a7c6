#!/usr/bin/env python3
"""Builds fuzz/seeds/<target>/ from the repository's scenes and assets and from the small
files of ../shared/assets (licences copied into fuzz/seeds/LICENSES/). Run from the
repository root; the output is committed, so CI does not need ../shared for fuzzing.

scene: every scenes/**/*.toml, with mesh, texture and include paths rewritten to the files
       the in-memory file system of fuzz/src/lib.rs holds.
obj:   OBJ files joined to their first MTL library by the separator of fuzz/src/lib.rs.
gltf:  small glTF/GLB files, external buffers and images inlined as data: URIs.
ply:   small PLY files in every encoding (ASCII, binary LE/BE, gzip).
image: a selector byte (index into IMAGE_EXTENSIONS) then a small image of each format.
"""
import base64, json, os, re, shutil, struct, subprocess, sys, zlib
from pathlib import Path

ROOT = Path.cwd()
SHARED = ROOT.parent / "shared" / "assets"
OUT = ROOT / "fuzz" / "seeds"
SEP = b"\n#--- m.mtl ---\n"
EXTS = ["png", "jpg", "hdr", "exr", "bmp", "tga", "tif", "pnm", "qoi"]


def put(target, name, data):
    d = OUT / target
    d.mkdir(parents=True, exist_ok=True)
    (d / name).write_bytes(data)


def scenes():
    for p in sorted((ROOT / "scenes").rglob("*.toml")):
        text = p.read_text()
        text = re.sub(r'"(\.\./)+shared/assets/[^"]*\.obj"', '"../assets/cornell_box/cornell_box.obj"', text)
        text = re.sub(r'"(\.\./)+shared/assets/[^"]*\.(gltf|glb)"', '"../assets/BoxTextured/BoxTextured.gltf"', text)
        text = re.sub(r'"(\.\./)+assets/', '"../assets/', text)
        text = text.replace('"../base/room.toml"', '"base/room.toml"').replace('"../room.toml"', '"room.toml"')
        text = text.replace('"../snowman.toml"', '"snowman.toml"')
        if p.parent.name == "parity":
            text = re.sub(r'file = "image_map', 'file = "parity/image_map', text)
        put("scene", str(p.relative_to(ROOT / "scenes")).replace("/", "_"), text.encode())


def objs():
    dirs = [ROOT / "assets" / "cornell_box"] + [SHARED / "obj" / d for d in ("tinyobjloader-cases", "assimp-cases", "cornell-box")]
    for d in dirs:
        for p in sorted(d.glob("*.obj")):
            data = p.read_bytes()
            if len(data) > 8000:
                continue
            mtl = b""
            m = re.search(rb"^\s*mtllib\s+(.+?)\s*$", data, re.M)
            if m:
                lib = d / m.group(1).decode(errors="replace").split()[0]
                if lib.is_file():
                    mtl = lib.read_bytes()
                data = data[: m.start(1)] + b"m.mtl" + data[m.end(1):]
            mtl = re.sub(rb"(map_\w+|bump|disp|norm)(.*?)\S+\s*$", rb"\1\2tex.png", mtl, flags=re.M)
            put("obj", f"{d.name}_{p.stem}", data + (SEP + mtl if mtl else b""))
    # A concave polygon, a polygon with a hole-like spike, and a big convex fan.
    put("obj", "concave", b"v 0 0 0\nv 2 0 0\nv 2 2 0\nv 1 0.5 0\nv 0 2 0\nf 1 2 3 4 5\n")
    n = 200
    ring = "".join(f"v {1 + (i % 2) * 0.5:.3f} 0 0\n" for i in range(0))
    import math
    ring = "".join(f"v {math.cos(2 * math.pi * i / n):.6f} {math.sin(2 * math.pi * i / n):.6f} 0\n" for i in range(n))
    put("obj", "convex200", (ring + "f " + " ".join(str(i + 1) for i in range(n)) + "\n").encode())
    star = "".join(
        f"v {(1 + (i % 2)) * math.cos(2 * math.pi * i / n):.6f} {(1 + (i % 2)) * math.sin(2 * math.pi * i / n):.6f} 0\n"
        for i in range(n)
    )
    put("obj", "star200", (star + "f " + " ".join(str(i + 1) for i in range(n)) + "\n").encode())


def inline_gltf(path):
    doc = json.loads(path.read_text())
    for key, mime in (("buffers", "application/octet-stream"), ("images", None)):
        for item in doc.get(key, []):
            uri = item.get("uri")
            if not uri or uri.startswith("data:"):
                continue
            f = path.parent / uri
            if not f.is_file():
                continue
            m = mime or ("image/png" if uri.lower().endswith(".png") else "image/jpeg")
            item["uri"] = f"data:{m};base64," + base64.b64encode(f.read_bytes()).decode()
    return json.dumps(doc, separators=(",", ":")).encode()


def gltfs():
    put("gltf", "BoxTextured_external.gltf", (ROOT / "assets/BoxTextured/BoxTextured.gltf").read_bytes())
    for p in sorted((SHARED / "gltf").rglob("*")):
        if p.suffix not in (".gltf", ".glb") or "draco" in str(p) or "ClearCoat" in str(p) or "2CylinderEngine" in str(p):
            continue
        name = f"{p.parent.name}_{p.name}"
        if p.suffix == ".glb":
            put("gltf", name, p.read_bytes())
            continue
        try:
            data = inline_gltf(p)
        except (ValueError, UnicodeDecodeError):
            data = p.read_bytes()  # deliberately broken JSON: a seed as it is
        if len(data) < 64_000:
            put("gltf", name, data)


def plys():
    """Small PLY files in each encoding: ASCII, binary both byte orders, gzip; with normals,
    uvs, colours, a quad, a pentagon and an unused element."""
    import gzip
    verts = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 1.5, 0.2)]
    faces = [(0, 1, 2, 3), (3, 2, 4), (0, 1, 4, 2, 3)]
    head = lambda fmt, extra="": (
        f"ply\nformat {fmt} 1.0\ncomment fuzz seed\nelement vertex {len(verts)}\n"
        "property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
        "property float nz\nproperty float s\nproperty float t\nproperty uchar red\nproperty uchar green\n"
        f"property uchar blue\nelement face {len(faces)}\nproperty list uchar int vertex_indices\n{extra}end_header\n"
    ).encode()
    rows = [(*v, 0.0, 0.0, 1.0, v[0], v[1], 200, 100, 50) for v in verts]
    ascii_body = "".join(" ".join(str(x) for x in r) + "\n" for r in rows)
    ascii_body += "".join(f"{len(f)} " + " ".join(map(str, f)) + "\n" for f in faces)
    ascii_ply = head("ascii") + ascii_body.encode()
    put("ply", "quad_ascii.ply", ascii_ply)
    for order, fmt in (("<", "binary_little_endian"), (">", "binary_big_endian")):
        body = b"".join(struct.pack(order + "8f3B", *r) for r in rows)
        body += b"".join(struct.pack(order + "B%di" % len(f), len(f), *f) for f in faces)
        put("ply", f"quad_{fmt}.ply", head(fmt) + body)
    put("ply", "quad_ascii.ply.gz", gzip.compress(ascii_ply, mtime=0))
    extra = "element material 1\nproperty uchar alpha\n"
    put("ply", "extra_element.ply", head("ascii", extra) + ascii_body.encode() + b"7\n")
    for p in sorted((ROOT / "assets" / "ply").rglob("*.ply*")):
        if p.stat().st_size < 64_000:
            put("ply", p.name, p.read_bytes())


def png(w, h, rgba):
    raw = b"".join(b"\0" + bytes(rgba[(y * w) * 4:(y * w + w) * 4]) for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def images():
    w, h = 8, 4
    rgb = [((x * 37 + y * 11) % 256, (x * 5) % 256, (y * 60) % 256) for y in range(h) for x in range(w)]
    rgba = [c for p in rgb for c in (*p, 255 - p[0] // 2)]
    sel = lambda ext: bytes([EXTS.index(ext)])
    put("image", "rgba.png", sel("png") + png(w, h, rgba))
    put("image", "CesiumLogoFlat.png", sel("png") + (ROOT / "assets/BoxTextured/CesiumLogoFlat.png").read_bytes())
    put("image", "SpiderTex.jpg", sel("jpg") + (SHARED / "obj/assimp-cases/SpiderTex.jpg").read_bytes())
    for p in sorted((ROOT / "scenes" / "parity").glob("image_map*.png")):
        put("image", p.name, sel("png") + p.read_bytes())
    hdr = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w)
    hdr += bytes(c for p in rgb for c in (p[0] | 1, p[1] | 1, p[2] | 1, 128))
    put("image", "flat.hdr", sel("hdr") + hdr)
    env = (ROOT / "assets/env/studio_256x128.hdr").read_bytes()
    put("image", "studio_rle.hdr", sel("hdr") + env[:]) if len(env) < 120_000 else None
    row = (w * 3 + 3) & ~3
    bmp_pixels = b"".join(bytes(c for x in range(w) for c in rgb[y * w + x][::-1]) + b"\0" * (row - w * 3) for y in reversed(range(h)))
    bmp = b"BM" + struct.pack("<IHHI", 54 + len(bmp_pixels), 0, 0, 54) + struct.pack("<IiiHHIIiiII", 40, w, h, 1, 24, 0, len(bmp_pixels), 2835, 2835, 0, 0) + bmp_pixels
    put("image", "rgb.bmp", sel("bmp") + bmp)
    tga = struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, w, h, 32, 8) + bytes(c for i in range(w * h) for c in (rgba[4 * i + 2], rgba[4 * i + 1], rgba[4 * i], rgba[4 * i + 3]))
    put("image", "rgba.tga", sel("tga") + tga)
    put("image", "rgb.pnm", sel("pnm") + b"P6\n%d %d\n255\n" % (w, h) + bytes(c for p in rgb for c in p))
    put("image", "grey.pnm", sel("pnm") + b"P2\n2 2\n15\n0 5\n10 15\n")
    qoi = b"qoif" + struct.pack(">IIBB", w, h, 4, 0) + b"".join(b"\xff" + bytes(rgba[4 * i:4 * i + 4]) for i in range(w * h)) + b"\0" * 7 + b"\1"
    put("image", "rgba.qoi", sel("qoi") + qoi)
    pix = bytes(c for p in rgb for c in p)
    entries = [(256, 3, 1, w), (257, 3, 1, h), (258, 3, 3, None), (259, 3, 1, 1), (262, 3, 1, 2), (273, 4, 1, None), (277, 3, 1, 3), (278, 3, 1, h), (279, 4, 1, len(pix))]
    ifd_at, bps_at = 8, 8 + 2 + 12 * len(entries) + 4
    data_at = bps_at + 6
    ifd = struct.pack("<H", len(entries))
    for tag, typ, count, value in entries:
        value = bps_at if tag == 258 else data_at if tag == 273 else value
        ifd += struct.pack("<HHI", tag, typ, count) + (struct.pack("<HH", value, 0) if typ == 3 and count == 1 else struct.pack("<I", value))
    tif = b"II*\0" + struct.pack("<I", ifd_at) + ifd + b"\0\0\0\0" + struct.pack("<HHH", 8, 8, 8) + pix
    put("image", "rgb.tif", sel("tif") + tif)
    put("image", "sunset.exr", sel("exr") + (ROOT / "assets/env/sunset_256x128.exr").read_bytes())
    # A tiny EXR as Prism writes it (needs a built target/release/prism).
    prism = ROOT / "target/release/prism"
    work = OUT.parent / "seed-work"
    work.mkdir(exist_ok=True)
    (work / "s.toml").write_text('[[object]]\nshape = "sphere"\n[[light]]\nkind = "point"\nposition = [0, 5, -5]\n')
    subprocess.run([str(prism), "render", "s.toml", "-o", "s.png", "--exr", "s.exr", "--width", "8", "--height", "4"],
                   cwd=work, check=True)
    put("image", "small.exr", sel("exr") + (work / "s.exr").read_bytes())
    shutil.rmtree(work)


def scene_dictionary():
    """fuzz/scene.dict: every key and enumerated value of the scene schema, for libFuzzer's -dict."""
    schema = json.loads(subprocess.run([str(ROOT / "target/release/prism"), "schema"], check=True,
                                       capture_output=True).stdout)
    words = set()

    def walk(node):
        if isinstance(node, dict):
            for key, value in node.items():
                if key == "properties" and isinstance(value, dict):
                    words.update(value.keys())
                if key in ("enum", "const"):
                    for v in value if isinstance(value, list) else [value]:
                        if isinstance(v, str):
                            words.add(v)
                walk(value)
        elif isinstance(node, list):
            for v in node:
                walk(v)

    walk(schema)
    words.update(["[[object]]", "[[light]]", "[materials.", "[render]", "[camera]", "[world]", "include", "shape"])
    lines = [json.dumps(w) for w in sorted(words) if w and all(32 <= ord(c) < 127 for c in w)]
    (OUT.parent / "scene.dict").write_text("\n".join(lines) + "\n")


def licences():
    d = OUT / "LICENSES"
    d.mkdir(parents=True, exist_ok=True)
    for src, name in [
        (SHARED / "obj/tinyobjloader-cases/LICENSE.tinyobjloader", "LICENSE.tinyobjloader"),
        (SHARED / "obj/assimp-cases/COPYRIGHT.debian-assimp-testmodels", "COPYRIGHT.debian-assimp-testmodels"),
        (SHARED / "gltf/khronos-samples/AssetGenerator/LICENSE", "LICENSE.glTF-Asset-Generator"),
        (SHARED / "gltf/khronos-samples/TextureTransformTest/License.txt", "License.TextureTransformTest"),
    ]:
        if src.is_file():
            shutil.copyfile(src, d / name)


if __name__ == "__main__":
    if OUT.exists():
        shutil.rmtree(OUT)
    scenes(); scene_dictionary(); objs(); gltfs(); plys(); images(); licences()
    for t in sorted(p for p in OUT.iterdir() if p.is_dir()):
        files = list(t.iterdir())
        print(t.name, len(files), "files", sum(f.stat().st_size for f in files), "bytes")
