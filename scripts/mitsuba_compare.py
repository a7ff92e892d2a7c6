#!/usr/bin/env python3
"""Statistical judge: do Prism's `path` integrator and Mitsuba 3 render the same
expected image?

Usage
-----
    python3 scripts/mitsuba_compare.py --prism P1.exr P2.exr ... \
        --mitsuba M1.exr M2.exr ... [--out DIR] [--alpha 0.01] \
        [--min-pass auto|FRACTION] [--bias 0.005] [--name NAME]
    python3 scripts/mitsuba_compare.py --self-test

Each side supplies K >= 16 (at least 2 are required) independent renders of
the same scene at the same size, made with different seeds (see
scripts/prism_render_seeds.sh and scripts/mitsuba_render_seeds.py). Images are
read with mitsuba.Bitmap (variant scalar_rgb); the R, G, B channels are used
(by name when the EXR has them, else the first three channels).

Statistics (modelled on mitsuba3/src/render/tests/test_renders.py, which
compares one render against a reference with a Z test and a Sidak-corrected
threshold; here both sides are Monte Carlo estimates, so it is a two-sample
test on the K renders of each side):

 * Per pixel channel: mean and unbiased variance over the K renders of each
   side; Welch's t = (mean_p - mean_m) / sqrt(var_p/K_p + var_m/K_m) with
   Welch-Satterthwaite degrees of freedom; two-sided p-value from the Student
   t CDF (implemented here via the regularized incomplete beta function; no
   scipy). Pixel channels whose variance is zero on both sides pass (p = 1)
   when the means agree within 1e-6 relative, else fail (p = 0). Non-finite
   values (NaN / inf) in any render make that pixel channel fail (p = 0) and
   fail the "finite" check.

 * Check "pixels" (uncorrected): fraction of the N pixel channels with
   p >= alpha must be >= --min-pass. Under the null hypothesis p is uniform,
   so the expected fraction is 1 - alpha (0.99 for alpha = 0.01). The default
   "auto" threshold is 1 - alpha - 4 * sqrt(alpha (1 - alpha) / n_pixels): 4
   binomial standard deviations below that expectation, counting each pixel
   (not each channel; R, G and B of a pixel are strongly correlated) as one
   trial. This catches a small bias spread over many pixels that no single
   pixel reveals. (A fixed 0.9975 together with an *uncorrected* alpha = 0.01
   cannot be met even by identical renderers; Mitsuba's 0.9975 applies to
   the Sidak threshold, see the next check, which is stricter: it allows no
   failure at all.)

 * Check "sidak" (strict): the Sidak-corrected per-test threshold is
   alpha_s = 1 - (1 - alpha)^(1/N). No pixel channel may have p < alpha_s;
   under the null hypothesis the chance that any does is alpha. This catches
   a localized gross error (a wrong highlight, a missing small object).

 * Check "bias" (whole image): per render, the image mean over all pixels and
   channels; Welch's test on the K image means of each side gives the
   difference of the grand means d = mean_p - mean_m with standard error se
   and degrees of freedom df. The 99 % confidence interval of d / mean_m is
   printed; the check passes when the whole interval lies within +-bias, i.e.
   |d| + t_{0.995, df} se < bias * mean_m (default bias 0.5 %). An interval
   wider than the bound fails too: then more or longer renders are needed.

Output: one line per check and a final "PASS NAME" / "FAIL NAME". Exit status
0 = pass, 1 = fail, 2 = bad input (unreadable file, mismatched sizes, K < 2).
With --out (or on failure, into ./compare_NAME when --out is absent) it
writes NAME_prism_mean.exr, NAME_mitsuba_mean.exr, NAME_difference.exr
(prism - mitsuba), NAME_pvalue.exr (per-pixel min p over channels),
NAME_pvalue.png (red: p < Sidak threshold, yellow: p < alpha, grey: pass) and
NAME_prism_mean.png / NAME_mitsuba_mean.png (sRGB, clipped).

--self-test runs synthetic checks in memory: the Student t CDF against known
values; same-distribution sides must pass for >= 19 of 20 seeds; a 1 % global
offset must fail the bias check; a 10-pixel blob 20 % brighter must fail the
Sidak check. Exit 0 when all hold.
"""

