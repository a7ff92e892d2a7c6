//! Polygon triangulation by ear clipping in the polygon's own plane, so concave faces (the
//! Sponza's 78-gons) come out right where a fan would cover the notches.

use glam::{DVec2, DVec3};

/// Triangles (as indices into `points`) covering the simple polygon `points`, in the
/// polygon's winding. A polygon with n vertices gives n - 2 triangles unless it is
/// degenerate; self-intersecting or degenerate input still gives n - 2 triangles (the
/// clipping falls back to the most convex corner) so no face silently disappears.
pub fn triangulate(points: &[DVec3]) -> Vec<[usize; 3]> {
    let n = points.len();
    if n < 3 {
        return Vec::new();
    }
    if n == 3 {
        return vec![[0, 1, 2]];
    }
    // Newell's normal is robust for non-planar and concave polygons.
    let mut normal = DVec3::ZERO;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        normal += DVec3::new((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    if normal.length_squared() == 0.0 || !normal.is_finite() {
        return (1..n - 1).map(|i| [0, i, i + 1]).collect();
    }
    // Project onto the plane with a basis that keeps the winding counter-clockwise.
    let (u, v) = prism_api::math::orthonormal_basis(normal.normalize());
    let mut p: Vec<DVec2> = points.iter().map(|q| DVec2::new(q.dot(u), q.dot(v))).collect();
    let signed_area: f64 = (0..n).map(|i| p[i].perp_dot(p[(i + 1) % n])).sum();
    if signed_area < 0.0 {
        p.iter_mut().for_each(|q| q.y = -q.y);
    }
    ear_clip(&p)
}

fn cross(o: DVec2, a: DVec2, b: DVec2) -> f64 {
    (a - o).perp_dot(b - o)
}

/// True when `p` lies inside or on triangle (a, b, c), given counter-clockwise.
fn in_triangle(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0
}

/// Ear clipping of a counter-clockwise 2D polygon, O(n^2) per ear.
fn ear_clip(p: &[DVec2]) -> Vec<[usize; 3]> {
    let mut remaining: Vec<usize> = (0..p.len()).collect();
    let mut out = Vec::with_capacity(p.len() - 2);
    while remaining.len() > 3 {
        let m = remaining.len();
        let mut ear = None;
        for k in 0..m {
            let (i0, i1, i2) = (remaining[(k + m - 1) % m], remaining[k], remaining[(k + 1) % m]);
            let (a, b, c) = (p[i0], p[i1], p[i2]);
            if cross(a, b, c) <= 0.0 {
                continue; // reflex or collinear corner
            }
            let blocked = remaining.iter().any(|&j| {
                j != i0 && j != i1 && j != i2 && p[j] != a && p[j] != b && p[j] != c && in_triangle(p[j], a, b, c)
            });
            if !blocked {
                ear = Some(k);
                break;
            }
        }
        // No proper ear (degenerate or self-intersecting input): clip the most convex corner.
        let k = ear.unwrap_or_else(|| {
            (0..m)
                .max_by(|&x, &y| {
                    let c = |k: usize| cross(p[remaining[(k + m - 1) % m]], p[remaining[k]], p[remaining[(k + 1) % m]]);
                    c(x).total_cmp(&c(y))
                })
                .unwrap_or(0)
        });
        out.push([remaining[(k + m - 1) % m], remaining[k], remaining[(k + 1) % m]]);
        remaining.remove(k);
    }
    out.push([remaining[0], remaining[1], remaining[2]]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(points: &[DVec3], tris: &[[usize; 3]]) -> f64 {
        tris.iter().map(|t| 0.5 * (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).length()).sum()
    }

    fn polygon_area(points: &[DVec3]) -> f64 {
        let mut n = DVec3::ZERO;
        for i in 0..points.len() {
            n += points[i].cross(points[(i + 1) % points.len()]);
        }
        0.5 * n.length()
    }

    #[test]
    fn concave_l_shape_is_covered_exactly() {
        // An L: a fan from vertex 0 would put a triangle across the notch.
        let l: Vec<DVec3> = [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)]
            .iter()
            .map(|&(x, y)| DVec3::new(x, y, 0.0))
            .collect();
        let tris = triangulate(&l);
        assert_eq!(tris.len(), 4);
        assert!((area(&l, &tris) - 3.0).abs() < 1e-12, "{tris:?}");
        // Every triangle keeps the polygon's winding.
        for t in &tris {
            assert!((l[t[1]] - l[t[0]]).cross(l[t[2]] - l[t[0]]).z > 0.0);
        }
    }

    #[test]
    fn concave_star_in_a_tilted_plane_clockwise() {
        // A 12-pointed star, clockwise, in a tilted plane.
        let tilt = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.7, -0.4, 1.9);
        let star: Vec<DVec3> = (0..24)
            .rev()
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 24.0;
                let r = if i % 2 == 0 { 2.0 } else { 0.7 };
                tilt * DVec3::new(r * a.cos(), r * a.sin(), 0.0) + DVec3::new(3.0, -1.0, 2.0)
            })
            .collect();
        let tris = triangulate(&star);
        assert_eq!(tris.len(), 22);
        assert!((area(&star, &tris) - polygon_area(&star)).abs() < 1e-9);
    }

    #[test]
    fn degenerate_input_still_gives_n_minus_2() {
        let line: Vec<DVec3> = (0..5).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        assert_eq!(triangulate(&line).len(), 3);
        // Repeated vertices.
        let q = [DVec3::ZERO, DVec3::X, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let tris = triangulate(&q);
        assert_eq!(tris.len(), 3);
        assert!((area(&q, &tris) - 1.0).abs() < 1e-12);
        assert!(triangulate(&[DVec3::ZERO, DVec3::X]).is_empty());
    }
}
