#!/usr/bin/env python3
"""RGB complex IOR (eta, k) of Mitsuba 3's named conductors, as its `scalar_rgb` variant sees them.

Origin: a re-implementation (written for Prism, no Mitsuba code copied) of what Mitsuba 3.9 does
when a `conductor`/`roughconductor` names a `material` in an RGB variant:
`complex_ior_from_file` (include/mitsuba/render/ior.h) reads `data/ior/<name>.eta.spd` and
`.k.spd` and turns each into an unbounded `srgb` texture with
`spectrum_list_to_srgb(wavelengths, values, bounded=false, d65=false)` (src/core/spectrum.cpp):

  * 1000 wavelengths evenly spaced over [360, 830] nm (both ends included);
  * wavelengths outside the file's range are skipped; inside, the data is linearly interpolated;
  * XYZ += cie1931_xyz(w) * value (the CIE 1931 2-degree table at 5 nm, linearly interpolated);
  * XYZ *= (830 - 360) / 106.7502593994140625 / 1000;
  * linear sRGB (Rec. 709) = the usual XYZ -> sRGB matrix; negative channels clamped to 0.

The spectral data files live in the mitsuba-data repository (ior/*.spd) and the CIE table in
Mitsuba's src/core/spectrum.cpp; neither is copied here. Usage:

    scripts/mitsuba_metal_rgb.py path/to/mitsuba3/src/core/spectrum.cpp path/to/mitsuba-data/ior

It prints one Rust table row per metal, the numbers in src/render/bsdf/metals.rs.
"""

import re
import sys
from pathlib import Path

CIE_MIN, CIE_MAX, CIE_SAMPLES = 360.0, 830.0, 95
CIE_Y_NORMALIZATION = 1.0 / 106.7502593994140625
XYZ_TO_SRGB = [
    [3.240479, -1.537150, -0.498535],
    [-0.969256, 1.875991, 0.041556],
    [0.055648, -0.204043, 1.057311],
]


def cie_table(spectrum_cpp):
    """The x, y and z tables (95 values each) of `cie1931_tbl` in Mitsuba's spectrum.cpp."""
    text = Path(spectrum_cpp).read_text()
    body = text[text.index("cie1931_tbl[") :]
    body = body[body.index("{") + 1 : body.index("};")]
    values = [float(v) for v in re.findall(r"Float\(([-0-9.eE+]+)\)", body)]
    assert len(values) == 3 * CIE_SAMPLES, len(values)
    return [values[i * CIE_SAMPLES : (i + 1) * CIE_SAMPLES] for i in range(3)]


def read_spd(path):
    """(wavelengths, values) of an .spd file: two numbers a line, '#' starts a comment."""
    wavelengths, values = [], []
    for line in Path(path).read_text().splitlines():
        line = line.split("#", 1)[0].split()
        if len(line) >= 2:
            wavelengths.append(float(line[0]))
            values.append(float(line[1]))
    return wavelengths, values


def cie_xyz(table, w):
    t = (w - CIE_MIN) * ((CIE_SAMPLES - 1) / (CIE_MAX - CIE_MIN))
    i0 = min(max(int(t), 0), CIE_SAMPLES - 2)
    w1 = t - i0
    return [(1.0 - w1) * tab[i0] + w1 * tab[i0 + 1] for tab in table]


def spectrum_to_srgb(table, wavelengths, values):
    steps = 1000
    xyz = [0.0, 0.0, 0.0]
    for i in range(steps):
        w = CIE_MIN + (i / (steps - 1)) * (CIE_MAX - CIE_MIN)
        if w < wavelengths[0] or w > wavelengths[-1]:
            continue
        index = 0
        for j in range(len(wavelengths) - 1):
            if wavelengths[j] <= w:
                index = j
        w0, w1 = wavelengths[index], wavelengths[index + 1]
        v0, v1 = values[index], values[index + 1]
        v = ((w - w1) * v0 + (w0 - w) * v1) / (w0 - w1)
        c = cie_xyz(table, w)
        xyz = [a + b * v for a, b in zip(xyz, c)]
    scale = (CIE_MAX - CIE_MIN) * CIE_Y_NORMALIZATION / steps
    xyz = [a * scale for a in xyz]
    rgb = [sum(m * x for m, x in zip(row, xyz)) for row in XYZ_TO_SRGB]
    return [max(c, 0.0) for c in rgb]


def main():
    table = cie_table(sys.argv[1])
    ior = Path(sys.argv[2])
    for name in ["Au", "Ag", "Cu", "Al", "Cr"]:
        eta = spectrum_to_srgb(table, *read_spd(ior / f"{name}.eta.spd"))
        k = spectrum_to_srgb(table, *read_spd(ior / f"{name}.k.spd"))
        fmt = lambda c: "DVec3::new({:.6}, {:.6}, {:.6})".format(*c)
        print(f'    ("{name}", {fmt(eta)}, {fmt(k)}),')


if __name__ == "__main__":
    main()