import argparse
import math
import os
import sys

import numpy as np

EXIT_PASS, EXIT_FAIL, EXIT_BAD_INPUT = 0, 1, 2


class BadInput(Exception):
    pass


# ---------------------------------------------------------------------------
# Student t distribution via the regularized incomplete beta function
# ---------------------------------------------------------------------------

_lgamma = np.vectorize(math.lgamma, otypes=[np.float64])


def _betacf(a, b, x, max_iter=100000, eps=1e-15):
    """Continued fraction of the incomplete beta function (modified Lentz),
    vectorized over arrays a, b, x; converged elements drop out."""
    a, b, x = np.broadcast_arrays(np.asarray(a, np.float64),
                                  np.asarray(b, np.float64),
                                  np.asarray(x, np.float64))
    a, b, x = a.ravel(), b.ravel(), x.ravel()
    tiny = 1e-300
    qab, qap, qam = a + b, a + 1.0, a - 1.0
    c = np.ones_like(x)
    d = 1.0 - qab * x / qap
    d = np.where(np.abs(d) < tiny, tiny, d)
    d = 1.0 / d
    h = d.copy()
    out = np.full_like(x, np.nan)
    idx = np.arange(x.size)
    for m in range(1, max_iter + 1):
        if idx.size == 0:
            break
        m2 = 2 * m
        aa = m * (b - m) * x / ((qam + m2) * (a + m2))
        d = 1.0 + aa * d
        d = np.where(np.abs(d) < tiny, tiny, d)
        c = 1.0 + aa / c
        c = np.where(np.abs(c) < tiny, tiny, c)
        d = 1.0 / d
        h = h * d * c
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2))
        d = 1.0 + aa * d
        d = np.where(np.abs(d) < tiny, tiny, d)
        c = 1.0 + aa / c
        c = np.where(np.abs(c) < tiny, tiny, c)
        d = 1.0 / d
        delta = d * c
        h = h * delta
        done = np.abs(delta - 1.0) < eps
        if done.any():
            out[idx[done]] = h[done]
            keep = ~done
            idx, a, b, x, c, d, h = (v[keep] for v in (idx, a, b, x, c, d, h))
            qab, qap, qam = a + b, a + 1.0, a - 1.0
    if idx.size:  # not converged (should not happen): best estimate
        out[idx] = h
    return out


def betainc_reg(a, b, x):
    """Regularized incomplete beta I_x(a, b) for a, b > 0, 0 <= x <= 1."""
    a, b, x = np.broadcast_arrays(np.asarray(a, np.float64),
                                  np.asarray(b, np.float64),
                                  np.asarray(x, np.float64))
    shape = x.shape
    a, b, x = a.ravel(), b.ravel(), x.ravel()
    res = np.empty_like(x)
    res[x <= 0.0] = 0.0
    res[x >= 1.0] = 1.0
    inner = (x > 0.0) & (x < 1.0)
    if inner.any():
        ai, bi, xi = a[inner], b[inner], x[inner]
        lbt = (_lgamma(ai + bi) - _lgamma(ai) - _lgamma(bi)
               + ai * np.log(xi) + bi * np.log1p(-xi))
        bt = np.exp(lbt)
        # Use the continued fraction where it converges fast, else symmetry.
        direct = xi < (ai + 1.0) / (ai + bi + 2.0)
        r = np.empty_like(xi)
        if direct.any():
            r[direct] = bt[direct] * _betacf(ai[direct], bi[direct], xi[direct]) / ai[direct]
        flip = ~direct
        if flip.any():
            r[flip] = 1.0 - bt[flip] * _betacf(bi[flip], ai[flip], 1.0 - xi[flip]) / bi[flip]
        res[inner] = r
    return res.reshape(shape)


