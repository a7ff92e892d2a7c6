#!/usr/bin/env python3
"""Render one Mitsuba 3 scene K times with different seeds, for
scripts/mitsuba_compare.py.

Usage:
    python3 scripts/mitsuba_render_seeds.py SCENE.xml --seeds K --spp S --out DIR \
        [--variant auto]

Loads SCENE.xml once and writes DIR/mitsuba_<k>.exr (linear RGB float32) for
k = 0 .. K-1 from mi.render(scene, seed=k, spp=S). Mitsuba multiplies the seed
by the pixel count before seeding each pixel's sampler, so consecutive seeds
give non-overlapping random streams: the K images are independent estimates
of the same expected image. --spp overrides the scene's sample_count. The
variant is per scene (`auto`, scripts/mitsuba_gltf_bsdf.py's variant_for):
scalar_rgb, or llvm_ad_rgb for scenes with a non-box pixel filter or that use the glTF metallic-roughness
plugin, which is registered before loading. Prints the time of each render.
Exit 2 when the scene cannot be loaded.
"""

import argparse
import os
import sys
import time


def main():
    ap = argparse.ArgumentParser(description="Render a Mitsuba scene with seeds 0..K-1")
    ap.add_argument("scene", help="Mitsuba XML scene")
    ap.add_argument("--seeds", type=int, required=True, metavar="K", help="number of renders")
    ap.add_argument("--spp", type=int, required=True, metavar="S", help="samples per pixel")
    ap.add_argument("--out", required=True, metavar="DIR", help="output directory")
    ap.add_argument("--variant", default="auto", help="Mitsuba variant (default auto: per scene)")
    args = ap.parse_args()

    import mitsuba as mi

    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import mitsuba_gltf_bsdf

    variant = mitsuba_gltf_bsdf.prepare(args.scene, args.variant)
    os.makedirs(args.out, exist_ok=True)
    t0 = time.perf_counter()
    try:
        scene = mi.load_file(args.scene)
    except Exception as e:  # noqa: BLE001
        print(f"error: cannot load {args.scene}: {e}", file=sys.stderr)
        return 2
    size = scene.sensors()[0].film().crop_size()
    print(f"loaded {args.scene} ({size[0]}x{size[1]}, {variant}) in {time.perf_counter() - t0:.2f} s")
    total = 0.0
    for k in range(args.seeds):
        t = time.perf_counter()
        img = mi.render(scene, seed=k, spp=args.spp)
        path = os.path.join(args.out, f"mitsuba_{k}.exr")
        mi.Bitmap(img).write(path)
        dt = time.perf_counter() - t
        total += dt
        msamples = size[0] * size[1] * args.spp / dt / 1e6
        print(f"seed {k}: {dt:.2f} s ({msamples:.2f} Msamples/s) -> {path}", flush=True)
    print(f"{args.seeds} renders at {args.spp} spp in {total:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
