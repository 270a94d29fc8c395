//! Shadows (#12): a cube shadow map from the point light, measured against the
//! ray tracer's shadow rays.

use rasterlab::app::figure::Raster;
use rasterlab::app::{self, Settings};
use rasterlab::extensions::shadow::Shadows;
use rasterlab::measure::raytrace::{raytrace, Options};
use rasterlab::{cornell_box, Figure, Frame, StageName};

fn pixel_light(shadows: Shadows, raster: Raster) -> Frame {
    let figure = Figure::of(StageName::PixelLight)
        .with_raster(raster)
        .with_shadows(shadows);
    app::render(figure, &cornell_box(), &Settings::default(), None).0
}

/// Which pixels shadows change: where `with` differs from `without`.
fn shadowed(without: &Frame, with: &Frame) -> Vec<bool> {
    without
        .color
        .iter()
        .zip(&with.color)
        .map(|(a, b)| a != b)
        .collect()
}

/// The shadow map darkens the pixels shadow rays darken, but for a thin band
/// along the shadows' edges. With the edge rasterizer, which samples the pixel
/// centres the rays go through, the two masks of shadowed pixels are compared.
#[test]
fn the_shadow_map_shadows_what_shadow_rays_shadow() {
    let s = Settings::default();
    let (camera, light) = (s.camera, s.light);
    let trace = |shadows| {
        let options = Options {
            shadows,
            ..Options::default()
        };
        raytrace(&cornell_box(), &camera, &light, &options).frame
    };
    let rays = shadowed(&trace(false), &trace(true));
    let plain = pixel_light(Shadows::None, Raster::Edge);
    let map = shadowed(&plain, &pixel_light(Shadows::Hard, Raster::Edge));
    let in_rays = rays.iter().filter(|&&r| r).count();
    let disagree = rays.iter().zip(&map).filter(|(a, b)| a != b).count();
    assert!(in_rays > 10_000, "{in_rays}");
    assert!(disagree * 20 < in_rays, "{disagree} of {in_rays}");
    // Measured: 71 of 12 617. Filtered shadows reach a pixel further out along
    // their edges, where part of the 3 x 3 texels see the light (742 pixels).
    let pcf = pixel_light(Shadows::Pcf, Raster::Edge);
    let soft = shadowed(&plain, &pcf);
    let differ = soft.iter().zip(&map).filter(|(a, b)| a != b).count();
    assert!(
        differ > 0 && differ * 10 < in_rays,
        "pcf differs from hard on {differ}"
    );
}

/// Without --shadows nothing changes: pixel-light draws the committed Figure 7,
/// byte for byte, and no shadow map; with them it does not.
#[test]
fn no_shadows_is_the_handouts_figure() {
    let figure7 = concat!(env!("CARGO_MANIFEST_DIR"), "/steps/fig7-pixel-light.png");
    let (w, h, committed) =
        rasterlab::app::image_io::read_rgb(std::path::Path::new(figure7)).unwrap();
    let plain = pixel_light(Shadows::None, Raster::Rows);
    assert_eq!((w, h), (plain.width, plain.height));
    assert!(
        plain.to_rgb8() == committed,
        "pixel-light without shadows is not Figure 7"
    );
    assert!(pixel_light(Shadows::Hard, Raster::Rows).to_rgb8() != committed);
    let s = Settings::default();
    assert!(Figure::of(StageName::PixelLight)
        .shadow_map(&cornell_box(), &s.light, s.camera.near.unwrap())
        .is_none());
    assert!(Figure::of(StageName::PixelLight)
        .with_shadows(Shadows::Hard)
        .shadow_map(&cornell_box(), &s.light, s.camera.near.unwrap())
        .is_some());
}
