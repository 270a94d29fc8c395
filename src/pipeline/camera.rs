//! The pinhole camera of the handout's section 1: world to camera space by
//! `P' = (P - C) R` (eq. 8) and the projection `x = f X/Z` (eq. 3, 4) relative to
//! the screen centre; the rasterizer places that on a pixel.

use super::clip::Rect;
use glam::Vec3;

/// Where the camera is, where it looks and how it projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// C in eq. 5: the pinhole's position in world space.
    pub position: Vec3,
    /// Turn about the y-axis, in radians; positive turns the view to the right.
    pub yaw: f32,
    /// Tilt, in radians; positive looks up (toward -y).
    pub pitch: f32,
    /// f in eq. 1 to 4, in pixels.
    pub focal: f32,
    pub width: u32,
    pub height: u32,
    /// The near clipping plane, `z = near` in camera space; `None` draws as the
    /// handout does, without clipping (`--no-clip`).
    pub near: Option<f32>,
}

/// The default near plane: 1 cm in a room 2 m wide.
pub const DEFAULT_NEAR: f32 = 0.01;

impl Camera {
    /// The course skeleton's camera: at (0, 0, -3.001), looking along +z, f = 500.
    pub fn handout(width: u32, height: u32) -> Self {
        Camera {
            position: Vec3::new(0.0, 0.0, -3.001),
            yaw: 0.0,
            pitch: 0.0,
            focal: 500.0,
            width,
            height,
            near: Some(DEFAULT_NEAR),
        }
    }

    /// The columns of R: the camera's right, down and forward directions in world space.
    pub fn axes(&self) -> [Vec3; 3] {
        let (sa, ca) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        let forward = Vec3::new(sa * cp, -sp, ca * cp);
        let right = Vec3::new(ca, 0.0, -sa);
        let down = forward.cross(right);
        [right, down, forward]
    }

    /// The camera with R computed once, ready to transform many vertices.
    pub fn projection(&self) -> Projection {
        Projection {
            position: self.position,
            axes: self.axes(),
            focal: self.focal,
        }
    }

    /// The screen's pixels in the screen-centred coordinates of [`Projection::project_centred`]:
    /// a point there truncates onto the screen only inside this rectangle.
    pub fn screen_rect(&self) -> Rect {
        let (hw, hh) = ((self.width / 2) as f32, (self.height / 2) as f32);
        Rect {
            left: -hw,
            top: -hh,
            right: self.width as f32 - hw,
            bottom: self.height as f32 - hh,
        }
    }

    /// `P' = (P - C) R` for one point (eq. 8).
    pub fn to_camera(&self, world: Vec3) -> Vec3 {
        self.projection().to_camera(world)
    }
}

/// A camera's eq. 8 and eq. 3, 4 with the rotation R already built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    position: Vec3,
    axes: [Vec3; 3],
    focal: f32,
}

impl Projection {
    /// `P' = (P - C) R` with P a row vector (eq. 8): one dot product per column of R,
    /// summed left to right as glm's `vec3 * mat3` does.
    #[inline]
    pub fn to_camera(&self, world: Vec3) -> Vec3 {
        let p = world - self.position;
        let [right, down, forward] = self.axes;
        Vec3::new(dot(p, right), dot(p, down), dot(p, forward))
    }

    /// Eq. 3 and 4 before rounding and before the half size is added, with 1/z:
    /// `(f X zinv, f Y zinv, zinv)` in f32, as the handout's `VertexShader` computes
    /// them. `None` where 1/z is not finite (a point on the camera plane).
    #[inline]
    pub fn project_centred(&self, camera_space: Vec3) -> Option<(f32, f32, f32)> {
        let (x, y, zinv) = self.project_centred_or_not_finite(camera_space);
        (zinv.is_finite() && x.is_finite() && y.is_finite()).then_some((x, y, zinv))
    }

    /// [`Projection::project_centred`], the three numbers finite or not: for a
    /// loop over many points that tests them without a branch.
    #[inline]
    pub fn project_centred_or_not_finite(&self, camera_space: Vec3) -> (f32, f32, f32) {
        let zinv = 1.0 / camera_space.z;
        let x = self.focal * camera_space.x * zinv;
        let y = self.focal * camera_space.y * zinv;
        (x, y, zinv)
    }
}

fn dot(a: Vec3, b: Vec3) -> f32 {
    a.x * b.x + a.y * b.y + a.z * b.z
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn yaw_and_pitch_zero_give_the_identity() {
        let c = Camera::handout(500, 500);
        assert_eq!(c.axes(), [Vec3::X, Vec3::Y, Vec3::Z]);
        assert_eq!(c.to_camera(Vec3::ZERO), Vec3::new(0.0, 0.0, 3.001));
    }

    #[test]
    fn positive_yaw_turns_right_and_positive_pitch_looks_up() {
        let mut c = Camera::handout(500, 500);
        c.position = Vec3::ZERO;
        c.yaw = 90f32.to_radians();
        // Looking along +x now: a point at +x is straight ahead.
        let p = c.to_camera(Vec3::X);
        assert!(p.abs_diff_eq(Vec3::Z, 1e-6), "{p}");
        c.yaw = 0.0;
        c.pitch = 90f32.to_radians();
        let p = c.to_camera(-Vec3::Y);
        assert!(p.abs_diff_eq(Vec3::Z, 1e-6), "{p}");
    }

    #[test]
    fn points_on_the_camera_plane_are_not_projected() {
        let p = Camera::handout(500, 500).projection();
        assert_eq!(p.project_centred(Vec3::new(1.0, 0.0, 0.0)), None);
        assert_eq!(p.project_centred(Vec3::new(f32::NAN, 0.0, 1.0)), None);
        // Behind the camera the handout's formula still gives numbers (mirrored);
        // the near-plane clip, not the projection, keeps such points out.
        assert_eq!(
            p.project_centred(Vec3::new(1.0, 0.0, -2.0)),
            Some((-250.0, -0.0, -0.5))
        );
    }
}
