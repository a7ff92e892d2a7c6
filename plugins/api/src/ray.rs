use glam::DVec3;

/// A ray `origin + t * direction`.
///
/// The direction need not be unit length: Prism transforms world rays into object space
/// without renormalising, so a hit's `t` means the same point in both spaces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: DVec3,
    /// Where the ray goes (not necessarily unit length).
    pub direction: DVec3,
}

impl Ray {
    /// A ray from `origin` along `direction`.
    pub fn new(origin: DVec3, direction: DVec3) -> Self {
        Self { origin, direction }
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.direction
    }
}
