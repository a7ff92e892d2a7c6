//! TEMPORARY stand-in for the BSDF module (replaced by the real one before merging).
#![allow(missing_docs, reason = "temporary stand-in")]
use glam::{DVec2, DVec3};

pub struct Frame {
    pub s: DVec3,
    pub t: DVec3,
    pub n: DVec3,
}
impl Frame {
    pub fn new(n: DVec3, hint: DVec3) -> Self {
        let mut s = hint - n * n.dot(hint);
        if s.length_squared() < 1e-20 {
            s = prism_api::math::tangent(n);
        }
        let s = s.normalize();
        Self { s, t: n.cross(s), n }
    }
    pub fn to_local(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }
    pub fn to_world(&self, v: DVec3) -> DVec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

#[derive(Clone, Debug)]
pub enum Bsdf {
    Diffuse {
        reflectance: DVec3,
    },
    Conductor {
        eta: DVec3,
        k: DVec3,
        alpha: f64,
        tint: DVec3,
    },
    Dielectric {
        eta: f64,
        alpha: f64,
        reflect_tint: DVec3,
        transmit_tint: DVec3,
    },
    ThinDielectric {
        eta: f64,
        reflect_tint: DVec3,
        transmit_tint: DVec3,
    },
    Plastic {
        diffuse: DVec3,
        eta: f64,
        alpha: f64,
    },
    MetallicRoughness {
        base_color: DVec3,
        metallic: f64,
        alpha: f64,
        ior: f64,
        transmission: f64,
        clearcoat: f64,
        clearcoat_alpha: f64,
    },
}

pub struct BsdfSample {
    pub wi: DVec3,
    pub weight: DVec3,
    pub pdf: f64,
    pub delta: bool,
}

fn cosine_hemisphere(u: DVec2) -> DVec3 {
    let r = u.x.sqrt();
    let phi = 2.0 * std::f64::consts::PI * u.y;
    DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt())
}

impl Bsdf {
    fn diffuse_color(&self) -> Option<DVec3> {
        match self {
            Bsdf::Diffuse { reflectance } => Some(*reflectance),
            Bsdf::Plastic { diffuse, .. } => Some(*diffuse),
            Bsdf::MetallicRoughness { base_color, .. } => Some(*base_color),
            Bsdf::Conductor { tint, .. } => Some(*tint * 0.9),
            _ => None,
        }
    }
    pub fn eval(&self, wo: DVec3, wi: DVec3) -> DVec3 {
        match self.diffuse_color() {
            Some(c) if wo.z > 0.0 && wi.z > 0.0 => c * wi.z / std::f64::consts::PI,
            _ => DVec3::ZERO,
        }
    }
    pub fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        match self.diffuse_color() {
            Some(_) if wo.z > 0.0 && wi.z > 0.0 => wi.z / std::f64::consts::PI,
            _ => 0.0,
        }
    }
    pub fn sample(&self, wo: DVec3, u_lobe: f64, u: DVec2) -> Option<BsdfSample> {
        if let Bsdf::Dielectric { eta, .. } = self {
            let cos_o = wo.z;
            let (eta_i, eta_t, n) = if cos_o > 0.0 { (1.0, *eta, 1.0) } else { (*eta, 1.0, -1.0) };
            let rel = eta_i / eta_t;
            let c = cos_o.abs();
            let sin2t = rel * rel * (1.0 - c * c);
            let r = if sin2t >= 1.0 {
                1.0
            } else {
                let ct = (1.0 - sin2t).sqrt();
                let rs = (eta_i * c - eta_t * ct) / (eta_i * c + eta_t * ct);
                let rp = (eta_t * c - eta_i * ct) / (eta_t * c + eta_i * ct);
                0.5 * (rs * rs + rp * rp)
            };
            if u_lobe < r {
                return Some(BsdfSample {
                    wi: DVec3::new(-wo.x, -wo.y, wo.z),
                    weight: DVec3::ONE,
                    pdf: r,
                    delta: true,
                });
            }
            let ct = (1.0 - sin2t).sqrt();
            let wi = DVec3::new(-rel * wo.x, -rel * wo.y, -n * ct);
            return Some(BsdfSample { wi, weight: DVec3::splat(rel * rel), pdf: 1.0 - r, delta: true });
        }
        if let Bsdf::ThinDielectric { .. } = self {
            return Some(BsdfSample { wi: -wo, weight: DVec3::ONE, pdf: 1.0, delta: true });
        }
        if wo.z <= 0.0 {
            return None;
        }
        let wi = cosine_hemisphere(u);
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample { wi, weight: self.eval(wo, wi) / pdf, pdf, delta: false })
    }
    pub fn is_delta(&self) -> bool {
        self.diffuse_color().is_none()
    }
    pub fn has_smooth_lobe(&self) -> bool {
        self.diffuse_color().is_some()
    }
    pub fn albedo(&self) -> DVec3 {
        self.diffuse_color().unwrap_or(DVec3::ONE)
    }
}
