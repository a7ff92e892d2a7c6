#!/usr/bin/env python3
"""Time saved by adaptive sampling (`--noise`) at equal RMSE.

Usage: scripts/measure-adaptive.py PRISM SCENE SIZE_X SIZE_Y REF_SPP [extra prism args...]

Renders a reference at REF_SPP, fixed-count renders at 16..256 spp and adaptive renders at
several noise targets (at most 1024 spp), measures each one's RMSE against the reference
and render time (the summary line's), and for each adaptive render prints the time a
fixed-count render of the same RMSE takes, interpolated log-log between the fixed renders
around it. RMSE both of linear RGB (where the few pixels of a light, 15 times brighter
than a wall, dominate) and of the displayed image (clipped to [0, 1]). Needs numpy and OpenEXR's Python bindings (pip install OpenEXR).
"""

import math
import re
import subprocess
import sys
import tempfile

import numpy as np
import OpenEXR


def render(prism, scene, size, args, exr):
    cmd = [prism, "render", scene, "--width", size[0], "--height", size[1], "--exr", exr, *args]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True)
    seconds = float(re.search(r" in ([0-9.]+) s:", out.stderr).group(1))
    spread = re.search(r"samples per pixel: .*", out.stderr)
    return seconds, spread.group(0) if spread else ""


def load(exr):
    part = OpenEXR.File(exr).parts[0]
    return np.asarray(part.channels["RGB"].pixels, dtype=np.float64)


def main():
    prism, scene, w, h, ref_spp, *extra = sys.argv[1:]
    size = (w, h)
    with tempfile.TemporaryDirectory() as tmp:
        ref_path = f"{tmp}/ref.exr"
        ref_time, _ = render(prism, scene, size, ["--samples", ref_spp, "--seed", "7", *extra], ref_path)
        ref = load(ref_path)
        print(f"reference: {ref_spp} spp in {ref_time:.1f} s")

        def rmse(path):
            image = load(path)
            linear = math.sqrt(float(np.mean((image - ref) ** 2)))
            shown = math.sqrt(float(np.mean((np.clip(image, 0, 1) - np.clip(ref, 0, 1)) ** 2)))
            return shown, linear

        def fixed_time(e, which):
            # Fixed renders' time at RMSE e, log-log between the neighbours (or extrapolated
            # from the nearest two).
            pts = sorted(((f[which], f[2]) for f in fixed), reverse=True)
            i = next((k for k in range(len(pts) - 1) if pts[k + 1][0] <= e), len(pts) - 2)
            (e0, t0), (e1, t1) = pts[i], pts[i + 1]
            slope = (math.log(t1) - math.log(t0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + slope * (math.log(e) - math.log(e0)))

        fixed = []
        for spp in [16, 32, 64, 128, 256]:
            path = f"{tmp}/fixed{spp}.exr"
            t, _ = render(prism, scene, size, ["--samples", str(spp), *extra], path)
            fixed.append((*rmse(path), t))
            print(f"fixed {spp:4d} spp: RMSE shown {fixed[-1][0]:.5f}, linear {fixed[-1][1]:.5f}, {t:.2f} s")
        for noise in ["0.2", "0.1", "0.05", "0.03"]:
            path = f"{tmp}/adaptive{noise}.exr"
            args = ["--samples", "1024", "--noise", noise, "--aov", "samples", *extra]
            t, spread = render(prism, scene, size, args, path)
            shown, linear = rmse(path)
            ts, tl = fixed_time(shown, 0), fixed_time(linear, 1)
            print(
                f"adaptive noise {noise}: {t:.2f} s, RMSE shown {shown:.5f} (fixed: {ts:.2f} s, ratio {t / ts:.2f}), "
                f"linear {linear:.5f} (fixed: {tl:.2f} s, ratio {t / tl:.2f}); {spread}"
            )


if __name__ == "__main__":
    main()
