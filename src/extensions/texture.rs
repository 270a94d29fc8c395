//! Textures: an image of reflectances that a material's ρ (eq. 11) is read from,
//! addressed by texture coordinates as the design notes define them (v up, rows
//! stored top first, coordinates outside [0, 1] repeating).

use crate::pipeline::Mesh;
use glam::{Vec2, Vec3};

/// How a texture is read between its texels (`--filter`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Filter {
    /// The texel whose square contains the point.
    #[default]
    Nearest,
    /// The four texel centres around the point, weighted by distance.
    Bilinear,
}

/// A W x H image of linear reflectances in [0, 1], rows stored top first.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    width: u32,
    height: u32,
    texels: Vec<Vec3>,
}

impl Texture {
    /// A texture of `width` x `height` texels; `None` if either is 0 or `texels`
    /// does not hold exactly that many.
    pub fn new(width: u32, height: u32, texels: Vec<Vec3>) -> Option<Texture> {
        let count = (width as usize).checked_mul(height as usize)?;
        (width > 0 && height > 0 && texels.len() == count).then_some(Texture {
            width,
            height,
            texels,
        })
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// The texel at column `x`, row `y` (from the top), both repeating. They lie
    /// within one image of it (from -1 to W or H), so one step brings them in,
    /// without a division.
    #[inline]
    fn texel(&self, x: i64, y: i64) -> Vec3 {
        let wrap = |i: i64, n: u32| {
            let n = n as i64;
            (if i < 0 {
                i + n
            } else if i >= n {
                i - n
            } else {
                i
            }) as usize
        };
        self.texels[wrap(y, self.height) * self.width as usize + wrap(x, self.width)]
    }

    /// This texture read as a tangent-space normal map at `uv`: the texel c
    /// encodes `n = 2c - 1` (x along `tangent`, the direction u grows; y along
    /// `bitangent`, where v grows; z along `normal`), turned into that frame and
    /// renormalised; `normal` itself where the frame is degenerate.
    pub fn tangent_normal(
        &self,
        uv: Vec2,
        filter: Filter,
        [tangent, bitangent, normal]: [Vec3; 3],
    ) -> Vec3 {
        if tangent == Vec3::ZERO {
            return normal;
        }
        let n = self.sample(uv, filter) * 2.0 - Vec3::ONE;
        (tangent * n.x + bitangent * n.y + normal * n.z).normalize_or(normal)
    }

    /// The reflectance at texture coordinate `uv`: the point `(u W, (1 - v) H)` of
    /// the image, read with `filter`.
    pub fn sample(&self, uv: Vec2, filter: Filter) -> Vec3 {
        // Only the fraction matters (the texture repeats); taking it first keeps
        // the image coordinates small and exact, from 0 to W and H.
        let (u, v) = (fraction(uv.x), fraction(uv.y));
        let x = u * self.width as f32;
        let y = (1.0 - v) * self.height as f32;
        match filter {
            // Not negative: truncation is the floor.
            Filter::Nearest => self.texel(x as i64, y as i64),
            Filter::Bilinear => {
                // Texel centres sit at half-integers: measure from them.
                let (x, y) = (x - 0.5, y - 0.5);
                let (x0, y0) = (floor(x), floor(y));
                let (fx, fy) = (x - x0, y - y0);
                let (i, j) = (x0 as i64, y0 as i64);
                let top = self.texel(i, j).lerp(self.texel(i + 1, j), fx);
                let bottom = self.texel(i, j + 1).lerp(self.texel(i + 1, j + 1), fx);
                top.lerp(bottom, fy)
            }
        }
    }
}

/// `v.floor()` for `v` from -1 to 2^23, without the library call `f32::floor` is
/// on x86-64 before SSE4.1.
#[inline]
fn floor(v: f32) -> f32 {
    let t = v as i64 as f32;
    if t > v {
        t - 1.0
    } else {
        t
    }
}

/// `v - v.floor()`, in [0, 1), for any `v`; NaN and the infinities give NaN.
#[inline]
fn fraction(v: f32) -> f32 {
    if !v.is_finite() {
        return f32::NAN;
    }
    if v.abs() >= 8_388_608.0 {
        return 0.0; // whole already, from 2^23 on
    }
    let f = v - floor(v);
    // Just below a whole number, `v + 1` can round up to it: stay below 1.
    if f >= 1.0 {
        0.0
    } else {
        f
    }
}

/// The images one material reads, as indices into [`Maps::images`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MaterialMaps {
    /// Where the mesh has (u, v) coordinates, ρ is read from this texture
    /// instead of the colour (an OBJ's `map_Kd`).
    pub texture: Option<u32>,
    /// A tangent-space normal map that tilts the surface's normal per pixel.
    pub normal_map: Option<u32>,
    /// A height map (its red channel, 0 to 1) that offsets the (u, v)
    /// coordinates along the view for parallax.
    pub height_map: Option<u32>,
}

/// What a mesh's materials read beyond their colours, kept beside the mesh (the
/// pipeline's materials are the handout's: a colour each).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Maps {
    pub images: Vec<Texture>,
    /// Material `i` of the mesh reads `materials[i]`; a material past the end
    /// reads nothing.
    pub materials: Vec<MaterialMaps>,
}

