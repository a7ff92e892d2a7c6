#!/usr/bin/env python3
"""Render the committed Mitsuba 3 references of the path integrator's equivalence scenes.

Usage: python3 scripts/mitsuba-references.py [--seeds K] [--spp S] [SCENE.xml ...]

For every scenes/mitsuba/NAME.xml (written by `prism export mitsuba`; run
scripts/mitsuba-check.sh or the exporter first), renders K seeds at S samples per pixel with
Mitsuba 3 (scalar_rgb, or llvm_ad_rgb for scenes that use the glTF metallic-roughness plugin
of scripts/mitsuba_gltf_bsdf.py, registered before loading, and for scenes with a non-box
pixel filter, which the scalar variants discretise) and writes scenes/mitsuba/refs/NAME.exr (the mean over seeds,
linear RGB) and scenes/mitsuba/refs/NAME_stderr.exr (the standard error of that mean per
pixel channel: the sample standard deviation over seeds / sqrt(K)). tests/mitsuba.rs
compares Prism's renders with them, so `cargo test` checks the path integrator against
Mitsuba without Mitsuba installed; CI also re-renders fresh references
(scripts/mitsuba-check.sh).
"""
import argparse
import glob
import os
import sys

import mitsuba as mi
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_gltf_bsdf  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=16)
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("scenes", nargs="*")
    args = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    scenes = args.scenes or sorted(glob.glob(os.path.join(root, "scenes/mitsuba/*.xml")))
    refs = os.path.join(root, "scenes/mitsuba/refs")
    os.makedirs(refs, exist_ok=True)
    for path in scenes:
        name = os.path.splitext(os.path.basename(path))[0]
        mitsuba_gltf_bsdf.prepare(path)
        scene = mi.load_file(path)
        images = np.stack([np.array(mi.render(scene, seed=k, spp=args.spp), dtype=np.float64)[..., :3]
                           for k in range(args.seeds)])
        mean = images.mean(axis=0)
        stderr = images.std(axis=0, ddof=1) / np.sqrt(args.seeds)
        mi.Bitmap(mean.astype(np.float32), mi.Bitmap.PixelFormat.RGB).write(os.path.join(refs, name + ".exr"))
        mi.Bitmap(stderr.astype(np.float32), mi.Bitmap.PixelFormat.RGB).write(os.path.join(refs, name + "_stderr.exr"))
        print(f"{name}: {args.seeds} x {args.spp} spp, mean {mean.mean():.6f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
