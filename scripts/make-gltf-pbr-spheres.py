#!/usr/bin/env python3
"""Writes assets/gltf/pbr-spheres/: three UV spheres in one glTF 2.0 file whose materials use
metallic-roughness textures, made here and dedicated to the public domain (CC0).

Usage: python3 scripts/make-gltf-pbr-spheres.py [OUT_DIR]

- sphere 0: base colour texture (sRGB tiles) and a metallicRoughness texture (blue = metal
  in bands along v, green = roughness rising along u from 0.25 to 1) whose red channel holds
  an occlusion map, also named as the material's occlusionTexture (ORM packing) - glTF's
  occlusion is for rasterisers' ambient term and must not darken path-traced light;
- sphere 1: gold base colour factor, metallic 1, roughness factor 0.8 times the same
  texture's green channel (its metal bands multiply the factor);
- sphere 2: a red dielectric with roughness 0.5 and no textures;
and material_grid.gltf: the same sphere ten times, a copper row and a blue dielectric row
with roughness 0.1 .. 0.9 (factors only), for scenes/gltf_showcase.toml.
The spheres are 64 x 32 quads (the pole rows are triangles) of radius 0.5, with smooth
normals and glTF uvs (v down from the image's top, 0 at the north pole). Needs numpy and
pillow. The output is deterministic.
"""

import json
import os
import struct
import sys

import numpy as np
from PIL import Image

SEGMENTS_U, SEGMENTS_V = 64, 32


def sphere():
    positions, normals, uvs = [], [], []
    for j in range(SEGMENTS_V + 1):
        v = j / SEGMENTS_V
        theta = np.pi * v
        for i in range(SEGMENTS_U + 1):
            u = i / SEGMENTS_U
            phi = 2.0 * np.pi * u
            n = (np.sin(theta) * np.cos(phi), np.cos(theta), -np.sin(theta) * np.sin(phi))
            normals.append(n)
            positions.append(tuple(0.5 * c for c in n))
            uvs.append((u, v))
    indices = []
    row = SEGMENTS_U + 1
    for j in range(SEGMENTS_V):
        for i in range(SEGMENTS_U):
            a, b = j * row + i, j * row + i + 1
            c, d = (j + 1) * row + i, (j + 1) * row + i + 1
            # Counter-clockwise seen from outside; the pole rows keep one triangle per quad.
            if j != 0:
                indices += [a, c, b]
            if j != SEGMENTS_V - 1:
                indices += [b, c, d]
    return (np.array(positions, np.float32), np.array(normals, np.float32), np.array(uvs, np.float32),
            np.array(indices, np.uint16))


def textures(out):
    w, h = 64, 32
    y, x = np.mgrid[0:h, 0:w]
    tiles = ((x // 8) + (y // 8)) % 2
    base = np.where(tiles[..., None] == 1, [230, 190, 60], [40, 110, 200]).astype(np.uint8)
    base[(x % 16) == 0] = [245, 245, 245]
    Image.fromarray(base, "RGB").save(os.path.join(out, "basecolor.png"), optimize=False)
    occlusion = np.where((y // 4) % 2 == 0, 255, 70)
    roughness = np.round(255 * (0.25 + 0.75 * x / (w - 1)))
    metal = np.where((y // 8) % 2 == 0, 255, 0)
    orm = np.stack([occlusion, roughness, metal], axis=-1).astype(np.uint8)
    Image.fromarray(orm, "RGB").save(os.path.join(out, "occlusion_roughness_metal.png"), optimize=False)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "assets", "gltf", "pbr-spheres")
    os.makedirs(out, exist_ok=True)
    textures(out)
    positions, normals, uvs, indices = sphere()
    blobs = [positions.tobytes(), normals.tobytes(), uvs.tobytes(), indices.tobytes()]
    offsets, data = [], b""
    for blob in blobs:
        data += b"\0" * (-len(data) % 4)
        offsets.append(len(data))
        data += blob
    with open(os.path.join(out, "pbr_spheres.bin"), "wb") as f:
        f.write(data)
    views = [{"buffer": 0, "byteOffset": o, "byteLength": len(b)} for o, b in zip(offsets, blobs)]
    views[3]["target"] = 34963
    for v in views[:3]:
        v["target"] = 34962
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
         "min": positions.min(axis=0).tolist(), "max": positions.max(axis=0).tolist()},
        {"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": len(uvs), "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
    ]
    primitive = {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}
    materials = [
        {"name": "textured", "pbrMetallicRoughness": {
            "baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1},
            "metallicFactor": 1.0, "roughnessFactor": 1.0},
         "occlusionTexture": {"index": 1}},
        {"name": "gold", "pbrMetallicRoughness": {
            "baseColorFactor": [1.0, 0.77, 0.34, 1.0], "metallicRoughnessTexture": {"index": 1},
            "metallicFactor": 1.0, "roughnessFactor": 0.8}},
        {"name": "red plastic", "pbrMetallicRoughness": {
            "baseColorFactor": [0.7, 0.08, 0.06, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5}},
    ]
    gltf = {
        "asset": {"version": "2.0", "generator": "scripts/make-gltf-pbr-spheres.py (Prism)",
                  "copyright": "CC0 1.0 (public domain dedication)"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": i, "translation": [1.1 * (i - 1), 0.5, 0.0], "name": m["name"]}
                  for i, m in enumerate(materials)],
        "meshes": [{"primitives": [dict(primitive, material=i)]} for i in range(3)],
        "materials": materials,
        "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}],
        "images": [{"uri": "basecolor.png"}, {"uri": "occlusion_roughness_metal.png"}],
        "buffers": [{"uri": "pbr_spheres.bin", "byteLength": len(data)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    with open(os.path.join(out, "pbr_spheres.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    # The material grid: the same sphere, roughness 0.1 .. 0.9 along x, a copper metal row
    # behind a blue dielectric row; no textures.
    grid = dict(gltf)
    roughnesses = [0.1, 0.3, 0.5, 0.7, 0.9]
    grid["materials"] = [
        {"name": f"{kind} r{r}", "pbrMetallicRoughness": {
            "baseColorFactor": color + [1.0], "metallicFactor": metal, "roughnessFactor": r}}
        for kind, color, metal in [("copper", [0.95, 0.64, 0.54], 1.0), ("blue", [0.05, 0.2, 0.6], 0.0)]
        for r in roughnesses
    ]
    grid["meshes"] = [{"primitives": [dict(primitive, material=i)]} for i in range(len(grid["materials"]))]
    grid["nodes"] = [{"mesh": row * 5 + i, "name": grid["materials"][row * 5 + i]["name"],
                      "translation": [1.1 * (i - 2), 0.5, -1.1 * (1 - row)]}
                     for row in range(2) for i in range(5)]
    grid["scenes"] = [{"nodes": list(range(len(grid["nodes"])))}]
    for key in ("textures", "samplers", "images"):
        del grid[key]
    with open(os.path.join(out, "material_grid.gltf"), "w") as f:
        json.dump(grid, f, indent=1)
        f.write("\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
