//! Clipping, which the handout leaves out (end of section 3).
//!
//! Two cuts, each carrying every per-vertex quantity with it:
//! - the near plane `z = near`, in camera space, before projection: a vertex at or
//!   behind the camera has no sensible projection. The stage's attributes are
//!   linear over the triangle in 3D, so they are interpolated in 3D;
//! - a guard band around the screen, after projection: a vertex just in front of
//!   the camera can project millions of pixels away, and walking such edges would
//!   cost far more than the screen. What is interpolated on the screen (1/z, q/z,
//!   or the affine q) is linear in screen space, so it is interpolated in 2D.
//!
//! Polygons live in a fixed-size [`Polygon`]: one triangle cut by one plane has at
//! most 4 corners, then by the band's 4 sides at most 8. Nothing is allocated.

use super::interpolate::Varying;
use glam::Vec3;

/// The most corners a clipped triangle can have.
pub const MAX_CORNERS: usize = 8;

/// A small polygon stored inline.
#[derive(Clone, Copy, Debug)]
pub struct Polygon<T> {
    corners: [T; MAX_CORNERS],
    len: usize,
}

impl<T: Copy + Default> Default for Polygon<T> {
    fn default() -> Self {
        Polygon {
            corners: [T::default(); MAX_CORNERS],
            len: 0,
        }
    }
}

impl<T: Copy + Default> Polygon<T> {
    pub fn from_slice(corners: &[T]) -> Self {
        let mut p = Polygon::default();
        for &c in corners {
            p.push(c);
        }
        p
    }

    pub fn push(&mut self, c: T) {
        if self.len < MAX_CORNERS {
            self.corners[self.len] = c;
            self.len += 1;
        }
    }

    pub fn as_slice(&self) -> &[T] {
        &self.corners[..self.len]
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// A vertex in camera space with the stage's per-vertex struct (linear in 3D).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CameraVertex<V> {
    pub position: Vec3,
    pub varying: V,
}

/// A projected vertex before it is placed on a pixel: `x = f X/Z` and
/// `y = f Y/Z` relative to the screen centre, and what is interpolated on screen
/// (1/z, and the varying as the interpolation encodes it).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScreenVertex<V> {
    pub x: f32,
    pub y: f32,
    pub zinv: f32,
    pub varying: V,
}

fn lerp_camera<V: Varying>(p: CameraVertex<V>, q: CameraVertex<V>, t: f32) -> CameraVertex<V> {
    CameraVertex {
        position: p.position + (q.position - p.position) * t,
        varying: p.varying + (q.varying - p.varying) * t,
    }
}

fn lerp_screen<V: Varying>(p: ScreenVertex<V>, q: ScreenVertex<V>, t: f32) -> ScreenVertex<V> {
    ScreenVertex {
        x: p.x + (q.x - p.x) * t,
        y: p.y + (q.y - p.y) * t,
        zinv: p.zinv + (q.zinv - p.zinv) * t,
        varying: p.varying + (q.varying - p.varying) * t,
    }
}

/// One pass of Sutherland–Hodgman: keeps the part of `input` where `inside(c) >= 0`,
/// `inside` being a signed distance that is linear along each edge.
fn clip_polygon<T: Copy + Default>(
    input: &Polygon<T>,
    inside: impl Fn(&T) -> f32,
    lerp: impl Fn(T, T, f32) -> T,
) -> Polygon<T> {
    let mut out = Polygon::default();
    let c = input.as_slice();
    for i in 0..c.len() {
        let (p, q) = (c[i], c[(i + 1) % c.len()]);
        let (dp, dq) = (inside(&p), inside(&q));
        if dp >= 0.0 {
            out.push(p);
        }
        if (dp >= 0.0) != (dq >= 0.0) {
            out.push(lerp(p, q, dp / (dp - dq)));
        }
    }
    out
}

/// The part of a polygon at `z >= near`.
pub fn clip_near<V: Varying>(
    input: &Polygon<CameraVertex<V>>,
    near: f32,
) -> Polygon<CameraVertex<V>> {
    clip_polygon(input, |c| c.position.z - near, lerp_camera)
}

/// The part of a segment at `z >= near`, if any.
pub fn clip_segment_near<V: Varying>(
    p: CameraVertex<V>,
    q: CameraVertex<V>,
    near: f32,
) -> Option<(CameraVertex<V>, CameraVertex<V>)> {
    let (dp, dq) = (p.position.z - near, q.position.z - near);
    match (dp >= 0.0, dq >= 0.0) {
        (true, true) => Some((p, q)),
        (false, false) => None,
        (true, false) => Some((p, lerp_camera(p, q, dp / (dp - dq)))),
        (false, true) => Some((lerp_camera(p, q, dp / (dp - dq)), q)),
    }
}

/// An axis-aligned rectangle in the screen-centred coordinates of [`ScreenVertex`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub left: f32,
    pub top: f32,
    pub right: f32,
    pub bottom: f32,
}

impl Rect {
    pub fn contains<V>(&self, v: &ScreenVertex<V>) -> bool {
        (self.left..=self.right).contains(&v.x) && (self.top..=self.bottom).contains(&v.y)
    }
}

