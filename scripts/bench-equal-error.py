#!/usr/bin/env python3
"""Time to equal error: Prism's `path` integrator against Mitsuba 3 (issue 13, item 8).

Usage (from the repository root, after `cargo build --release`):
    python3 scripts/bench-equal-error.py [SCENE.toml] [--size 512] [--threads 2]
        [--ladder 4,8,16,32,64,128,256] [--rounds 3] [--reference-spp 2048] [--work DIR]
        [--variants llvm_ad_rgb,scalar_rgb,llvm_ad_rgb:ldsampler] [--prism-time process|render]

The scene (default scenes/mitsuba/cornell.toml, the Cornell box with max depth 8) is exported
with `prism export mitsuba` and resized to SIZE x SIZE. A converged reference is rendered
once with Mitsuba (the first variant that loads) at --reference-spp and cached in the work
folder. Then, for each sample count of the ladder, Prism and each Mitsuba variant render the
scene; the time of each render and its RMSE against the reference are recorded. A variant
`NAME:SAMPLER` renders with Mitsuba's SAMPLER (`ldsampler`, its low-discrepancy (0, 2)-
sequences per dimension pair, the counterpart of Prism's padded Sobol points; `multijitter`,
`stratified`) instead of the exported `independent` one, for a comparison of stratified
samplers on both sides. These samplers round a sample count up to a square (ldsampler: a
power of 4, so 32 spp renders 64), so they render only the ladder's squares. Prism's time is the wall time of the `prism render` process (scene loading included:
a few milliseconds here); Mitsuba's is `mi.render` alone, after one warm-up render so that the
llvm variant's kernel compilation is not counted.

The ladder runs --rounds times, every renderer interleaved with the others, and each render's
time is the fastest of its rounds (on a shared machine load only ever adds time); the seeds,
and so the images, are the same in every round. The time each renderer needs to reach an error
e is read off its own ladder: the sample count where its RMSE falls to e, by log-log
interpolation between the two ladder points around it (extrapolated along the last segment
beyond the ladder), and the time there, interpolated the same way. Nothing assumes
RMSE ~ 1/sqrt(spp), which a stratified sampler beats. The target error is what Mitsuba
llvm_ad_rgb (independent sampler, as exported) reaches at 256 spp, or at the ladder's largest
count when 256 is not in it. Prints a Markdown table and the ratio Prism / Mitsuba llvm_ad_rgb
at equal error. Tests never time anything; this is the benchmark.

Needs: numpy, OpenEXR (pip), mitsuba 3.9.1 (pip); llvm_ad_rgb needs Debian's libllvm19.
"""

import argparse
import math
import os
import re
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
mi.set_log_level(mi.LogLevel.Error)  # stdout carries the timings
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


def with_sampler(text, sampler):
    """The scene XML `text` with its sampler's type replaced by `sampler`."""
    replaced, count = re.subn(r'<sampler type="[a-z_]+"', f'<sampler type="{sampler}"', text)
    if count != 1:
        sys.exit(f"cannot set the sampler to {sampler}: {count} <sampler> elements")
    return replaced


def log_interpolate(x, x0, x1, y0, y1):
    """y at x on the line through (x0, y0) and (x1, y1) in log-log space."""
    slope = (math.log(y1) - math.log(y0)) / (math.log(x1) - math.log(x0))
    return math.exp(math.log(y0) + slope * (math.log(x) - math.log(x0)))


