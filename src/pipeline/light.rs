//! The handout's light model (section 6.1): an omni light, eq. 10 for the direct
//! light falling on a surface and eq. 11 for what a diffuse surface reflects.

use glam::Vec3;
use std::f32::consts::PI;

/// One point light plus a constant indirect term, as the skeleton's globals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    pub position: Vec3,
    /// P in eq. 10: the light's power per colour channel.
    pub power: Vec3,
    /// N in eq. 11: indirect light per surface area, a constant guess.
    pub indirect: Vec3,
}

impl Light {
    /// The skeleton's light: at (0, -0.5, -0.7), power 1.1, indirect 0.5.
    pub fn handout() -> Self {
        Light {
            position: Vec3::new(0.0, -0.5, -0.7),
            power: Vec3::splat(1.1),
            indirect: Vec3::splat(0.5),
        }
    }

    /// Eq. 10: `D = P max(r̂·n̂, 0) / (4 π |r|²)`, with r from the surface point to
    /// the light.
    #[inline]
    pub fn direct(&self, position: Vec3, normal: Vec3) -> Vec3 {
        let r = self.position - position;
        // A floor under |r|² keeps a light on the surface itself finite (0 / 0
        // would be NaN); no surface in a scene of ordinary size comes that close.
        let r2 = r.x * r.x + r.y * r.y + r.z * r.z;
        let r2 = if r2 > 1e-12 { r2 } else { 1e-12 };
        // r̂·n̂ / (4π r²) as one division: (r·n) / (4π r² |r|). Selects rather than
        // max() so that loops over pixels vectorise (NaN also gives 0 here).
        let r_dot_n = r.x * normal.x + r.y * normal.y + r.z * normal.z;
        let facing = if r_dot_n > 0.0 { r_dot_n } else { 0.0 };
        self.power * (facing / (4.0 * PI * r2 * r2.sqrt()))
    }

    /// Eq. 11: `R = ρ (D + N)`, the light a diffuse surface of reflectance ρ sends back.
    #[inline]
    pub fn reflected(&self, position: Vec3, normal: Vec3, reflectance: Vec3) -> Vec3 {
        reflectance * (self.direct(position, normal) + self.indirect)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direct_light_by_hand() {
        // A light 1 unit straight above a floor facing it: cos = 1, r² = 1,
        // so D = P / 4π.
        let light = Light {
            position: Vec3::new(0.0, -1.0, 0.0),
            power: Vec3::splat(4.0 * PI),
            indirect: Vec3::ZERO,
        };
        let d = light.direct(Vec3::ZERO, Vec3::new(0.0, -1.0, 0.0));
        assert!(d.abs_diff_eq(Vec3::ONE, 1e-6), "{d}");
        // Seen at 60 degrees and 2 units away: cos = 1/2 and r² = 4, so 1/8.
        let p = Vec3::new(3f32.sqrt(), 0.0, 0.0);
        let d = light.direct(p, Vec3::new(0.0, -1.0, 0.0));
        assert!(d.abs_diff_eq(Vec3::splat(0.125), 1e-6), "{d}");
        // Behind the surface: no direct light.
        assert_eq!(light.direct(Vec3::ZERO, Vec3::Y), Vec3::ZERO);
        // The light on the surface point itself: finite (no direction, no light).
        let on = light.direct(light.position, Vec3::Y);
        assert_eq!(on, Vec3::ZERO);
        // Just above it: very bright, still finite.
        let near = light.direct(light.position + Vec3::Y * 1e-3, -Vec3::Y);
        assert!(near.is_finite() && near.x > 1e5, "{near}");
    }

    #[test]
    fn reflected_adds_indirect_and_multiplies_by_reflectance() {
        let light = Light::handout();
        let rho = Vec3::new(0.75, 0.15, 0.15);
        let far_behind = light.reflected(Vec3::new(0.0, -0.5, 5.0), Vec3::Z, rho);
        assert!(far_behind.abs_diff_eq(rho * 0.5, 1e-7), "{far_behind}");
    }
}