/// The part of a projected polygon inside `rect`.
pub fn clip_rect<V: Varying>(
    input: &Polygon<ScreenVertex<V>>,
    rect: &Rect,
) -> Polygon<ScreenVertex<V>> {
    let mut p = *input;
    let distances: [fn(&Rect, f32, f32) -> f32; 4] = [
        |r, x, _| x - r.left,
        |r, x, _| r.right - x,
        |r, _, y| y - r.top,
        |r, _, y| r.bottom - y,
    ];
    for d in distances {
        if p.as_slice().iter().any(|v| d(rect, v.x, v.y) < 0.0) {
            p = clip_polygon(&p, |v| d(rect, v.x, v.y), lerp_screen);
        }
    }
    p
}

/// The part of a projected segment inside `rect` (Liang–Barsky), if any.
pub fn clip_segment_rect<V: Varying>(
    p: ScreenVertex<V>,
    q: ScreenVertex<V>,
    rect: &Rect,
) -> Option<(ScreenVertex<V>, ScreenVertex<V>)> {
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    let (dx, dy) = (q.x - p.x, q.y - p.y);
    for (num, den) in [
        (p.x - rect.left, -dx),
        (rect.right - p.x, dx),
        (p.y - rect.top, -dy),
        (rect.bottom - p.y, dy),
    ] {
        // Inside where den * t <= num.
        if den == 0.0 {
            if num < 0.0 {
                return None;
            }
        } else {
            let t = num / den;
            if den < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 <= t1).then(|| (lerp_screen(p, q, t0), lerp_screen(p, q, t1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cv(x: f32, y: f32, z: f32, a: f32) -> CameraVertex<f32> {
        CameraVertex {
            position: Vec3::new(x, y, z),
            varying: a,
        }
    }

    #[test]
    fn near_clip_cuts_a_triangle_into_a_quad_and_carries_attributes() {
        // One corner behind the camera: two edges cross z = 1.
        let tri = Polygon::from_slice(&[
            cv(0.0, 0.0, -1.0, 0.0),
            cv(1.0, 0.0, 3.0, 4.0),
            cv(0.0, 1.0, 3.0, 8.0),
        ]);
        let out = clip_near(&tri, 1.0);
        let c = out.as_slice();
        assert_eq!(c.len(), 4);
        assert!(c.iter().all(|v| v.position.z >= 1.0 - 1e-6));
        // The cut on the edge to (1, 0, 3) is halfway: attribute 2, x 0.5.
        assert!(c
            .iter()
            .any(|v| (v.position - Vec3::new(0.5, 0.0, 1.0)).length() < 1e-6
                && (v.varying - 2.0).abs() < 1e-6));
        assert!(c
            .iter()
            .any(|v| (v.position - Vec3::new(0.0, 0.5, 1.0)).length() < 1e-6
                && (v.varying - 4.0).abs() < 1e-6));
        // Wholly behind: nothing; wholly in front: unchanged.
        let behind = Polygon::from_slice(&[
            cv(0.0, 0.0, -1.0, 0.0),
            cv(1.0, 0.0, 0.5, 0.0),
            cv(0.0, 1.0, 0.0, 0.0),
        ]);
        assert!(clip_near(&behind, 1.0).is_empty());
        assert_eq!(clip_near(&out, 1.0).len(), 4);
    }

    #[test]
    fn segments_are_cut_at_the_near_plane() {
        let (p, q) =
            clip_segment_near(cv(0.0, 0.0, 0.0, 0.0), cv(0.0, 4.0, 4.0, 1.0), 1.0).unwrap();
        assert_eq!(p.position, Vec3::new(0.0, 1.0, 1.0));
        assert_eq!(p.varying, 0.25);
        assert_eq!(q.position.z, 4.0);
        assert!(clip_segment_near(cv(0.0, 0.0, 0.0, 0.0), cv(0.0, 4.0, 0.5, 1.0), 1.0).is_none());
    }

    fn sv(x: f32, y: f32) -> ScreenVertex<f32> {
        ScreenVertex {
            x,
            y,
            zinv: x,
            varying: x + y,
        }
    }

    #[test]
    fn rect_clip_keeps_what_is_inside_and_interpolates_linearly() {
        let r = Rect {
            left: -10.0,
            top: -10.0,
            right: 10.0,
            bottom: 10.0,
        };
        let huge = Polygon::from_slice(&[sv(-1e6, -1e6), sv(1e6, -1e6), sv(0.0, 1e6)]);
        let out = clip_rect(&huge, &r);
        assert!(out.len() >= 3 && out.len() <= MAX_CORNERS);
        for v in out.as_slice() {
            assert!(r.contains(v), "{v:?}");
            // v was x + y at every corner and is interpolated linearly.
            assert!(
                (v.varying - (v.x + v.y)).abs() < 1e-3 * (1.0 + v.varying.abs()),
                "{v:?}"
            );
        }
        let (p, q) = clip_segment_rect(sv(-100.0, 0.0), sv(100.0, 0.0), &r).unwrap();
        assert_eq!((p.x, q.x, p.varying, q.varying), (-10.0, 10.0, -10.0, 10.0));
        assert!(clip_segment_rect(sv(-100.0, 20.0), sv(100.0, 20.0), &r).is_none());
    }
}
