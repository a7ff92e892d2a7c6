#!/usr/bin/env python3
"""Time to equal error: Prism's `path` integrator against Mitsuba 3 (issue 13, item 8).

Usage (from the repository root, after `cargo build --release`):
    python3 scripts/bench-equal-error.py [SCENE.toml] [--size 512] [--threads 2]
        [--ladder 4,8,16,32,64,128,256] [--reference-spp 2048] [--work DIR]
        [--variants llvm_ad_rgb,scalar_rgb]

The scene (default scenes/mitsuba/cornell.toml, the Cornell box with max depth 8) is exported
with `prism export mitsuba` and resized to SIZE x SIZE. A converged reference is rendered
once with Mitsuba (llvm_ad_rgb when it loads, else scalar_rgb) at --reference-spp and cached
in the work folder. Then, for each sample count of the ladder, Prism and each Mitsuba variant
render the scene; the time of each render and its RMSE against the reference are recorded.
Prism's time is the wall time of the `prism render` process (scene loading included: a few
milliseconds here); Mitsuba's is `mi.render` alone, after one warm-up render so that the
llvm variant's kernel compilation is not counted.

RMSE of an unbiased estimator falls as 1/sqrt(spp), so time x RMSE^2 is a constant c of each
renderer and scene; c is the median over the ladder's points from 16 spp on, and the time to
reach an error e is c / e^2. The target error is what Mitsuba llvm_ad_rgb reaches at 256 spp
(or at the ladder's largest count when 256 is not in it). Prints a Markdown table and the ratio
Prism / Mitsuba llvm_ad_rgb at equal error. Tests never time anything; this is the benchmark.

Needs: numpy, OpenEXR (pip), mitsuba 3.9.1 (pip); llvm_ad_rgb needs Debian's libllvm19.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np


def read_exr(path):
    import OpenEXR

    with OpenEXR.File(str(path)) as f:
        channels = f.channels()
        if "RGB" in channels:
            return np.asarray(channels["RGB"].pixels, dtype=np.float64)
        return np.stack([np.asarray(channels[c].pixels, dtype=np.float64) for c in "RGB"], axis=-1)


def rmse(image, reference):
    return float(np.sqrt(np.mean((image - reference) ** 2)))


def resize_xml(text, size):
    text = re.sub(r'(<integer name="width" value=")\d+', rf"\g<1>{size}", text)
    return re.sub(r'(<integer name="height" value=")\d+', rf"\g<1>{size}", text)


class Mitsuba:
    """One Mitsuba variant in a child process (a process holds one variant at a time)."""

    CHILD = r"""
import os, sys, time, mitsuba as mi
sys.path.insert(0, sys.argv[3])
import mitsuba_gltf_bsdf
mitsuba_gltf_bsdf.prepare(sys.argv[2], sys.argv[1])
scene = mi.load_file(sys.argv[2])
mi.render(scene, seed=999, spp=4)  # warm-up: the llvm variant compiles its kernel here
for line in sys.stdin:
    spp, seed, out = line.split()
    t = time.perf_counter()
    image = mi.render(scene, seed=int(seed), spp=int(spp))
    import drjit as dr; dr.eval(image); dr.sync_thread()
    elapsed = time.perf_counter() - t
    mi.Bitmap(image).write(out)
    print(elapsed, flush=True)
