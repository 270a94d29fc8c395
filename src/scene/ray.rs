//! One ray against one triangle: the ray tracer's test (through its bounding
//! volume hierarchy), and the framing's test of whether a model hides its light.

use crate::pipeline::Triangle;
use glam::Vec3;

/// Distance along `dir` (in units of `dir`'s length) to `tri` (Möller–Trumbore),
/// if the ray hits it farther than `t_min`. Primary rays take any hit in front;
/// shadow rays skip the first 1e-4 of the way so they do not hit their own surface.
pub fn intersect(origin: Vec3, dir: Vec3, tri: &Triangle, t_min: f32) -> Option<f32> {
    let e1 = tri.v1 - tri.v0;
    let e2 = tri.v2 - tri.v0;
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None; // parallel to the triangle's plane, or degenerate
    }
    let inv = 1.0 / det;
    let s = origin - tri.v0;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > t_min).then_some(t)
}
