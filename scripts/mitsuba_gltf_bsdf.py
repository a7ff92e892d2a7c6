#!/usr/bin/env python3
"""glTF 2.0 metallic-roughness as a Mitsuba 3 BSDF plugin, `gltf_metallic_roughness`.

Written from the glTF 2.0 specification's Appendix B ("BRDF Implementation"), not from
Prism's code, so that the live Mitsuba check judges Prism's reading of it independently:

    material        = mix(dielectric_brdf, metal_brdf, metallic)
    metal_brdf      = conductor_fresnel(f0 = baseColor, bsdf = specular_brdf(alpha))
    dielectric_brdf = fresnel_mix(ior, base = diffuse_brdf(baseColor), layer = specular_brdf(alpha))
    alpha           = roughness^2

    specular_brdf   = V * D with the GGX (Trowbridge-Reitz) D,
        D = alpha^2 chi+(N.H) / (pi ((N.H)^2 (alpha^2 - 1) + 1)^2),
      and the separable Smith visibility V = G1(L) G1(V) / (4 |N.L| |N.V|),
        G1(X) = 2 |N.X| chi+(H.X / N.X) / (|N.X| + sqrt(alpha^2 + (1 - alpha^2) (N.X)^2))
    diffuse_brdf    = baseColor / pi
    conductor_fresnel(f0, bsdf) = bsdf * (f0 + (1 - f0) (1 - |V.H|)^5)
    fresnel_mix(ior, base, layer) = mix(base, layer, f0 + (1 - f0) (1 - |V.H|)^5),
        f0 = ((1 - ior) / (1 + ior))^2  (ior = 1.5 unless KHR_materials_ior says otherwise)

With KHR_materials_specular, KHR_materials_transmission (thin-walled: no
KHR_materials_volume) and KHR_materials_clearcoat, from those extensions' specifications:

    dielectric_brdf = F * specular_brdf(alpha) + (1 - max_value(F)) * base,
        base = mix(diffuse_brdf(baseColor), specular_btdf(alpha) * baseColor, transmission),
        F    = mix(f0, f90, (1 - |V.H|)^5) (RGB), f0 = min(f0_ior * specularColor, 1) * specular,
               f90 = specular (specular = 1 and specularColor = 1 without the extension give
               Appendix B's fresnel_mix)
    specular_btdf   = specular_brdf with L mirrored through the surface (L' = L - 2 N (N.L)):
                      thin-walled transmission leaves straight through, blurred by the roughness,
                      and its Fresnel is read at V.H' with H' the half vector of V and L'
    coated_material = mix(material, clearcoat_brdf, clearcoat * fr(0.04, |N.V|)),
        clearcoat_brdf = specular_brdf(alpha = clearcoatRoughness^2)

Parameters (as glTF's pbrMetallicRoughness writes them; a texture multiplies its factor):
    base_color_factor (rgb, linear, default 1), base_color_texture (texture, optional; a
    `bitmap` decoded from sRGB), metallic (float, default 1), roughness (float, default 1),
    metallic_roughness_texture (texture, optional; a linear `bitmap`: blue multiplies
    metallic, green multiplies roughness), ior (float, default 1.5), specular (float, default
    1), specular_color (rgb, default 1), transmission, clearcoat, clearcoat_roughness (floats,
    default 0).
The surface scatters alike from both sides (the shading frame is flipped to the viewer's
side), as Prism's path integrator reads glTF surfaces. Factors and products are clamped to
0..1 as glTF's ranges are. alpha is kept above 1e-4 so that a roughness of 0 stays finite.

Sampling picks the diffuse lobe (cosine-weighted), the specular lobe (GGX visible
normals), the transmission lobe (the specular lobe's direction mirrored through the surface)
or the coat's lobe with probabilities estimated from the Fresnel weights at N.V; eval and
pdf are the full model and the mixture density, which is all Mitsuba's path integrator needs.

Usage: import this module (after mi.set_variant) and call register(); the JIT variants
(llvm_ad_rgb) run it fast, scalar_rgb calls Python per sample. Run as a script to check it:
    python3 scripts/mitsuba_gltf_bsdf.py [--variant llvm_ad_rgb]
runs a chi-square test of the sampling against pdf, an eval/pdf consistency check (the
sampled estimate of the directional albedo equals a quadrature of eval) and a furnace
bound (a white metal never reflects more than it receives).
"""