"""

    def __init__(self, variant, xml, threads):
        env = dict(os.environ, DRJIT_NUM_THREADS=str(threads))
        self.proc = subprocess.Popen(
            [sys.executable, "-c", self.CHILD, variant, str(xml), os.path.dirname(os.path.abspath(__file__))],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env,
        )

    def render(self, spp, seed, out):
        self.proc.stdin.write(f"{spp} {seed} {out}\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        if not line:
            raise RuntimeError("the Mitsuba child process ended")
        return float(line)

    def close(self):
        self.proc.stdin.close()
        self.proc.wait()


def variant_works(variant):
    probe = "import mitsuba as mi; mi.set_variant('%s'); mi.render(mi.load_dict(mi.cornell_box()), spp=1)" % variant
    return subprocess.run([sys.executable, "-c", probe], capture_output=True).returncode == 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene", nargs="?", default="scenes/mitsuba/cornell.toml")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--ladder", default="4,8,16,32,64,128,256")
    ap.add_argument("--reference-spp", type=int, default=2048)
    ap.add_argument("--work", default="target/bench-equal-error")
    ap.add_argument("--variants", default="llvm_ad_rgb,scalar_rgb")
    ap.add_argument("--prism", default="target/release/prism")
    args = ap.parse_args()

    work = Path(args.work) / Path(args.scene).stem
    work.mkdir(parents=True, exist_ok=True)
    ladder = [int(s) for s in args.ladder.split(",")]
    xml = work / "scene.xml"
    subprocess.run([args.prism, "export", "mitsuba", args.scene, "-o", str(xml)], check=True)
    xml.write_text(resize_xml(xml.read_text(), args.size))

    variants = [v for v in args.variants.split(",") if variant_works(v)]
    skipped = sorted(set(args.variants.split(",")) - set(variants))
    if skipped:
        print(f"note: Mitsuba variants that do not run here: {', '.join(skipped)}", file=sys.stderr)
    if not variants:
        sys.exit("no Mitsuba variant runs here")

    reference_path = work / f"reference_{args.size}_{args.reference_spp}.exr"
    if not reference_path.exists():
        print(f"rendering the reference: {variants[0]}, {args.reference_spp} spp ...", file=sys.stderr, flush=True)
        m = Mitsuba(variants[0], xml, args.threads)
        m.render(args.reference_spp, 12345, str(reference_path))
        m.close()
    reference = read_exr(reference_path)

    results = {}  # renderer -> [(spp, seconds, rmse)]
    mitsubas = {v: Mitsuba(v, xml, args.threads) for v in variants}
    for spp in ladder:
        # Interleaved, so that the machine's load falls on every renderer alike.
        out = work / f"prism_{spp}.exr"
        start = time.perf_counter()
        subprocess.run(
            [args.prism, "render", args.scene, "--integrator", "path", "--width", str(args.size), "--height",
             str(args.size), "--samples", str(spp), "--threads", str(args.threads), "-o", str(work / "prism.png"),
             "--exr", str(out)],
            check=True, capture_output=True,
        )
        seconds = time.perf_counter() - start
        results.setdefault("Prism path", []).append((spp, seconds, rmse(read_exr(out), reference)))
        for v, m in mitsubas.items():
            out = work / f"{v}_{spp}.exr"
            seconds = m.render(spp, spp, str(out))
            results.setdefault(f"Mitsuba {v}", []).append((spp, seconds, rmse(read_exr(out), reference)))
        print(f"{spp} spp done", file=sys.stderr, flush=True)
    for m in mitsubas.values():
        m.close()

    constants = {
        name: statistics.median(t * e * e for spp, t, e in rows if spp >= 16) for name, rows in results.items()
    }
    judge = "Mitsuba llvm_ad_rgb" if "Mitsuba llvm_ad_rgb" in results else f"Mitsuba {variants[0]}"
    target_spp = 256 if 256 in ladder else max(ladder)
    target = next(e for spp, _, e in results[judge] if spp == target_spp)
    print(f"\nScene {args.scene} at {args.size}x{args.size}, {args.threads} threads; reference "
          f"{variants[0]} at {args.reference_spp} spp. Target error: {judge} at {target_spp} spp, "
          f"RMSE {target:.5f}.\n")
    print("| renderer | " + " | ".join(f"{s} spp: s / RMSE" for s in ladder) + " | time to target |")
    print("| --- | " + " | ".join("---" for _ in ladder) + " | --- |")
    for name, rows in results.items():
        cells = " | ".join(f"{t:.2f} / {e:.5f}" for _, t, e in rows)
        print(f"| {name} | {cells} | {constants[name] / target ** 2:.2f} s |")
    ratio = constants["Prism path"] / constants[judge]
    print(f"\nPrism / {judge} time at equal error: {ratio:.2f}x")


if __name__ == "__main__":
    main()
