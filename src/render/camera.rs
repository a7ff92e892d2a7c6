//! The pinhole / thin-lens and orthographic cameras, with POV-Ray's pixel convention: pixel
//! (i, j) at sub-pixel position (sx, sy) maps to x0 = (i + sx)/W - 0.5, y0 = 0.5 - (j + sy)/H;
//! a perspective ray's direction is normalize(D + x0 R + y0 U), an orthographic ray starts
//! at E + x0 R + y0 U and runs along D (POV-Ray's `orthographic`).

use glam::{DVec2, DVec3};
use prism_api::Ray;

use crate::world::components::{Camera, Projection};

/// A camera ready to make rays.
#[derive(Clone, Debug)]
pub struct RenderCamera {
    /// Eye position.
    pub position: DVec3,
    /// Unit viewing direction (POV-Ray's `direction`, length 1).
    pub direction: DVec3,
    /// Full viewport width vector (POV-Ray's `right`): at distance 1 for a perspective
    /// camera, in scene units for an orthographic one.
    pub right: DVec3,
    /// Full viewport height vector (POV-Ray's `up`).
    pub up: DVec3,
    /// Rays run parallel to `direction` from points on the viewport.
    pub orthographic: bool,
    /// Lens diameter (0 = pinhole).
    pub aperture: f64,
    /// Distance of the sharp plane along the view axis.
    pub focal_distance: f64,
    /// Unit `right` and `up`, the lens axes.
    lens_axes: (DVec3, DVec3),
}

/// A camera's orthonormal frame and viewport height, the part that does not depend on the
/// image size (the POV-Ray exporter writes the same numbers the renderer uses).
#[derive(Clone, Copy, Debug)]
pub struct CameraFrame {
    /// Eye position.
    pub position: DVec3,
    /// Unit viewing direction.
    pub direction: DVec3,
    /// Unit vector toward the image's right edge.
    pub right: DVec3,
    /// Unit vector toward the image's top edge.
    pub up: DVec3,
    /// Viewport height (POV-Ray's `up` length): at distance 1 for a perspective camera, in
    /// scene units for an orthographic one.
    pub height: f64,
    /// Distance of the sharp plane along the view axis.
    pub focal_distance: f64,
}

impl CameraFrame {
    /// The frame of `camera`.
    pub fn new(camera: &Camera) -> Self {
        let position = DVec3::from_array(camera.position);
        let look_at = DVec3::from_array(camera.look_at);
        let direction = (look_at - position).normalize();
        let right = direction.cross(DVec3::from_array(camera.up)).normalize();
        let up = right.cross(direction);
        let spread = 2.0 * (camera.vfov.to_radians() * 0.5).tan();
        let distance = (look_at - position).length();
        Self {
            position,
            direction,
            right,
            up,
            height: match camera.projection {
                Projection::Perspective => spread,
                Projection::Orthographic => camera.view_height.unwrap_or(spread * distance),
            },
            focal_distance: camera.focal_distance.unwrap_or(distance),
        }
    }
}

impl RenderCamera {
    /// The camera for an image of `width` x `height` pixels.
    pub fn new(camera: &Camera, width: u32, height: u32) -> Self {
        let frame = CameraFrame::new(camera);
        let aspect = camera.aspect.unwrap_or(f64::from(width) / f64::from(height));
        Self {
            position: frame.position,
            direction: frame.direction,
            right: frame.right * frame.height * aspect,
            up: frame.up * frame.height,
            orthographic: camera.projection == Projection::Orthographic,
            aperture: camera.aperture,
            focal_distance: frame.focal_distance,
            lens_axes: (frame.right, frame.up),
        }
    }

    /// A box holding every camera ray's origin: the lens disc, the orthographic viewport, or
    /// the position.
    pub fn lens_bounds(&self) -> prism_api::Aabb {
        let reach = if self.orthographic {
            0.5 * (self.right.abs() + self.up.abs())
        } else {
            let (x_axis, y_axis) = self.lens_axes;
            0.5 * self.aperture.max(0.0) * (x_axis.abs() + y_axis.abs())
        };
        prism_api::Aabb::from_corners(self.position - reach, self.position + reach)
    }

    /// True when every camera ray starts at `position` (a pinhole).
    pub fn has_single_origin(&self) -> bool {
        !self.orthographic && self.aperture <= 0.0
    }

    /// The ray through image-plane coordinates (x0, y0) in [-0.5, 0.5], through lens point
    /// `lens` on the unit disc.
    pub fn ray(&self, x0: f64, y0: f64, lens: DVec2) -> Ray {
        if self.orthographic {
            return Ray::new(self.position + x0 * self.right + y0 * self.up, self.direction);
        }
        let through = self.direction + x0 * self.right + y0 * self.up;
        if self.aperture <= 0.0 {
            return Ray::new(self.position, through.normalize());
        }
        let (x_axis, y_axis) = self.lens_axes;
        let offset = 0.5 * self.aperture * (lens.x * x_axis + lens.y * y_axis);
        let focus = through * self.focal_distance;
        Ray::new(self.position + offset, (focus - offset).normalize())
    }
}

/// POV-Ray's screen coordinates (x0, y0) in [-0.5, 0.5] of the image position (x, y), where
/// (i, j) is the centre of pixel column i, row j (`TracePixel::CreateCameraRay`, written the
/// way POV-Ray computes it so that both renderers send the same rays).
pub fn pov_screen(x: f64, y: f64, width: f64, height: f64) -> (f64, f64) {
    let (x, y) = (x + 0.5, y - 0.5);
    (x / width - 0.5, ((height - 1.0) - y) / height - 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_camera_matches_pov_ray_vectors() {
        let c = RenderCamera::new(&Camera::default(), 1600, 900);
        assert!((c.direction - DVec3::NEG_Z).length() < 1e-12);
        assert!((c.up - DVec3::new(0.0, 2.0, 0.0)).length() < 1e-12);
        assert!((c.right - DVec3::new(32.0 / 9.0, 0.0, 0.0)).length() < 1e-12);
        let corner = c.ray(0.5, 0.5, DVec2::ZERO);
        assert!(corner.direction.x > 0.0 && corner.direction.y > 0.0, "top right is +x +y");
    }

    #[test]
    fn pov_screen_puts_pixel_centres_at_integers() {
        let (x0, y0) = pov_screen(0.0, 0.0, 8.0, 6.0);
        assert!((x0 - (0.5 / 8.0 - 0.5)).abs() < 1e-15 && (y0 - (0.5 - 0.5 / 6.0)).abs() < 1e-15);
        let (x0, y0) = pov_screen(7.5, 5.5, 8.0, 6.0);
        assert!((x0 - 0.5).abs() < 1e-15 && (y0 + 0.5).abs() < 1e-15, "bottom-right corner");
    }

    #[test]
    fn focal_plane_is_sharp() {
        let camera = Camera { aperture: 0.5, focal_distance: Some(3.0), ..Camera::default() };
        let c = RenderCamera::new(&camera, 100, 100);
        let a = c.ray(0.1, 0.2, DVec2::new(0.7, -0.3));
        let b = c.ray(0.1, 0.2, DVec2::new(-0.5, 0.5));
        // Both rays meet where they cross the plane 3 units along the view axis.
        let ta = (3.0 - (a.origin - c.position).dot(c.direction)) / a.direction.dot(c.direction);
        let tb = (3.0 - (b.origin - c.position).dot(c.direction)) / b.direction.dot(c.direction);
        assert!((a.at(ta) - b.at(tb)).length() < 1e-9);
    }
}
