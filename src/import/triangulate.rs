//! Polygon triangulation by ear clipping in the polygon's own plane, so concave faces (the
//! Sponza's 78-gons) come out right where a fan would cover the notches.
//!
//! Ear clipping is quadratic, so large polygons take other paths: a strictly convex
//! polygon of more than [`SMALL_POLYGON`] vertices is cut in a zigzag in linear time (a
//! million-vertex face takes well under a second; every vertex keeps at most four
//! triangles, so smoothing stays linear too), and a larger non-convex one is ear-clipped
//! with a linked list that tests only reflex corners, up to [`MAX_CONCAVE_POLYGON`] vertices.

use glam::{DVec2, DVec3};

/// Polygons up to this many vertices are ear-clipped by the simple search (the output of
/// every shipped mesh stays what it always was).
pub const SMALL_POLYGON: usize = 64;

/// Most vertices of a polygon that is not strictly convex (`docs/security.md`): ear
/// clipping costs up to the square of the count.
pub const MAX_CONCAVE_POLYGON: usize = 16_384;

/// A polygon too large to triangulate.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "a face with {vertices} vertices that is not strictly convex: at most {MAX_CONCAVE_POLYGON} vertices are triangulated"
)]
pub struct PolygonTooLarge {
    /// The face's vertex count.
    pub vertices: usize,
}

/// Triangles (as indices into `points`) covering the simple polygon `points`, in the
/// polygon's winding. A polygon with n vertices gives n - 2 triangles unless it is
/// degenerate; self-intersecting or degenerate input still gives n - 2 triangles (the
/// clipping falls back to the most convex corner) so no face silently disappears.
/// A polygon of more than [`MAX_CONCAVE_POLYGON`] vertices must be strictly convex.
pub fn triangulate(points: &[DVec3]) -> Result<Vec<[usize; 3]>, PolygonTooLarge> {
    triangulate_counting(points, &mut 0)
}