import re
import sys

import drjit as dr
import mitsuba as mi

PLUGIN_NAME = "gltf_metallic_roughness"
MIN_ALPHA = 1e-4


def _optional_texture(props, name):
    if name in props:
        value = props[name]
        if isinstance(value, mi.Texture):
            return value
        raise ValueError(f"{PLUGIN_NAME}: `{name}` must be a texture")
    return None


def _color(props, name, default):
    if name not in props:
        return mi.ScalarColor3f(default)
    value = props[name]
    if isinstance(value, mi.Texture):
        raise ValueError(f"{PLUGIN_NAME}: `{name}` must be an rgb value (a texture goes in *_texture)")
    return mi.ScalarColor3f(value)


def _schlick(f0, cos):
    """Schlick's Fresnel f0 + (1 - f0)(1 - cos)^5."""
    m = dr.clip(1.0 - cos, 0.0, 1.0)
    m2 = m * m
    return f0 + (1.0 - f0) * (m2 * m2 * m)


def _plugin_class():
    """The plugin class; mi.BSDF depends on the variant, so it is made after set_variant."""

    class GltfMetallicRoughness(mi.BSDF):
        """glTF 2.0 Appendix B metallic-roughness BRDF (see the module's docstring)."""

        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.base_color_factor = _color(props, "base_color_factor", 1.0)
            self.base_color_texture = _optional_texture(props, "base_color_texture")
            self.metallic = float(props.get("metallic", 1.0))
            self.roughness = float(props.get("roughness", 1.0))
            self.metallic_roughness_texture = _optional_texture(props, "metallic_roughness_texture")
            self.ior = float(props.get("ior", 1.5))
            self.specular = float(props.get("specular", 1.0))
            self.specular_color = _color(props, "specular_color", 1.0)
            self.transmission = float(props.get("transmission", 0.0))
            self.clearcoat = float(props.get("clearcoat", 0.0))
            self.clearcoat_roughness = float(props.get("clearcoat_roughness", 0.0))
            sides = mi.BSDFFlags.FrontSide | mi.BSDFFlags.BackSide
            diffuse = mi.BSDFFlags.DiffuseReflection | sides
            glossy = mi.BSDFFlags.GlossyReflection | sides
            through = mi.BSDFFlags.GlossyTransmission | sides
            self.m_components = [diffuse, glossy, through, glossy]
            self.m_flags = diffuse | glossy | through

        # Parameters at a surface point ----------------------------------------------------
        def _params(self, si, active):
            base = mi.Color3f(self.base_color_factor)
            if self.base_color_texture is not None:
                base = base * self.base_color_texture.eval(si, active)
            base = dr.clip(base, 0.0, 1.0)
            metallic = mi.Float(self.metallic)
            roughness = mi.Float(self.roughness)
            if self.metallic_roughness_texture is not None:
                t = self.metallic_roughness_texture.eval(si, active)
                roughness = roughness * t[1]
                metallic = metallic * t[2]
            metallic = dr.clip(metallic, 0.0, 1.0)
            roughness = dr.clip(roughness, 0.0, 1.0)
            alpha = dr.maximum(roughness * roughness, MIN_ALPHA)
            return base, metallic, alpha

        def _f0_dielectric(self):
            return ((1.0 - self.ior) / (1.0 + self.ior)) ** 2

        def _dielectric_fresnel(self, cos):
            """KHR_materials_specular's Fresnel F (RGB) at cos = |V.H|."""
            f0 = dr.minimum(self._f0_dielectric() * mi.Color3f(self.specular_color), 1.0) * self.specular
            m = dr.clip(1.0 - dr.abs(cos), 0.0, 1.0)
            return dr.lerp(f0, mi.Color3f(self.specular), m * m * m * m * m)

        @staticmethod
        def _upper(si, wo):
            """Both directions flipped to the viewer's side (two-sided scattering)."""
            flip = mi.Frame3f.cos_theta(si.wi) < 0.0
            sign = dr.select(flip, -1.0, 1.0)
            wi = mi.Vector3f(si.wi.x, si.wi.y, si.wi.z * sign)
            wo = mi.Vector3f(wo.x, wo.y, wo.z * sign)
            return wi, wo

        # The model, from the specification --------------------------------------------------
        @staticmethod
        def _d(alpha, n_h):
            a2 = alpha * alpha
            t = n_h * n_h * (a2 - 1.0) + 1.0
            return dr.select(n_h > 0.0, a2 / (dr.pi * t * t), 0.0)

        @staticmethod
        def _g1(alpha, n_x, h_x):
            a2 = alpha * alpha
            n = dr.abs(n_x)
            g = 2.0 * n / (n + dr.sqrt(a2 + (1.0 - a2) * n_x * n_x))
            return dr.select(h_x * n_x > 0.0, g, 0.0)

        def _specular(self, alpha, v, l):
            """specular_brdf times |N.L| for V = v and L = l above the surface, and V.H."""
            h = dr.normalize(v + l)
            v_h, l_h = dr.dot(v, h), dr.dot(l, h)
            vis = self._g1(alpha, v.z, v_h) * self._g1(alpha, l.z, l_h) / (4.0 * dr.abs(l.z) * dr.abs(v.z))
            return vis * self._d(alpha, h.z) * dr.abs(l.z), v_h

        def _coat_weight(self, n_v):
            return self.clearcoat * _schlick(0.04, dr.abs(n_v))

        def _coat_alpha(self):
            return max(self.clearcoat_roughness * self.clearcoat_roughness, MIN_ALPHA)

        def _eval_local(self, base, metallic, alpha, wi, wo):
            """f(V = wi, L = wo) |N.L| with V above the surface, L on either side."""
            n_v = wi.z
            above = wo.z > 0.0
            # Thin-walled transmission: the reflection lobe's formulas at L mirrored.
            l = mi.Vector3f(wo.x, wo.y, dr.abs(wo.z))
            specular, v_h = self._specular(alpha, wi, l)
            fr = self._dielectric_fresnel(v_h)
            fr_max = dr.maximum(dr.maximum(fr[0], fr[1]), fr[2])
            diffuse = base * dr.inv_pi * l.z
            base_part = dr.select(above, diffuse * (1.0 - self.transmission), base * specular * self.transmission)
            layer = dr.select(above, specular, 0.0)
            dielectric = fr * layer + (1.0 - fr_max) * base_part
            metal = dr.select(above, specular, 0.0) * _schlick(base, dr.abs(v_h))
            material = dr.lerp(dielectric, metal, metallic)
            coat, _ = self._specular(self._coat_alpha(), wi, l)
            f = dr.lerp(material, mi.Color3f(dr.select(above, coat, 0.0)), self._coat_weight(n_v))
            valid = (n_v > 0.0) & (wo.z != 0.0)
            return dr.select(valid, f, 0.0)

        # Sampling ---------------------------------------------------------------------------
        def _lobe_probabilities(self, base, metallic, n_v):
            """Probabilities of the diffuse, specular, transmission and coat lobes."""
            fr = self._dielectric_fresnel(n_v)
            fd = dr.maximum(dr.maximum(fr[0], fr[1]), fr[2])
            fm = _schlick(base, n_v)
            fm_mean = (fm[0] + fm[1] + fm[2]) / 3.0
            base_mean = (base[0] + base[1] + base[2]) / 3.0
            coat = self._coat_weight(n_v)
            w_spec = (1.0 - coat) * dr.maximum(metallic * fm_mean + (1.0 - metallic) * fd, 0.05)
            w_base = (1.0 - coat) * (1.0 - metallic) * (1.0 - fd) * base_mean
            w_diff, w_through = w_base * (1.0 - self.transmission), w_base * self.transmission
            total = w_diff + w_spec + w_through + coat
            return w_diff / total, w_spec / total, w_through / total, coat / total

        def _glossy_pdf(self, alpha, v, l):
            """Density of the GGX visible-normal reflection of v giving l (both above)."""
            h = dr.normalize(v + l)
            v_h, l_h = dr.dot(v, h), dr.dot(l, h)
            pdf_h = self._g1(alpha, v.z, v_h) * dr.abs(v_h) * self._d(alpha, h.z) / v.z
            return dr.select(l.z > 0.0, pdf_h / (4.0 * dr.abs(l_h)), 0.0)

        def _pdf_local(self, base, metallic, alpha, wi, wo):
            n_v = wi.z
            p_diff, p_spec, p_through, p_coat = self._lobe_probabilities(base, metallic, n_v)
            above = wo.z > 0.0
            l = mi.Vector3f(wo.x, wo.y, dr.abs(wo.z))
            glossy = self._glossy_pdf(alpha, wi, l)
            coat = self._glossy_pdf(self._coat_alpha(), wi, l)
            pdf_above = p_diff * l.z * dr.inv_pi + p_spec * glossy + p_coat * coat
            pdf = dr.select(above, pdf_above, p_through * glossy)
            return dr.select((n_v > 0.0) & (wo.z != 0.0), pdf, 0.0)

        def sample(self, ctx, si, sample1, sample2, active=True):
            base, metallic, alpha = self._params(si, active)
            wi, _ = self._upper(si, si.wi)
            flip = mi.Frame3f.cos_theta(si.wi) < 0.0
            p_diff, p_spec, p_through, _ = self._lobe_probabilities(base, metallic, wi.z)
            pick_diff = sample1 < p_diff
            pick_spec = ~pick_diff & (sample1 < p_diff + p_spec)
            pick_through = ~pick_diff & ~pick_spec & (sample1 < p_diff + p_spec + p_through)
            pick_coat = ~pick_diff & ~pick_spec & ~pick_through
            lobe_alpha = dr.select(pick_coat, self._coat_alpha(), alpha)
            distribution = mi.MicrofacetDistribution(mi.MicrofacetType.GGX, lobe_alpha, True)
            m, _ = distribution.sample(wi, sample2)
            wo_glossy = mi.reflect(wi, m)
            wo_diff = mi.warp.square_to_cosine_hemisphere(sample2)
            wo = dr.select(pick_diff, wo_diff, wo_glossy)
            wo = dr.select(pick_through, mi.Vector3f(wo.x, wo.y, -wo.z), wo)
            value = self._eval_local(base, metallic, alpha, wi, wo)
            pdf = self._pdf_local(base, metallic, alpha, wi, wo)
            # A glossy reflection below the surface (or its mirror above it) is no sample.
            sampled_side = dr.select(pick_through, wo.z < 0.0, wo.z > 0.0)
            ok = active & (wi.z > 0.0) & sampled_side & (pdf > 0.0)
            bs = mi.BSDFSample3f()
            bs.wo = mi.Vector3f(wo.x, wo.y, dr.select(flip, -wo.z, wo.z))
            bs.pdf = dr.select(ok, pdf, 0.0)
            bs.eta = 1.0
            bs.sampled_component = dr.select(
                pick_diff, mi.UInt32(0), dr.select(pick_spec, mi.UInt32(1), dr.select(pick_through, mi.UInt32(2), mi.UInt32(3)))
            )
            reflection = dr.select(
                pick_diff, mi.UInt32(+mi.BSDFFlags.DiffuseReflection), mi.UInt32(+mi.BSDFFlags.GlossyReflection)
            )
            bs.sampled_type = dr.select(pick_through, mi.UInt32(+mi.BSDFFlags.GlossyTransmission), reflection)
            weight = dr.select(ok, value / dr.maximum(pdf, 1e-30), 0.0)
            return bs, weight

        def eval(self, ctx, si, wo, active=True):
            base, metallic, alpha = self._params(si, active)
            wi, wo = self._upper(si, wo)
            return dr.select(active, self._eval_local(base, metallic, alpha, wi, wo), 0.0)

        def pdf(self, ctx, si, wo, active=True):
            base, metallic, alpha = self._params(si, active)
            wi, wo = self._upper(si, wo)
            return dr.select(active, self._pdf_local(base, metallic, alpha, wi, wo), 0.0)

        def eval_pdf(self, ctx, si, wo, active=True):
            base, metallic, alpha = self._params(si, active)
            wi, wo = self._upper(si, wo)
            value = self._eval_local(base, metallic, alpha, wi, wo)
            pdf = self._pdf_local(base, metallic, alpha, wi, wo)
            return dr.select(active, value, 0.0), dr.select(active, pdf, 0.0)

        def traverse(self, callback):
            flags = +mi.ParamFlags.NonDifferentiable
            callback.put("base_color_factor", self.base_color_factor, flags)
            callback.put("metallic", self.metallic, flags)
            callback.put("roughness", self.roughness, flags)
            callback.put("ior", self.ior, flags)
            callback.put("specular", self.specular, flags)
            callback.put("specular_color", self.specular_color, flags)
            callback.put("transmission", self.transmission, flags)
            callback.put("clearcoat", self.clearcoat, flags)
            callback.put("clearcoat_roughness", self.clearcoat_roughness, flags)
            for name in ("base_color_texture", "metallic_roughness_texture"):
                texture = getattr(self, name)
                if texture is not None:
                    callback.put(name, texture, flags)

        def to_string(self):
            return (
                f"GltfMetallicRoughness[base_color_factor={self.base_color_factor}, "
                f"metallic={self.metallic}, roughness={self.roughness}, ior={self.ior}, "
                f"specular={self.specular}, specular_color={self.specular_color}, "
                f"transmission={self.transmission}, clearcoat={self.clearcoat}, "
                f"clearcoat_roughness={self.clearcoat_roughness}, "
                f"base_color_texture={self.base_color_texture is not None}, "
                f"metallic_roughness_texture={self.metallic_roughness_texture is not None}]"
            )

    return GltfMetallicRoughness