def t_two_sided_p(t, df):
    """Two-sided p-value P(|T| >= |t|) of Student's t with df degrees of
    freedom: I_{df/(df+t^2)}(df/2, 1/2)."""
    t = np.asarray(t, np.float64)
    df = np.asarray(df, np.float64)
    t, df = np.broadcast_arrays(t, df)
    x = df / (df + t * t)
    p = betainc_reg(df / 2.0, 0.5, x)
    return np.clip(p, 0.0, 1.0)


def t_cdf(t, df):
    """CDF of Student's t."""
    t = np.asarray(t, np.float64)
    half = 0.5 * t_two_sided_p(t, df)
    return np.where(t >= 0, 1.0 - half, half)


def t_quantile(q, df):
    """Quantile of Student's t (scalar), by bisection on the CDF."""
    if not 0.0 < q < 1.0:
        raise ValueError("q must be in (0, 1)")
    if q < 0.5:
        return -t_quantile(1.0 - q, df)
    lo, hi = 0.0, 1.0
    while float(t_cdf(hi, df)) < q:
        hi *= 2.0
        if hi > 1e12:
            return math.inf
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if float(t_cdf(mid, df)) < q:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-12 * max(1.0, hi):
            break
    return 0.5 * (lo + hi)


# ---------------------------------------------------------------------------
# Welch's test
# ---------------------------------------------------------------------------

# Relative difference of two means below which they agree: a few float32 roundings.
FLOAT_AGREEMENT = 2e-5


def welch(mean_a, var_a, n_a, mean_b, var_b, n_b):
    """Welch's t statistic, Welch-Satterthwaite df and standard error."""
    va, vb = var_a / n_a, var_b / n_b
    se2 = va + vb
    with np.errstate(divide="ignore", invalid="ignore"):
        se = np.sqrt(se2)
        t = (mean_a - mean_b) / se
        df = se2 * se2 / (va * va / (n_a - 1) + vb * vb / (n_b - 1))
    return t, df, se


# ---------------------------------------------------------------------------
# The comparison
# ---------------------------------------------------------------------------

