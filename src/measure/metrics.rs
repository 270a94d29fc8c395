//! How far a stage's image is from the reference, in numbers a student can compare.

use crate::pipeline::camera::Projection;
use crate::pipeline::target::unpack;
use crate::pipeline::{Camera, Frame, Mesh};

/// Error of an image against a reference, in 8-bit units over all three channels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageError {
    pub rmse: f64,
    pub max: u8,
    /// 20 log10(255 / rmse) in dB; infinite for identical images.
    pub psnr: f64,
    /// Pixels compared.
    pub pixels: usize,
}

/// RMSE, max and PSNR of `image` against `reference` over the pixels where `mask`
/// is true (all pixels without a mask).
pub fn image_error(image: &Frame, reference: &Frame, mask: Option<&[bool]>) -> ImageError {
    assert_eq!(
        image.color.len(),
        reference.color.len(),
        "images of different sizes"
    );
    let (mut sum, mut max, mut pixels) = (0u64, 0u8, 0usize);
    for (i, (&a, &b)) in image.color.iter().zip(&reference.color).enumerate() {
        if mask.is_some_and(|m| !m[i]) {
            continue;
        }
        pixels += 1;
        for (p, q) in unpack(a).into_iter().zip(unpack(b)) {
            let d = p.abs_diff(q);
            sum += (d as u64) * (d as u64);
            max = max.max(d);
        }
    }
    let rmse = if pixels == 0 {
        0.0
    } else {
        (sum as f64 / (3 * pixels) as f64).sqrt()
    };
    ImageError {
        rmse,
        max,
        psnr: 20.0 * (255.0 / rmse).log10(),
        pixels,
    }
}

/// The fraction of pixels (under `mask`) whose colour differs at all.
pub fn differing_fraction(image: &Frame, reference: &Frame, mask: Option<&[bool]>) -> f64 {
    let (mut differ, mut n) = (0usize, 0usize);
    for (i, (a, b)) in image.color.iter().zip(&reference.color).enumerate() {
        if mask.is_some_and(|m| !m[i]) {
            continue;
        }
        n += 1;
        differ += (a != b) as usize;
    }
    if n == 0 {
        0.0
    } else {
        differ as f64 / n as f64
    }
}

/// Each face's surface, named by the first face of it: faces of one flat
/// surface (a wall's two triangles) share a normal and a colour; on a mesh with
/// vertex normals, which is smooth across its faces, the colour alone names it.
/// A map, so this stays linear in the number of faces.
pub fn surfaces(mesh: &Mesh) -> Vec<usize> {
    let smooth = !mesh.normals.is_empty();
    // `+ 0.0` makes -0 and 0 one key, as `==` would.
    let bits = |v: glam::Vec3| v.to_array().map(|c| (c + 0.0).to_bits());
    let mut first = std::collections::HashMap::new();
    mesh.triangles()
        .enumerate()
        .map(|(i, t)| {
            let normal = if smooth { glam::Vec3::ZERO } else { t.normal };
            *first.entry((bits(normal), bits(t.color))).or_insert(i)
        })
        .collect()
}

/// Interior pixels: those whose whole (2 margin + 1)² neighbourhood shows the same
/// surface (same colour and normal) in `hit`, the reference's triangle per pixel.
/// Near edges the rasterizer and the ray tracer sample differently (truncation
/// versus pixel centres), so errors there say little about shading.
pub fn interior_mask(
    mesh: &Mesh,
    hit: &[Option<u32>],
    width: u32,
    height: u32,
    margin: u32,
) -> Vec<bool> {
    let surface = surfaces(mesh);
    let id = |x: u32, y: u32| hit[(y * width + x) as usize].map(|i| surface[i as usize]);
    let mut mask = vec![false; (width * height) as usize];
    let m = margin;
    for y in m..height.saturating_sub(m) {
        for x in m..width.saturating_sub(m) {
            let centre = id(x, y);
            mask[(y * width + x) as usize] = centre.is_some()
                && (y - m..=y + m).all(|yy| (x - m..=x + m).all(|xx| id(xx, yy) == centre));
        }
    }
    mask
}

/// Eq. 3 and 4 without rounding, in f64: where a world point really lands on the
/// screen, if it is in front of the camera.
fn exact_projection(camera: &Camera, p: &Projection, v: glam::Vec3) -> Option<(f64, f64)> {
    let c = p.to_camera(v);
    let f = camera.focal as f64;
    (c.z > 0.0).then(|| {
        (
            f * c.x as f64 / c.z as f64 + (camera.width / 2) as f64,
            f * c.y as f64 / c.z as f64 + (camera.height / 2) as f64,
        )
    })
}