def register():
    """Registers `gltf_metallic_roughness` with Mitsuba (call after mi.set_variant)."""
    plugin = _plugin_class()
    mi.register_bsdf(PLUGIN_NAME, lambda props: plugin(props))


# The Mitsuba variant of a scene ------------------------------------------------------------
# Scenes without this plugin render in scalar_rgb (Mitsuba's reference, no compiler needed).
# A Python BSDF in scalar_rgb is called per sample from Python (hours for 16 x 256 spp), so
# scenes that use it render in llvm_ad_rgb, where the plugin is traced once into a compiled
# kernel (needs LLVM: Debian's libllvm19).
JIT_VARIANT = "llvm_ad_rgb"
SCALAR_VARIANT = "scalar_rgb"


def variant_for(xml_path):
    """The Mitsuba variant that renders the scene file `xml_path`: the JIT variant for scenes
    that use this plugin, and for scenes with a non-box pixel filter, because the scalar
    variants splat with a discretised filter (`eval_discretized`: MI_FILTER_RESOLUTION = 31
    steps over the radius, each the value at its inner end), a slightly wider filter than the
    one named, which a 32-seed comparison sees at every sharp edge; the JIT variants evaluate
    the filter exactly, as Prism does."""
    with open(xml_path, encoding="utf-8") as f:
        text = f.read()
    exact_filter_needed = re.search(r'<rfilter type="(?!box")', text) is not None
    return JIT_VARIANT if f'type="{PLUGIN_NAME}"' in text or exact_filter_needed else SCALAR_VARIANT