/// [`triangulate`], adding to `point_tests` the number of corners the ear clipping checked
/// against a candidate ear (each a point-in-triangle test unless it is one of the ear's own
/// corners): the work that grows with the square of the vertex count, which the tests bound
/// instead of the run time.
fn triangulate_counting(points: &[DVec3], point_tests: &mut u64) -> Result<Vec<[usize; 3]>, PolygonTooLarge> {
    let n = points.len();
    if n < 3 {
        return Ok(Vec::new());
    }
    if n == 3 {
        return Ok(vec![[0, 1, 2]]);
    }
    // Newell's normal is robust for non-planar and concave polygons.
    let mut normal = DVec3::ZERO;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        normal += DVec3::new((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    if normal.length_squared() == 0.0 || !normal.is_finite() {
        return Ok((1..n - 1).map(|i| [0, i, i + 1]).collect());
    }
    // Project onto the plane with a basis that keeps the winding counter-clockwise.
    let (u, v) = prism_api::math::orthonormal_basis(normal.normalize());
    let mut p: Vec<DVec2> = points.iter().map(|q| DVec2::new(q.dot(u), q.dot(v))).collect();
    let signed_area: f64 = (0..n).map(|i| p[i].perp_dot(p[(i + 1) % n])).sum();
    if signed_area < 0.0 {
        p.iter_mut().for_each(|q| q.y = -q.y);
    }
    if n <= SMALL_POLYGON {
        return Ok(ear_clip(&p, point_tests));
    }
    if strictly_convex(&p) {
        return Ok(zigzag(n));
    }
    if n > MAX_CONCAVE_POLYGON {
        return Err(PolygonTooLarge { vertices: n });
    }
    Ok(ear_clip_linked(&p, point_tests))
}

/// True when every corner of the counter-clockwise polygon `p` turns left and the turns add
/// up to one full turn (a polygon winding twice around a point turns left everywhere too).
fn strictly_convex(p: &[DVec2]) -> bool {
    let n = p.len();
    let mut turning = 0.0;
    for i in 0..n {
        let (a, b, c) = (p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
        let (d0, d1) = (b - a, c - b);
        let turn = d0.perp_dot(d1);
        if turn <= 0.0 || !turn.is_finite() {
            return false;
        }
        turning += turn.atan2(d0.dot(d1));
    }
    (turning - std::f64::consts::TAU).abs() < 1e-6
}

/// A convex polygon of `n` vertices cut into a zigzag strip between its two halves:
/// counter-clockwise triangles, each vertex in at most four.
fn zigzag(n: usize) -> Vec<[usize; 3]> {
    let mut out = Vec::with_capacity(n - 2);
    // `lo` walks forwards from 0, `hi` backwards from n - 1; (lo, lo + 1, hi) and
    // (lo + 1, hi - 1, hi) alternate.
    let (mut lo, mut hi) = (0, n - 1);
    let mut forward = true;
    while hi - lo >= 2 {
        if forward {
            out.push([lo, lo + 1, hi]);
            lo += 1;
        } else {
            out.push([lo, hi - 1, hi]);
            hi -= 1;
        }
        forward = !forward;
    }
    out
}

fn cross(o: DVec2, a: DVec2, b: DVec2) -> f64 {
    (a - o).perp_dot(b - o)
}

/// True when `p` lies inside or on triangle (a, b, c), given counter-clockwise.
fn in_triangle(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0
}

/// Ear clipping of a counter-clockwise 2D polygon, O(n^2) per ear; counts the corners it
/// checks against candidate ears in `point_tests`.
fn ear_clip(p: &[DVec2], point_tests: &mut u64) -> Vec<[usize; 3]> {
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
                *point_tests += 1;
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

/// Ear clipping of a counter-clockwise 2D polygon over a doubly linked list: the search
/// goes on from the last ear instead of starting over, removal is O(1), and only reflex
/// corners (the only ones that can lie inside an ear) are tested against a candidate ear.
/// Counts the corners it checks against candidate ears in `point_tests`.
fn ear_clip_linked(p: &[DVec2], point_tests: &mut u64) -> Vec<[usize; 3]> {
    let n = p.len();
    let mut next: Vec<usize> = (1..=n).map(|i| i % n).collect();
    let mut prev: Vec<usize> = (0..n).map(|i| (i + n - 1) % n).collect();
    let corner = |prev: &[usize], next: &[usize], i: usize| cross(p[prev[i]], p[i], p[next[i]]);
    let mut reflex: Vec<bool> = (0..n).map(|i| corner(&prev, &next, i) <= 0.0).collect();
    let mut reflex_list: Vec<usize> = (0..n).filter(|&i| reflex[i]).collect();
    let mut out = Vec::with_capacity(n - 2);
    let mut remaining = n;
    let mut i = 0;
    // Corners tested since the last clip: a whole round without an ear means none is left.
    let mut tested = 0;
    while remaining > 3 {
        let (i0, i2) = (prev[i], next[i]);
        let (a, b, c) = (p[i0], p[i], p[i2]);
        let is_ear = !reflex[i]
            && cross(a, b, c) > 0.0
            && !reflex_list.iter().any(|&j| {
                *point_tests += 1;
                reflex[j]
                    && j != i0
                    && j != i
                    && j != i2
                    && p[j] != a
                    && p[j] != b
                    && p[j] != c
                    && in_triangle(p[j], a, b, c)
            });
        let clip = if is_ear {
            Some(i)
        } else if tested >= remaining {
            // A whole round without an ear: the rest is degenerate or self-intersecting and
            // has no right answer; a fan keeps its n - 2 triangles in linear time.
            let mut k = next[i];
            while next[k] != i {
                out.push([i, k, next[k]]);
                k = next[k];
            }
            return out;
        } else {
            None
        };
        match clip {
            Some(k) => {
                let (k0, k2) = (prev[k], next[k]);
                out.push([k0, k, k2]);
                next[k0] = k2;
                prev[k2] = k0;
                remaining -= 1;
                reflex[k] = false;
                for j in [k0, k2] {
                    let was = reflex[j];
                    reflex[j] = corner(&prev, &next, j) <= 0.0;
                    if reflex[j] && !was {
                        reflex_list.push(j);
                    }
                }
                if reflex_list.len() > 2 * remaining.max(8) {
                    reflex_list.retain(|&j| reflex[j]);
                }
                tested = 0;
                i = k2;
            }
            None => {
                tested += 1;
                i = next[i];
            }
        }
    }
    out.push([prev[i], i, next[i]]);
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
        let tris = triangulate(&l).unwrap();
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
        let tris = triangulate(&star).unwrap();
        assert_eq!(tris.len(), 22);
        assert!((area(&star, &tris) - polygon_area(&star)).abs() < 1e-9);
    }

    #[test]
    fn degenerate_input_still_gives_n_minus_2() {
        let line: Vec<DVec3> = (0..5).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        assert_eq!(triangulate(&line).unwrap().len(), 3);
        // Repeated vertices.
        let q = [DVec3::ZERO, DVec3::X, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let tris = triangulate(&q).unwrap();
        assert_eq!(tris.len(), 3);
        assert!((area(&q, &tris) - 1.0).abs() < 1e-12);
        assert!(triangulate(&[DVec3::ZERO, DVec3::X]).unwrap().is_empty());
    }

    fn ring(n: usize, radius: impl Fn(usize) -> f64) -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / n as f64;
                DVec3::new(radius(i) * a.cos(), radius(i) * a.sin(), 0.5)
            })
            .collect()
    }

    fn assert_covers(points: &[DVec3], tris: &[[usize; 3]]) {
        assert_eq!(tris.len(), points.len() - 2);
        let want = polygon_area(points);
        assert!((area(points, tris) - want).abs() < 1e-9 * want, "{} vs {want}", area(points, tris));
        for t in tris {
            assert!((points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).z >= 0.0, "{t:?}");
        }
    }

    #[test]
    fn a_million_vertex_convex_face_is_cut_in_linear_time_and_exactly() {
        let points = ring(1_000_000, |_| 1.0);
        let mut point_tests = 0;
        let tris = triangulate_counting(&points, &mut point_tests).unwrap();
        // Quadratic ear clipping took hours; the zigzag tests no point against a triangle.
        assert_eq!(point_tests, 0);
        assert_covers(&points, &tris);
        let mut valence = vec![0u8; points.len()];
        tris.iter().flatten().for_each(|&v| valence[v] += 1);
        assert!(valence.iter().all(|&v| v <= 4), "zigzag vertices keep at most four triangles");
    }

    #[test]
    fn large_concave_faces_are_ear_clipped_quickly_up_to_the_cap() {
        // A star with 8,192 spikes: half its corners are reflex (each tip is tested against them all).
        let star = ring(MAX_CONCAVE_POLYGON, |i| if i % 2 == 0 { 2.0 } else { 1.0 });
        let mut point_tests = 0;
        let tris = triangulate_counting(&star, &mut point_tests).unwrap();
        // Each tip is tested against the reflex corners left, so the work is quadratic (the
        // reason for the cap) but no worse: under half the square of the count (about 0.38
        // of it here; a search that went round the polygon again for every ear would be
        // cubic).
        let n = MAX_CONCAVE_POLYGON as u64;
        assert!(point_tests <= n * n / 2, "{point_tests} point-in-triangle tests");
        assert_covers(&star, &tris);
        // An L with a long, finely divided edge (many collinear corners, one notch).
        let mut l: Vec<DVec3> = (0..=1000).map(|i| DVec3::new(2.0 * i as f64 / 1000.0, 0.0, 0.0)).collect();
        l.extend([(2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)].map(|(x, y)| DVec3::new(x, y, 0.0)));
        assert_covers(&l, &triangulate(&l).unwrap());
        let too_many = ring(MAX_CONCAVE_POLYGON + 2, |i| if i % 2 == 0 { 2.0 } else { 1.0 });
        let e = triangulate(&too_many).unwrap_err();
        assert_eq!(e, PolygonTooLarge { vertices: MAX_CONCAVE_POLYGON + 2 });
        assert!(e.to_string().contains("16386 vertices"), "{e}");
    }

    #[test]
    fn large_self_intersecting_faces_still_give_n_minus_2() {
        // A polygon winding twice around the origin turns left at every corner.
        let twice: Vec<DVec3> = (0..1001)
            .map(|i| {
                let a = i as f64 * 2.0 * std::f64::consts::TAU / 1001.0;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        assert_eq!(triangulate(&twice).unwrap().len(), 999);
    }
}
