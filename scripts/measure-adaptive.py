#!/usr/bin/env python3
"""Time saved by adaptive sampling (`--noise`) at equal RMSE.

Usage: scripts/measure-adaptive.py [options] PRISM SCENE [extra prism args...]

Renders (or reads) a converged reference, fixed-count renders at 16..256 spp and adaptive
renders at several noise targets (at most --max-spp), measures each one's RMSE against the
reference and cost, and for each adaptive render prints the cost of a fixed-count render of
the same RMSE, interpolated log-log between the fixed renders around it (ratio < 1: adaptive
sampling saves time). RMSE both of the displayed image (linear values clipped to [0, 1]) and
of linear RGB (where the few pixels of a light, 15 times brighter than a wall, dominate).

Cost is measured twice: the CPU time (user + system) of the prism process (not the wall
time its summary line prints: on a shared machine the wall time says more about the
neighbours than about the render), and the number of rays the render traced, which its
summary line prints: a deterministic cost, free of the machine's noise (CPU time varied by
30 % between identical runs on a shared machine), that counts a cheap background sample
as cheap. Every render in one run uses the same thread count (--threads, default 2).
--repeat N renders everything N times, interleaved, and keeps each render's smallest CPU
time.

Options: --size W H (default: the scene's), --reference FILE.exr (a converged image, e.g.
scenes/mitsuba/refs/cornell.exr) or --ref-spp N (rendered with another seed, default 4096),
--noise LIST (comma-separated targets, default 0.2,0.1,0.05,0.03), --max-spp N (default
1024), --prism-adaptive BINARY[,BINARY...] (other builds for the adaptive renders, to compare
rules in one run), --seeds K (render everything with seeds 1..K and average the squared
errors and costs: one render's RMSE moves by several per cent with its seed, which is as
much as the differences measured).

Needs numpy and OpenEXR's Python bindings (pip install OpenEXR).

Example (the measurements in docs/long-renders.md):
  scripts/measure-adaptive.py target/release/prism scenes/mitsuba/cornell.toml \\
      --reference scenes/mitsuba/refs/cornell.exr --noise 0.1,0.05,0.03,0.02
"""

import argparse
import math
import re
import resource
import subprocess
import tempfile

import numpy as np
import OpenEXR


def render(prism, scene, args, exr):
    cmd = [prism, "render", scene, "--exr", exr, *args]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(cmd, capture_output=True, text=True, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    spread = re.search(r"samples per pixel: .*", out.stderr)
    rays = re.search(r"(\d+) rays in all", out.stderr)
    return cpu, int(rays.group(1)), spread.group(0) if spread else ""


def load(exr):
    part = OpenEXR.File(exr).parts[0]
    return np.asarray(part.channels["RGB"].pixels, dtype=np.float64)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("prism")
    ap.add_argument("scene")
    ap.add_argument("--size", nargs=2, metavar=("W", "H"))
    ap.add_argument("--reference")
    ap.add_argument("--ref-spp", default="4096")
    ap.add_argument("--noise", default="0.2,0.1,0.05,0.03")
    ap.add_argument("--max-spp", default="1024")
    ap.add_argument("--threads", default="2")
    ap.add_argument("--prism-adaptive")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--seeds", type=int, default=1)
    args, extra = ap.parse_known_args()
    extra = [*extra, "--threads", args.threads]
    if args.size:
        extra = [*extra, "--width", args.size[0], "--height", args.size[1]]
    with tempfile.TemporaryDirectory() as tmp:
        if args.reference:
            ref = load(args.reference)
            print(f"reference: {args.reference}")
        else:
            ref_path = f"{tmp}/ref.exr"
            cpu, _, _ = render(args.prism, args.scene, ["--samples", args.ref_spp, "--seed", "7", *extra], ref_path)
            ref = load(ref_path)
            print(f"reference: {args.ref_spp} spp in {cpu:.1f} CPU s")

        def squared_errors(path):
            image = load(path)
            shown = float(np.mean((np.clip(image, 0, 1) - np.clip(ref, 0, 1)) ** 2))
            linear = float(np.mean((image - ref) ** 2))
            return shown, linear

        def fixed_cost(e, which, cost):
            # Fixed renders' cost at RMSE e, log-log between the neighbours (or extrapolated
            # from the nearest two).
            pts = sorted(((f[which], f[cost]) for f in fixed), reverse=True)
            i = next((k for k in range(len(pts) - 1) if pts[k + 1][0] <= e), len(pts) - 2)
            (e0, t0), (e1, t1) = pts[i], pts[i + 1]
            slope = (math.log(t1) - math.log(t0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + slope * (math.log(e) - math.log(e0)))

        # Each render's (RMSE shown, RMSE linear, smallest CPU time, rays, spread), the RMSE
        # over seeds the root of the mean squared error, CPU time and rays the means.
        runs = {}
        adaptive_builds = (args.prism_adaptive or args.prism).split(",")
        jobs = [(f"fixed{spp}", args.prism, ["--samples", str(spp), *extra]) for spp in [16, 32, 64, 128, 256]]
        for noise in args.noise.split(","):
            adaptive_args = ["--samples", args.max_spp, "--noise", noise, "--aov", "samples", *extra]
            for build, binary in enumerate(adaptive_builds):
                jobs.append((f"adaptive{noise}/{build}", binary, adaptive_args))
        for _ in range(args.repeat):
            for name, binary, job_args in jobs:
                path = f"{tmp}/job.exr"
                errors, cpu, ray_count = [0.0, 0.0], 0.0, 0
                for seed in range(1, args.seeds + 1):
                    t, rays, spread = render(binary, args.scene, [*job_args, "--seed", str(seed)], path)
                    errors = [a + b / args.seeds for a, b in zip(errors, squared_errors(path))]
                    cpu += t / args.seeds
                    ray_count += rays / args.seeds
                previous = runs.get(name)
                runs[name] = (*map(math.sqrt, errors), min(cpu, previous[2]) if previous else cpu, ray_count, spread)
        fixed = []
        for spp in [16, 32, 64, 128, 256]:
            fixed.append(runs[f"fixed{spp}"])
            shown, linear, t, rays, _ = fixed[-1]
            print(f"fixed {spp:4d} spp: RMSE shown {shown:.5f}, linear {linear:.5f}, {t:.2f} CPU s, {rays / 1e6:.2f} Mrays")
        for noise in args.noise.split(","):
            for build, binary in enumerate(adaptive_builds):
                shown, linear, t, rays, spread = runs[f"adaptive{noise}/{build}"]
                ts, tl = fixed_cost(shown, 0, 2), fixed_cost(linear, 1, 2)
                rs, rl = fixed_cost(shown, 0, 3), fixed_cost(linear, 1, 3)
                print(
                    f"adaptive ({binary}) noise {noise}: RMSE shown {shown:.5f}: CPU {t:.2f} s vs fixed {ts:.2f} s (ratio {t / ts:.2f}), "
                    f"rays {rays / 1e6:.2f} M vs {rs / 1e6:.2f} M (ratio {rays / rs:.2f}); "
                    f"linear {linear:.5f}: CPU ratio {t / tl:.2f}, rays ratio {rays / rl:.2f}; {spread}"
                )
    

if __name__ == "__main__":
    main()