def compare(prism, mitsuba, alpha=0.01, min_pass=None, bias=0.005):
    """prism, mitsuba: float64 arrays (K, H, W, 3). Returns a dict with the
    per-check results and the images for the report."""
    kp, km = prism.shape[0], mitsuba.shape[0]
    if kp < 2 or km < 2:
        raise BadInput(f"need K >= 2 renders per side (prism {kp}, mitsuba {km})")
    if prism.shape[1:] != mitsuba.shape[1:]:
        raise BadInput(f"image sizes differ: prism {prism.shape[1:]} vs mitsuba {mitsuba.shape[1:]}")
    h, w, c = prism.shape[1:]
    n = h * w * c
    n_pixels = h * w

    finite_p = np.isfinite(prism).all(axis=0)
    finite_m = np.isfinite(mitsuba).all(axis=0)
    nonfinite_p = int((~np.isfinite(prism)).sum())
    nonfinite_m = int((~np.isfinite(mitsuba)).sum())
    pz = np.where(np.isfinite(prism), prism, 0.0)
    mz = np.where(np.isfinite(mitsuba), mitsuba, 0.0)

    mean_p, mean_m = pz.mean(axis=0), mz.mean(axis=0)
    var_p, var_m = pz.var(axis=0, ddof=1), mz.var(axis=0, ddof=1)
    t, df, _ = welch(mean_p, var_p, kp, mean_m, var_m, km)

    both_const = (var_p == 0.0) & (var_m == 0.0)
    ok = ~both_const
    p = np.ones_like(mean_p)
    if ok.any():
        p[ok] = t_two_sided_p(np.abs(t[ok]), df[ok])
    scale = np.maximum(np.abs(mean_p), np.abs(mean_m))
    equal = np.abs(mean_p - mean_m) <= 1e-6 * scale
    p[both_const] = np.where(equal[both_const], 1.0, 0.0)
    # Means within float32 rounding of each other (a background both sides render as the
    # same constant, summed in different orders) agree whatever the variances say; so do
    # means within rounding of the image's level (a black pixel that a filter with negative
    # lobes leaves at 1e-10 after cancelling its neighbours' weights in float32).
    level = float(np.abs(mean_p).mean() + np.abs(mean_m).mean()) / 2.0
    p[np.abs(mean_p - mean_m) <= FLOAT_AGREEMENT * np.maximum(scale, level)] = 1.0
    p[~(finite_p & finite_m)] = 0.0
    p = np.where(np.isnan(p), 0.0, p)

    sidak = 1.0 - (1.0 - alpha) ** (1.0 / n)
    if min_pass is None:
        min_pass = 1.0 - alpha - 4.0 * math.sqrt(alpha * (1.0 - alpha) / n_pixels)
    frac = float((p >= alpha).mean())
    n_sidak = int((p < sidak).sum())
    worst = np.unravel_index(int(np.argmin(p)), p.shape)

    # Whole-image bias: Welch on the K per-render image means.
    img_p = pz.reshape(kp, -1).mean(axis=1)
    img_m = mz.reshape(km, -1).mean(axis=1)
    gp, gm = img_p.mean(), img_m.mean()
    sp2, sm2 = img_p.var(ddof=1), img_m.var(ddof=1)
    _, bdf, bse = welch(gp, sp2, kp, gm, sm2, km)
    d = gp - gm
    if bse > 0 and np.isfinite(bdf):
        tq = t_quantile(0.995, float(bdf))
    else:
        tq, bdf = 0.0, float("inf")
    half = tq * bse
    if gm > 0:
        lo, hi = (d - half) / gm, (d + half) / gm
        bias_ok = bool(abs(d) + half < bias * gm)
    else:
        lo = hi = float("nan")
        bias_ok = bool(abs(d) + half <= 1e-6 * max(abs(gp), 1e-300)) and gp == gm

    checks = []
    if nonfinite_p or nonfinite_m:
        checks.append(("finite", False,
                       f"non-finite values: prism {nonfinite_p}, mitsuba {nonfinite_m}"))
    checks.append(("pixels", frac >= min_pass,
                   f"{frac * 100:.3f} % of {n} pixel channels have p >= {alpha:g} "
                   f"(need >= {min_pass * 100:.3f} %; expected {100 * (1 - alpha):.2f} % "
                   f"if equal); {int(both_const.sum())} constant on both sides"))
    checks.append(("sidak", n_sidak == 0,
                   f"{n_sidak} pixel channels have p < Sidak threshold {sidak:.3e} "
                   f"(min p = {p.min():.3e} at x={worst[1]} y={worst[0]} ch={'RGB'[worst[2]] if c == 3 else worst[2]}: "
                   f"prism {mean_p[worst]:.6g} vs mitsuba {mean_m[worst]:.6g})"))
    checks.append(("bias", bias_ok,
                   f"image mean prism {gp:.6g} mitsuba {gm:.6g}: relative difference "
                   f"{(d / gm if gm else float('nan')) * 100:+.3f} %, 99 % CI "
                   f"[{lo * 100:+.3f} %, {hi * 100:+.3f} %] (df {bdf:.1f}), "
                   f"must lie within +-{bias * 100:.3g} %"))
    return {
        "checks": checks,
        "passed": all(ok for _, ok, _ in checks),
        "mean_p": mean_p, "mean_m": mean_m, "p": p,
        "alpha": alpha, "sidak": sidak, "frac": frac, "n_sidak": n_sidak,
        "bias_lo": lo, "bias_hi": hi, "bias_ok": bias_ok,
    }