def prepare(xml_path, variant="auto"):
    """Sets the variant for `xml_path` (`auto`: variant_for) and registers the plugin in it;
    returns the variant's name. Call before mi.load_file."""
    chosen = variant_for(xml_path) if variant == "auto" else variant
    mi.set_variant(chosen)
    register()
    return chosen


# Self-checks ---------------------------------------------------------------------------
def _bsdf(metallic, roughness, base=(0.8, 0.5, 0.2), ior=1.5, extensions=None):
    extensions = {k: mi.ScalarColor3f(v) if isinstance(v, tuple) else v for k, v in (extensions or {}).items()}
    return mi.load_dict({
        "type": PLUGIN_NAME,
        "base_color_factor": mi.ScalarColor3f(base),
        "metallic": metallic,
        "roughness": roughness,
        "ior": ior,
        **extensions,
    })


def _directional_albedo(bsdf, wi, n):
    """(sampled mean of eval/pdf, quadrature of eval over the hemisphere), channel 0..2."""
    import numpy as np

    si = dr.zeros(mi.SurfaceInteraction3f)
    si.wi = mi.Vector3f(wi)
    ctx = mi.BSDFContext()
    sampler = mi.load_dict({"type": "independent"})
    sampler.seed(1, n)
    bs, weight = bsdf.sample(ctx, si, sampler.next_1d(), sampler.next_2d())
    sampled = np.array(weight).reshape(3, -1).mean(axis=1) if dr.width(weight) > 1 else np.array(weight)
    # Quadrature: stratified uniform hemisphere directions, eval / (1 / 2 pi), above the
    # surface and mirrored below it (where transmission leaves).
    side = int(np.sqrt(n))
    u = (np.arange(side) + 0.5) / side
    uu, vv = np.meshgrid(u, u)
    wo = mi.warp.square_to_uniform_hemisphere(mi.Point2f(uu.ravel(), vv.ravel()))
    si_q = dr.zeros(mi.SurfaceInteraction3f, side * side)
    si_q.wi = mi.Vector3f(wi)
    quadrature = 0.0
    for below in (False, True):
        direction = mi.Vector3f(wo.x, wo.y, -wo.z) if below else wo
        value = bsdf.eval(ctx, si_q, direction)
        quadrature = quadrature + np.array(value).reshape(3, -1).mean(axis=1) * 2.0 * np.pi
    return sampled, quadrature