def time_to_error(rows, target):
    """Seconds a renderer needs to reach RMSE `target`, read off its ladder rows
    (spp, seconds, rmse): the sample count where the RMSE crosses the target (log-log
    between the points around it, extrapolated along the last segment beyond the ladder),
    and the time at that count, interpolated the same way. Also returns that count."""
    rows = sorted(rows)
    pairs = list(zip(rows, rows[1:]))
    segment = next(((a, b) for a, b in pairs if a[2] >= target >= b[2]), None)
    if segment is None:
        segment = pairs[0] if target > rows[0][2] else pairs[-1]
    (s0, t0, e0), (s1, t1, e1) = segment
    # The sample count where the error reaches the target: interpolate spp against RMSE.
    spp = log_interpolate(target, e0, e1, s0, s1) if e0 != e1 else s1
    return log_interpolate(spp, s0, s1, t0, t1), spp


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene", nargs="?", default="scenes/mitsuba/cornell.toml")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--ladder", default="4,8,16,32,64,128,256")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--reference-spp", type=int, default=2048)
    ap.add_argument("--work", default="target/bench-equal-error")
    ap.add_argument("--variants", default="llvm_ad_rgb,scalar_rgb,llvm_ad_rgb:ldsampler")
    ap.add_argument("--prism", default="target/release/prism")
    ap.add_argument("--prism-time", choices=["process", "render"], default="process")
    args = ap.parse_args()

    work = Path(args.work) / Path(args.scene).stem
    work.mkdir(parents=True, exist_ok=True)
    ladder = [int(s) for s in args.ladder.split(",")]
    xml = work / "scene.xml"
    subprocess.run([args.prism, "export", "mitsuba", args.scene, "-o", str(xml)], check=True)
    xml.write_text(resize_xml(xml.read_text(), args.size))

    requested = args.variants.split(",")
    variants = [v for v in requested if variant_works(v.split(":")[0])]
    skipped = sorted(set(requested) - set(variants))
    if skipped:
        print(f"note: Mitsuba variants that do not run here: {', '.join(skipped)}", file=sys.stderr)
    if not variants:
        sys.exit("no Mitsuba variant runs here")

    def scene_file(variant):
        if ":" not in variant:
            return xml
        sampler = variant.split(":")[1]
        path = work / f"scene_{sampler}.xml"
        path.write_text(with_sampler(xml.read_text(), sampler))
        return path

    reference_path = work / f"reference_{args.size}_{args.reference_spp}.exr"
    if not reference_path.exists():
        first = variants[0].split(":")[0]
        print(f"rendering the reference: {first}, {args.reference_spp} spp ...", file=sys.stderr, flush=True)
        m = Mitsuba(first, xml, args.threads)
        m.render(args.reference_spp, 12345, str(reference_path))
        m.close()
    reference = read_exr(reference_path)

    def renders(variant, spp):
        """Whether the variant's sampler takes `spp` as it is (the stratified ones round a
        count up to a square, ldsampler to a power of 4)."""
        if ":" not in variant:
            return True
        root = math.isqrt(spp)
        return root * root == spp and (variant.split(":")[1] != "ldsampler" or spp & (spp - 1) == 0)

    best = {}  # (renderer, spp) -> (fastest seconds, rmse)

    def record(name, spp, seconds, out):
        previous = best.get((name, spp))
        error = previous[1] if previous else rmse(read_exr(out), reference)
        best[(name, spp)] = (min(seconds, previous[0]) if previous else seconds, error)

    mitsubas = {v: Mitsuba(v.split(":")[0], scene_file(v), args.threads) for v in variants}
    for round_index in range(args.rounds):
        for spp in ladder:
            # Interleaved, so that the machine's load falls on every renderer alike.
            out = work / f"prism_{spp}.exr"
            start = time.perf_counter()
            done = subprocess.run(
                [args.prism, "render", args.scene, "--integrator", "path", "--width", str(args.size), "--height",
                 str(args.size), "--samples", str(spp), "--threads", str(args.threads), "-o",
                 str(work / "prism.png"), "--exr", str(out)],
                check=True, capture_output=True, text=True,
            )
            seconds = time.perf_counter() - start
            if args.prism_time == "render":
                reported = re.search(r"^rendered .* in ([0-9.]+) s", done.stderr, re.MULTILINE)
                if not reported:
                    sys.exit(f"prism did not report its render time:\n{done.stderr}")
                seconds = float(reported.group(1))
            record("Prism path", spp, seconds, out)
            for v, m in mitsubas.items():
                if not renders(v, spp):
                    continue
                out = work / f"{v.replace(':', '_')}_{spp}.exr"
                record(f"Mitsuba {v}", spp, m.render(spp, spp, str(out)), out)
            print(f"round {round_index + 1}: {spp} spp done", file=sys.stderr, flush=True)
    for m in mitsubas.values():
        m.close()

    names = ["Prism path"] + [f"Mitsuba {v}" for v in variants]
    results = {name: [(spp, *best[(name, spp)]) for spp in ladder if (name, spp) in best] for name in names}
    judge = "Mitsuba llvm_ad_rgb" if "Mitsuba llvm_ad_rgb" in results else f"Mitsuba {variants[0]}"
    target_spp = 256 if 256 in ladder else max(ladder)
    target = next(e for spp, _, e in results[judge] if spp == target_spp)
    reached = {name: time_to_error(rows, target) for name, rows in results.items()}
    print(f"\nScene {args.scene} at {args.size}x{args.size}, {args.threads} threads, fastest of "
          f"{args.rounds} interleaved rounds; reference {variants[0].split(':')[0]} at {args.reference_spp} spp. "
          f"Target error: {judge} at {target_spp} spp, RMSE {target:.5f}.\n")
    print("| renderer | " + " | ".join(f"{s} spp: s / RMSE" for s in ladder) + " | spp to target | time to target |")
    print("| --- | " + " | ".join("---" for _ in ladder) + " | --- | --- |")
    for name, rows in results.items():
        measured = {spp: (t, e) for spp, t, e in rows}
        cells = " | ".join(f"{measured[s][0]:.2f} / {measured[s][1]:.5f}" if s in measured else "-" for s in ladder)
        seconds, spp = reached[name]
        print(f"| {name} | {cells} | {spp:.0f} | {seconds:.2f} s |")
    for name in names:
        if name != judge:
            print(f"\n{name} / {judge} time at equal error: {reached[name][0] / reached[judge][0]:.2f}x")


if __name__ == "__main__":
    main()