# ---------------------------------------------------------------------------
# Image input / output (mitsuba.Bitmap)
# ---------------------------------------------------------------------------

_mi = None


def mitsuba():
    global _mi
    if _mi is None:
        import mitsuba as mi
        mi.set_variant("scalar_rgb")
        _mi = mi
    return _mi


def read_rgb(path):
    mi = mitsuba()
    if not os.path.isfile(path):
        raise BadInput(f"cannot read {path}: no such file")
    try:
        bmp = mi.Bitmap(path)
        st = bmp.struct_()
        names = [st[i].name for i in range(len(st))]
        arr = np.array(bmp, copy=True).astype(np.float64)
    except Exception as e:  # noqa: BLE001 - any reader error is bad input
        raise BadInput(f"cannot read {path}: {e}") from None
    if arr.ndim == 2:
        arr = arr[..., None]
    if all(ch in names for ch in ("R", "G", "B")):
        arr = arr[..., [names.index("R"), names.index("G"), names.index("B")]]
    elif arr.shape[2] >= 3:
        arr = arr[..., :3]
    else:
        raise BadInput(f"{path}: need 3 colour channels, found {names}")
    return arr


def read_side(paths, label):
    imgs = [read_rgb(p) for p in paths]
    shapes = {im.shape for im in imgs}
    if len(shapes) != 1:
        detail = ", ".join(f"{p}: {im.shape[1]}x{im.shape[0]}" for p, im in zip(paths, imgs))
        raise BadInput(f"{label} renders differ in size: {detail}")
    return np.stack(imgs)


def write_outputs(res, out_dir, name):
    mi = mitsuba()
    os.makedirs(out_dir, exist_ok=True)
    f32 = lambda a: np.ascontiguousarray(a, dtype=np.float32)  # noqa: E731
    files = []

    def exr(suffix, arr):
        path = os.path.join(out_dir, f"{name}_{suffix}.exr")
        fmt = mi.Bitmap.PixelFormat.RGB if arr.ndim == 3 else mi.Bitmap.PixelFormat.Y
        mi.Bitmap(f32(arr), fmt).write(path)
        files.append(path)

    def png_srgb(suffix, arr):
        path = os.path.join(out_dir, f"{name}_{suffix}.png")
        bmp = mi.Bitmap(f32(np.clip(arr, 0.0, None)), mi.Bitmap.PixelFormat.RGB)
        bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, True).write(path)
        files.append(path)

    pmin = res["p"].min(axis=2)
    exr("prism_mean", res["mean_p"])
    exr("mitsuba_mean", res["mean_m"])
    exr("difference", res["mean_p"] - res["mean_m"])
    exr("pvalue", pmin)
    png_srgb("prism_mean", res["mean_p"])
    png_srgb("mitsuba_mean", res["mean_m"])
    col = np.full(pmin.shape + (3,), 128, np.uint8)
    col[pmin < res["alpha"]] = (255, 255, 0)
    col[pmin < res["sidak"]] = (255, 0, 0)
    path = os.path.join(out_dir, f"{name}_pvalue.png")
    mi.Bitmap(np.ascontiguousarray(col), mi.Bitmap.PixelFormat.RGB).write(path)
    files.append(path)
    return files


def report(res, name, out=sys.stdout):
    for check, ok, msg in res["checks"]:
        print(f"{'ok  ' if ok else 'FAIL'} {check:6s} {msg}", file=out)
    print(f"{'PASS' if res['passed'] else 'FAIL'} {name}", file=out)


# ---------------------------------------------------------------------------
# Self-test
# ---------------------------------------------------------------------------

def _synthetic(rng, k=16, h=32, w=32, spp=400):
    """A smooth image with a black corner (zero variance on both sides), and
    K renders of it with gamma noise (the mean of `spp` exponential samples:
    relative standard deviation 1/sqrt(spp), slightly skewed)."""
    y, x = np.mgrid[0:h, 0:w] / np.array([h, w])[:, None, None]
    base = np.stack([0.2 + 0.8 * x, 0.3 + 0.5 * y, 0.1 + 0.4 * x * y], axis=-1)
    base[:4, :4] = 0.0

    def side():
        shape = (k, h, w, 3)
        return rng.gamma(spp, 1.0 / spp, size=shape) * base

    return base, side