impl Maps {
    /// What material `material` reads.
    #[inline]
    pub fn of(&self, material: u32) -> MaterialMaps {
        self.materials
            .get(material as usize)
            .copied()
            .unwrap_or_default()
    }

    /// The image `index` names, if there is one.
    #[inline]
    pub fn image(&self, index: Option<u32>) -> Option<&Texture> {
        index.and_then(|i| self.images.get(i as usize))
    }

    /// Adds `image` and returns its index.
    pub fn push(&mut self, image: Texture) -> u32 {
        self.images.push(image);
        self.images.len() as u32 - 1
    }

    /// The maps of material `material`, to change (grown to hold it).
    pub fn of_mut(&mut self, material: usize) -> &mut MaterialMaps {
        if self.materials.len() <= material {
            self.materials.resize(material + 1, MaterialMaps::default());
        }
        &mut self.materials[material]
    }

    /// Whether any material of `mesh`, which has (u, v) coordinates, reads what
    /// `pick` chooses.
    pub fn any(&self, mesh: &Mesh, pick: impl Fn(&MaterialMaps) -> Option<u32>) -> bool {
        !mesh.uvs.is_empty()
            && (0..mesh.materials.len() as u32).any(|m| self.image(pick(&self.of(m))).is_some())
    }
}

/// A mesh and what its materials read beyond their colours: what the stages
/// beyond the handout draw.
#[derive(Clone, Copy, Debug)]
pub struct Model<'a> {
    pub mesh: &'a Mesh,
    pub maps: &'a Maps,
}

/// No maps at all: the handout's materials.
pub static NO_MAPS: Maps = Maps {
    images: Vec::new(),
    materials: Vec::new(),
};

impl<'a> From<&'a Mesh> for Model<'a> {
    /// The handout's: colours alone.
    fn from(mesh: &'a Mesh) -> Self {
        Model {
            mesh,
            maps: &NO_MAPS,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2 x 2: black, white on the top row; red, green below.
    fn four() -> Texture {
        let texels = vec![Vec3::ZERO, Vec3::ONE, Vec3::X, Vec3::Y];
        Texture::new(2, 2, texels).unwrap()
    }

    #[test]
    fn nearest_takes_the_texel_containing_the_point_with_v_up() {
        let t = four();
        // v near 1 is the top row; u near 0 the left column.
        assert_eq!(t.sample(Vec2::new(0.1, 0.9), Filter::Nearest), Vec3::ZERO);
        assert_eq!(t.sample(Vec2::new(0.9, 0.9), Filter::Nearest), Vec3::ONE);
        assert_eq!(t.sample(Vec2::new(0.1, 0.1), Filter::Nearest), Vec3::X);
        assert_eq!(t.sample(Vec2::new(0.9, 0.1), Filter::Nearest), Vec3::Y);
        // Repeats outside [0, 1], on both sides.
        assert_eq!(t.sample(Vec2::new(1.1, -0.1), Filter::Nearest), Vec3::ZERO);
        assert_eq!(t.sample(Vec2::new(-0.1, 2.1), Filter::Nearest), Vec3::Y);
    }

    #[test]
    fn bilinear_weights_the_four_centres_around_the_point() {
        let t = four();
        // At a texel's centre, that texel.
        assert_eq!(
            t.sample(Vec2::new(0.25, 0.75), Filter::Bilinear),
            Vec3::ZERO
        );
        assert_eq!(t.sample(Vec2::new(0.75, 0.25), Filter::Bilinear), Vec3::Y);
        // Midway between all four centres: their mean.
        let mid = t.sample(Vec2::new(0.5, 0.5), Filter::Bilinear);
        assert!((mid - Vec3::new(0.5, 0.5, 0.25)).length() < 1e-6, "{mid}");
        // On the image's edge, the repeat blends in the opposite side: u = 0 is
        // midway between the right column's centre and the left one's.
        let edge = t.sample(Vec2::new(0.0, 0.75), Filter::Bilinear);
        assert!((edge - Vec3::splat(0.5)).length() < 1e-6, "{edge}");
    }

    #[test]
    fn fraction_is_v_minus_its_floor() {
        for bits in (0..=u32::MAX).step_by(97) {
            let v = f32::from_bits(bits);
            let expected = v - v.floor();
            let got = fraction(v);
            if v.is_finite() {
                let expected = if expected >= 1.0 { 0.0 } else { expected };
                assert_eq!(got, expected, "{v:e}");
                assert!((0.0..1.0).contains(&got), "{v:e}");
            } else {
                assert!(got.is_nan(), "{v:e}");
            }
        }
    }

    #[test]
    fn bad_coordinates_and_sizes_do_not_panic() {
        let t = four();
        for uv in [Vec2::NAN, Vec2::INFINITY, Vec2::new(1e30, -1e30)] {
            for f in [Filter::Nearest, Filter::Bilinear] {
                let _ = t.sample(uv, f);
            }
        }
        assert!(Texture::new(0, 2, vec![]).is_none());
        assert!(Texture::new(2, 2, vec![Vec3::ONE; 3]).is_none());
    }
}
