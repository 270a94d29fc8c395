//! Normal maps (#12): a tangent-space map tilts each pixel's normal in the face's
//! tangent frame; the ray tracer reads the same map.

use glam::Vec3;
use rasterlab::app::figure::Raster;
use rasterlab::app::{self, Settings};
use rasterlab::extensions::texture::Texture;
use rasterlab::measure::raytrace::{raytrace, Options};
use rasterlab::pipeline::Frame;
use rasterlab::scene::parse_scene;
use rasterlab::scene::texture::{apply_normal_map, bumps};
use rasterlab::scene::Scene;
use rasterlab::{Figure, StageName};

fn mapped_box(map: Texture) -> Scene {
    let mut scene = parse_scene("cornell").unwrap();
    apply_normal_map(&mut scene, map);
    scene
}

fn pixel_light<'a>(
    model: impl Into<rasterlab::extensions::texture::Model<'a>>,
    raster: Raster,
) -> Frame {
    let figure = Figure::of(StageName::PixelLight).with_raster(raster);
    app::render(figure, model, &Settings::default(), None).0
}

fn gap(a: u32, b: u32) -> u32 {
    (0..3)
        .map(|k| ((a >> (8 * k)) & 255).abs_diff((b >> (8 * k)) & 255))
        .max()
        .unwrap()
}

/// A map whose every texel says "straight out" changes no normal: the image is
/// the plain box's, up to one level where renormalising moves the last bit.
#[test]
fn a_flat_map_changes_nothing() {
    let flat = Texture::new(1, 1, vec![Vec3::new(0.5, 0.5, 1.0)]).unwrap();
    let plain = pixel_light(&rasterlab::cornell_box(), Raster::Rows);
    let mapped = pixel_light(&mapped_box(flat), Raster::Rows);
    let worst = plain
        .color
        .iter()
        .zip(&mapped.color)
        .map(|(&a, &b)| gap(a, b))
        .max()
        .unwrap();
    assert!(worst <= 1, "{worst}");
}

/// The bumps change the room's light, and the ray tracer, reading the same map at
/// each hit, agrees with the edge rasterizer but for pixels where both sample
/// across a bump's rim or an edge.
#[test]
fn bumps_tilt_the_light_as_the_ray_tracer_does() {
    let mesh = mapped_box(bumps());
    let s = Settings::default();
    let edge = pixel_light(&mesh, Raster::Edge);
    let plain = pixel_light(&rasterlab::cornell_box(), Raster::Edge);
    let traced = raytrace(&mesh, &s.camera, &s.light, &Options::default()).frame;
    let count = |a: &Frame, b: &Frame| {
        a.color
            .iter()
            .zip(&b.color)
            .filter(|(&x, &y)| gap(x, y) > 2)
            .count()
    };
    let changed = count(&plain, &edge);
    let off = count(&edge, &traced);
    assert!(changed > 20_000, "the bumps change {changed} pixels");
    assert!(
        off * 20 < changed,
        "{off} pixels off against the ray tracer"
    );
}

#[test]
fn normal_maps_are_refused_where_nothing_reads_them() {
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_rasterlab"))
            .args(args)
            .output()
            .unwrap()
    };
    let o = run(&["vertex-light", "--normal-map", "bumps", "-o", "-"]);
    assert_eq!(o.status.code(), Some(2));
    let o = run(&["pixel-light", "--normal-map", "/no/such.png", "-o", "-"]);
    assert_eq!(o.status.code(), Some(1));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.starts_with("error: texture /no/such.png: "), "{e}");
}

/// Parallax moves the texture coordinates by the bumps' heights along the view:
/// on the domes the checker and the bumps' light shift, on the flat between them
/// (height 0) nothing moves.
#[test]
fn parallax_moves_what_the_domes_show() {
    use rasterlab::scene::texture::{apply_parallax, apply_texture, TextureSpec};
    let s = Settings {
        camera: rasterlab::Camera {
            position: Vec3::new(0.3, 0.0, -0.2),
            yaw: (-30f32).to_radians(),
            ..rasterlab::Camera::handout(500, 500)
        },
        light: rasterlab::Light {
            position: Vec3::new(0.0, 0.0, 0.4),
            power: Vec3::splat(2.0),
            ..rasterlab::Light::handout()
        },
        ..Settings::default()
    };
    let draw = |parallax: bool| {
        let mut scene = parse_scene("cornell").unwrap();
        apply_texture(&mut scene, &TextureSpec::Checker).unwrap();
        apply_normal_map(&mut scene, bumps());
        if parallax {
            apply_parallax(&mut scene);
        }
        app::render(Figure::of(StageName::PixelLight), &scene, &s, None).0
    };
    let (off, on) = (draw(false), draw(true));
    let moved = off
        .color
        .iter()
        .zip(&on.color)
        .filter(|(a, b)| a != b)
        .count();
    assert!(moved > 5_000, "{moved} pixels moved");
    assert!(
        moved < 125_000,
        "{moved} pixels moved: more than the domes cover"
    );
}