def self_test():
    failures = 0

    def check(label, cond, detail=""):
        nonlocal failures
        print(f"{'ok  ' if cond else 'FAIL'} {label}{': ' + detail if detail else ''}")
        failures += 0 if cond else 1

    # (d) Student t against known values.
    for t, df, want in [(2.0, 10, 0.07339), (1.0, 1, 0.5), (1.96, 1e6, 0.05),
                        (0.0, 5, 1.0), (2.042272, 30, 0.05)]:
        got = float(t_two_sided_p(t, df))
        check(f"t two-sided p(t={t}, df={df:g})", abs(got - want) < 1e-4,
              f"{got:.6f} (want {want})")
    got = float(betainc_reg(2.0, 3.0, 0.4))  # = 0.5248 exactly
    check("I_0.4(2, 3)", abs(got - 0.5248) < 1e-10, f"{got:.10f}")
    got = t_quantile(0.995, 30)
    check("t quantile 0.995, df 30", abs(got - 2.749996) < 1e-4, f"{got:.6f}")
    # Monotone and consistent on a grid, incl. the symmetry branch.
    ts = np.linspace(0, 10, 101)
    ps = t_two_sided_p(ts, 7.3)
    check("p monotone in |t|", bool(np.all(np.diff(ps) <= 1e-15)) and ps[0] == 1.0)

    # (a) Same distribution on both sides passes for >= 19 of 20 seeds.
    passes = 0
    for seed in range(20):
        rng = np.random.default_rng(seed)
        _, side = _synthetic(rng)
        res = compare(side(), side())
        passes += res["passed"]
        if not res["passed"]:
            print(f"     seed {seed}: " + "; ".join(f"{c} {m}" for c, ok, m in res["checks"] if not ok))
    check("same distribution passes", passes >= 19, f"{passes} of 20 seeds")

    # (b) A 1 % global brightness offset fails the bias check.
    rng = np.random.default_rng(100)
    _, side = _synthetic(rng)
    res = compare(side() * 1.01, side())
    check("1 % global offset fails bias", not res["bias_ok"] and not res["passed"],
          f"CI [{res['bias_lo'] * 100:+.3f} %, {res['bias_hi'] * 100:+.3f} %]")

    # (c) A 10-pixel blob 20 % too bright fails the Sidak check.
    rng = np.random.default_rng(101)
    _, side = _synthetic(rng)
    a = side()
    blob = [(10, 20), (10, 21), (11, 20), (11, 21), (11, 22),
            (12, 20), (12, 21), (12, 22), (13, 21), (13, 22)]
    for yy, xx in blob:
        a[:, yy, xx, :] *= 1.2
    res = compare(a, side())
    check("10-pixel blob +20 % fails Sidak", res["n_sidak"] > 0 and not res["passed"],
          f"{res['n_sidak']} pixel channels below {res['sidak']:.3e}, bias ok={res['bias_ok']}")

    # Zero-variance handling: identical constant sides pass, different fail.
    const = np.ones((4, 2, 2, 3))
    check("constant equal sides pass", compare(const, const.copy())["passed"])
    r = compare(const, const * 1.001)
    check("constant different sides fail", not r["passed"] and r["n_sidak"] == 12)
    # A black pixel one side leaves at float32 rounding of the image's level passes; one at
    # a visible fraction of it fails.
    rng_black = np.random.default_rng(5)
    lit = 0.5 + 0.01 * rng_black.standard_normal((16, 4, 4, 3))
    lit_too = 0.5 + 0.01 * rng_black.standard_normal((16, 4, 4, 3))
    lit[:, 0, 0, :] = 0.0
    lit_too[:, 0, 0, :] = 1e-10 * (1.0 + rng_black.random((16, 3)))
    check("rounding-level black pixel passes", compare(lit, lit_too)["n_sidak"] == 0)
    lit_too[:, 0, 0, :] = 1e-3 * (1.0 + 0.01 * rng_black.random((16, 3)))
    check("visible black pixel difference fails", compare(lit, lit_too)["n_sidak"] == 3)

    # Bad input.
    try:
        compare(np.zeros((1, 2, 2, 3)), np.zeros((3, 2, 2, 3)))
        check("K < 2 rejected", False)
    except BadInput:
        check("K < 2 rejected", True)
    try:
        compare(np.zeros((3, 2, 2, 3)), np.zeros((3, 2, 3, 3)))
        check("size mismatch rejected", False)
    except BadInput:
        check("size mismatch rejected", True)

    print(f"{'PASS' if failures == 0 else 'FAIL'} self-test ({failures} failures)")
    return EXIT_PASS if failures == 0 else EXIT_FAIL