def self_check():
    """Chi-square, eval/pdf consistency and furnace checks; returns the number of failures."""
    import numpy as np
    from mitsuba import chi2

    failures = 0
    # The chi-square histogram (64 x 128 cells) resolves lobes of alpha >= 0.2; sharper ones
    # are checked by the albedo comparison only.
    # The extensions: thin-walled transmission, a clear coat, both over a half metal.
    cases = [(m, r, {}) for m, r in [(0.0, 0.2), (0.0, 0.5), (0.5, 0.5), (1.0, 0.3), (1.0, 0.5), (0.0, 1.0), (0.3, 0.7)]]
    cases += [
        (0.0, 0.5, {"transmission": 0.8}),
        (0.0, 0.7, {"transmission": 1.0, "ior": 1.2}),
        (0.2, 0.6, {"clearcoat": 1.0, "clearcoat_roughness": 0.5}),
        (0.3, 0.5, {"transmission": 0.6, "clearcoat": 0.5, "clearcoat_roughness": 0.6}),
        (0.0, 0.4, {"specular": 0.4, "specular_color": (1.5, 0.6, 0.2), "transmission": 0.5}),
    ]
    for metallic, roughness, extensions in cases:
        params = (
            f'<rgb name="base_color_factor" value="0.8, 0.5, 0.2"/><float name="metallic" value="{metallic}"/>'
            f'<float name="roughness" value="{roughness}"/>'
        ) + "".join(
            f'<rgb name="{k}" value="{", ".join(map(str, v))}"/>' if isinstance(v, tuple) else f'<float name="{k}" value="{v}"/>'
            for k, v in extensions.items()
        )
        ior = extensions.pop("ior", 1.5)
        for theta in [10.0, 45.0, 80.0]:
            t = np.radians(theta)
            wi = [float(np.sin(t)), 0.0, float(np.cos(t))]
            sample_func, pdf_func = chi2.BSDFAdapter(PLUGIN_NAME, params, wi=wi)
            test = chi2.ChiSquareTest(
                domain=chi2.SphericalDomain(), sample_func=sample_func, pdf_func=pdf_func, sample_dim=3,
                sample_count=200_000, res=64,
            )
            ok = roughness * roughness < 0.2 or test.run()
            print(f"chi2 metallic {metallic} roughness {roughness} {extensions} theta {theta}: {'ok' if ok else 'FAIL'}")
            failures += 0 if ok else 1
            bsdf = _bsdf(metallic, roughness, ior=ior, extensions=extensions)
            sampled, quadrature = _directional_albedo(bsdf, wi, 1 << 20)
            close = np.allclose(sampled, quadrature, rtol=0.02, atol=2e-3)
            print(f"  albedo sampled {np.round(sampled, 4)} quadrature {np.round(quadrature, 4)}: {'ok' if close else 'FAIL'}")
            failures += 0 if close else 1
    # Furnace: a white metal (conductor_fresnel with f0 = 1 is 1) is a GGX mirror that
    # loses energy to masking only: its albedo is at most 1 and near 1 at low roughness.
    for roughness in [0.1, 0.5, 1.0]:
        for theta in [0.0, 60.0]:
            t = np.radians(theta)
            wi = [float(np.sin(t)), 0.0, float(np.cos(t))]
            _, albedo = _directional_albedo(_bsdf(1.0, roughness, base=(1.0, 1.0, 1.0)), wi, 1 << 20)
            ok = albedo.max() <= 1.0 + 2e-3 and (roughness > 0.2 or albedo.min() > 0.97)
            print(f"furnace white metal roughness {roughness} theta {theta}: albedo {albedo[0]:.4f} {'ok' if ok else 'FAIL'}")
            failures += 0 if ok else 1
    return failures


if __name__ == "__main__":
    import argparse

    ap = argparse.ArgumentParser(description="Check the glTF metallic-roughness Mitsuba plugin")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    args = ap.parse_args()
    mi.set_variant(args.variant)
    register()
    bad = self_check()
    print("all checks pass" if bad == 0 else f"{bad} checks FAIL")
    sys.exit(1 if bad else 0)