/// Of the scene's projected vertices in front of the camera and on screen, how
/// many are drawn within one pixel of where the exact projection `f X/Z + W/2`
/// puts them: the pixel (x, y) covers [x, x + 1) x [y, y + 1), and counts if its
/// centre is within 1 of the exact point on both axes. Returns (within, total).
pub fn points_within_one_pixel(mesh: &Mesh, camera: &Camera, frame: &Frame) -> (usize, usize) {
    let (w, h) = (camera.width as f64, camera.height as f64);
    let p = camera.projection();
    let (mut within, mut total) = (0, 0);
    for v in mesh.triangles().flat_map(|t| t.vertices()) {
        let Some((ex, ey)) = exact_projection(camera, &p, v) else {
            continue;
        };
        if !(0.0..w).contains(&ex) || !(0.0..h).contains(&ey) {
            continue;
        }
        total += 1;
        // Is there a drawn pixel whose centre is within 1 of the exact point?
        let near = (ex.floor() as i64 - 1..=ex.floor() as i64 + 1).any(|x| {
            (ey.floor() as i64 - 1..=ey.floor() as i64 + 1).any(|y| {
                (0..w as i64).contains(&x)
                    && (0..h as i64).contains(&y)
                    && (x as f64 + 0.5 - ex).abs() <= 1.0
                    && (y as f64 + 0.5 - ey).abs() <= 1.0
                    && frame.color[(y as u32 * camera.width + x as u32) as usize] != 0
            })
        });
        within += near as usize;
    }
    (within, total)
}

/// Of the lit pixels of a wireframe, how many have their centre within one pixel
/// of an exactly projected edge. Returns (within, total).
pub fn edge_pixels_within_one_pixel(mesh: &Mesh, camera: &Camera, frame: &Frame) -> (usize, usize) {
    let p = camera.projection();
    let exact = |v| exact_projection(camera, &p, v);
    let segments: Vec<((f64, f64), (f64, f64))> = mesh
        .triangles()
        .flat_map(|t| {
            let v = t.vertices();
            [(v[0], v[1]), (v[1], v[2]), (v[2], v[0])]
        })
        .filter_map(|(a, b)| Some((exact(a)?, exact(b)?)))
        .collect();
    let dist = |(px, py): (f64, f64), ((ax, ay), (bx, by)): ((f64, f64), (f64, f64))| {
        let (dx, dy) = (bx - ax, by - ay);
        let len2 = dx * dx + dy * dy;
        let t = if len2 == 0.0 {
            0.0
        } else {
            (((px - ax) * dx + (py - ay) * dy) / len2).clamp(0.0, 1.0)
        };
        ((px - ax - t * dx).powi(2) + (py - ay - t * dy).powi(2)).sqrt()
    };
    let (mut within, mut total) = (0, 0);
    for y in 0..camera.height {
        for x in 0..camera.width {
            if frame.color[(y * camera.width + x) as usize] == 0 {
                continue;
            }
            total += 1;
            let centre = (x as f64 + 0.5, y as f64 + 0.5);
            within += segments.iter().any(|&s| dist(centre, s) <= 1.0) as usize;
        }
    }
    (within, total)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::Triangle;

    #[test]
    fn identical_images_have_no_error() {
        let mut a = Frame::new(4, 4);
        a.color[5] = 0x0012_3456;
        let e = image_error(&a, &a.clone(), None);
        assert_eq!((e.rmse, e.max, e.pixels), (0.0, 0, 16));
        assert!(e.psnr.is_infinite());
        assert_eq!(differing_fraction(&a, &a, None), 0.0);
    }

    #[test]
    fn truncation_toward_zero_misplaces_points_left_of_the_centre() {
        // Three vertices at z = 0, 3.001 from the handout's camera, placed so their
        // exact projections are (300.7, 310.2), (320.3, 330.3) and (199.2, 250.5).
        // The first two truncate to pixels whose centres are 0.2 to 0.3 away; the
        // third has x - W/2 = -50.8, truncated toward zero to -50: pixel 200,
        // centre 200.5, 1.3 from 199.2, so it does not count.
        let camera = Camera::handout(500, 500);
        let world = |x: f32, y: f32| {
            glam::Vec3::new(
                (x - 250.0) * 3.001 / 500.0,
                (y - 250.0) * 3.001 / 500.0,
                0.0,
            )
        };
        let tri = Triangle::new(
            world(300.7, 310.2),
            world(320.3, 330.3),
            world(199.2, 250.5),
            glam::Vec3::ONE,
        );
        let mesh = Mesh::from_triangles(&[tri]);
        let mut frame = Frame::default();
        crate::pipeline::Pipeline::<_, crate::pipeline::Affine, crate::pipeline::RowRaster>::new()
            .render(&crate::pipeline::Points, &mesh, &camera, &mut frame);
        assert_eq!(frame.color.iter().filter(|&&c| c != 0).count(), 3);
        assert_eq!(points_within_one_pixel(&mesh, &camera, &frame), (2, 3));
    }

    #[test]
    fn one_pixel_off_by_a_known_amount() {
        // One pixel of 10 x 10 off by 30 in one channel: the mean square over
        // 300 values is 900 / 300 = 3, so the RMSE is sqrt(3).
        let a = Frame::new(10, 10);
        let mut b = a.clone();
        b.color[42] = 30 << 8;
        let e = image_error(&a, &b, None);
        assert!((e.rmse - 3f64.sqrt()).abs() < 1e-12, "{}", e.rmse);
        assert_eq!(e.max, 30);
        assert!((e.psnr - 20.0 * (255.0 / 3f64.sqrt()).log10()).abs() < 1e-9);
        assert_eq!(differing_fraction(&a, &b, None), 0.01);
        // Masked out, the difference is gone.
        let mut mask = vec![true; 100];
        mask[42] = false;
        assert_eq!(image_error(&a, &b, Some(&mask)).rmse, 0.0);
    }
}