# ---------------------------------------------------------------------------

def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--prism", nargs="+", metavar="EXR", help="Prism renders")
    ap.add_argument("--mitsuba", nargs="+", metavar="EXR", help="Mitsuba renders")
    ap.add_argument("--out", metavar="DIR", help="write mean / difference / p-value images here")
    ap.add_argument("--alpha", type=float, default=0.01, help="significance level (default 0.01)")
    ap.add_argument("--min-pass", default="auto",
                    help="minimum fraction of pixel channels with p >= alpha "
                         "(default auto: 1 - alpha - 4 binomial sigmas over pixels)")
    ap.add_argument("--bias", type=float, default=0.005,
                    help="bound on the relative whole-image bias (default 0.005)")
    ap.add_argument("--name", default="compare", help="name in the verdict and output files")
    ap.add_argument("--self-test", action="store_true", help="run the synthetic self-test")
    args = ap.parse_args(argv)

    if args.self_test:
        return self_test()
    if not args.prism or not args.mitsuba:
        print("error: --prism and --mitsuba are required (or --self-test)", file=sys.stderr)
        return EXIT_BAD_INPUT
    try:
        min_pass = None if args.min_pass == "auto" else float(args.min_pass)
    except ValueError:
        print(f"error: bad --min-pass {args.min_pass!r}", file=sys.stderr)
        return EXIT_BAD_INPUT
    if not 0.0 < args.alpha < 1.0:
        print("error: --alpha must be in (0, 1)", file=sys.stderr)
        return EXIT_BAD_INPUT
    try:
        prism = read_side(args.prism, "prism")
        mits = read_side(args.mitsuba, "mitsuba")
        if len(args.prism) < 16 or len(args.mitsuba) < 16:
            print(f"warning: K = {len(args.prism)} prism, {len(args.mitsuba)} mitsuba renders; "
                  "16 or more per side are recommended", file=sys.stderr)
        res = compare(prism, mits, alpha=args.alpha, min_pass=min_pass, bias=args.bias)
    except BadInput as e:
        print(f"error: {e}", file=sys.stderr)
        print(f"BAD INPUT {args.name}")
        return EXIT_BAD_INPUT

    h, w = prism.shape[1:3]
    print(f"{args.name}: {w}x{h}, K = {prism.shape[0]} prism / {mits.shape[0]} mitsuba renders, "
          f"alpha {args.alpha:g}, Sidak threshold {res['sidak']:.3e}")
    out_dir = args.out or (None if res["passed"] else f"compare_{args.name}")
    if out_dir:
        files = write_outputs(res, out_dir, args.name)
        print(f"wrote {len(files)} images to {out_dir}/ ({args.name}_*.exr, *.png)")
    report(res, args.name)
    return EXIT_PASS if res["passed"] else EXIT_FAIL


if __name__ == "__main__":
    sys.exit(main())
