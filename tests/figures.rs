//! The figures committed in steps/ must be what the code draws now. After a
//! change that alters a figure on purpose, regenerate them with
//! `cargo run --release -- all --out steps` and commit the new PNGs.

use rasterlab::app::image_io::read_rgb;
use rasterlab::app::overview::figure_one;
use rasterlab::app::{self, Settings, OVERVIEW_FILE};
use rasterlab::extensions::shadow::Shadows;
use rasterlab::extensions::texture::Filter;
use rasterlab::{cornell_box, Figure};
use std::path::Path;

fn steps() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/steps"))
}

/// Compares an image with a committed PNG, naming the first differing pixel.
fn assert_matches(name: &str, width: u32, height: u32, rgb: &[u8]) {
    let path = steps().join(name);
    let (w, h, committed) = read_rgb(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((w, h), (width, height), "{name}: size");
    if let Some(i) = (0..rgb.len())
        .step_by(3)
        .find(|&i| rgb[i..i + 3] != committed[i..i + 3])
    {
        let p = i as u32 / 3;
        let differing = (0..rgb.len())
            .step_by(3)
            .filter(|&i| rgb[i..i + 3] != committed[i..i + 3])
            .count();
        panic!(
            "{name}: {differing} pixels differ from the committed figure, first at ({}, {}): drawn {:?}, committed {:?}; \
             regenerate with `cargo run --release -- all --out steps` if the change is meant",
            p % w,
            p / w,
            &rgb[i..i + 3],
            &committed[i..i + 3]
        );
    }
}

#[test]
fn committed_figures_match_the_code() {
    let mut frames = Vec::new();
    for view in Figure::FIGURES {
        let (frame, _) = app::render(view, &cornell_box(), &Settings::default(), None);
        assert_matches(
            view.figure_file(),
            frame.width,
            frame.height,
            &frame.to_rgb8(),
        );
        frames.push(frame);
    }
    let overview = figure_one(frames).unwrap();
    assert_matches(
        OVERVIEW_FILE,
        overview.width,
        overview.height,
        &overview.to_rgb8(),
    );
}

fn docs() -> std::path::PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/docs")).to_path_buf()
}

/// Compares a picture with a committed PNG anywhere in the repository.
fn assert_picture(path: &Path, frame: &rasterlab::Frame) {
    let (w, h, committed) = read_rgb(path).unwrap_or_else(|e| panic!("{e}"));
    let rgb = frame.to_rgb8();
    assert!(
        (w, h) == (frame.width, frame.height) && committed == rgb,
        "{} is stale: redraw it with the command on its page",
        path.display()
    );
}

/// The pictures of the algorithms in steps/ and docs/, each redrawn by the code it
/// comes from (the commands are on the pages that show them).
#[test]
fn committed_pictures_match_the_code() {
    use rasterlab::app::explain::{explain_edge, explain_line, explain_rows};
    let steps = steps();
    // rasterlab explain line 4,2 1,8; rasterlab explain rows 10,5 5,10 15,15
    assert_picture(
        &steps.join("explain-line.png"),
        &explain_line((4, 2), (1, 8)).unwrap(),
    );
    assert_picture(
        &steps.join("explain-rows.png"),
        &explain_rows(&[(10, 5), (5, 10), (15, 15)]).unwrap(),
    );
    // rasterlab explain bresenham 0,0 12,5
    assert_picture(
        &steps.join("explain-bresenham.png"),
        &rasterlab::app::explain::explain_bresenham((0, 0), (12, 5)).unwrap(),
    );
    // rasterlab explain edge 0.5,0.5 6.5,0.5 0.5,6.5
    assert_picture(
        &steps.join("explain-edge.png"),
        &explain_edge(&[(0.5, 0.5), (6.5, 0.5), (0.5, 6.5)]).unwrap(),
    );
    // rasterlab explain shared 1.3,1.2 12.6,2.4 11.2,11.7 2.1,10.4
    assert_picture(
        &steps.join("explain-shared.png"),
        &rasterlab::app::explain::explain_shared(&[
            (1.3, 1.2),
            (12.6, 2.4),
            (11.2, 11.7),
            (2.1, 10.4),
        ])
        .unwrap(),
    );
    // rasterlab vertex-light|pixel-light --scene docs/models/sphere.obj --size 300x300
    //   --focal 300 --light -1,-1.5,-2 --light-power 20
    let sphere = rasterlab::scene::load_obj(&docs().join("models/sphere.obj")).unwrap();
    let scene = rasterlab::scene::Scene {
        name: "sphere".into(),
        mesh: sphere,
        maps: Default::default(),
        is_box: false,
        pitch: 0.0,
        warnings: Vec::new(),
    };
    let looking = rasterlab::Camera {
        focal: 300.0,
        ..rasterlab::Camera::handout(300, 300)
    };
    let (camera, _) = rasterlab::scene::framed_view(&scene, &looking).unwrap();
    let settings = Settings {
        camera,
        light: rasterlab::Light {
            position: glam::Vec3::new(-1.0, -1.5, -2.0),
            power: glam::Vec3::splat(20.0),
            ..rasterlab::Light::handout()
        },
        ..Settings::default()
    };
    for stage in [
        rasterlab::StageName::VertexLight,
        rasterlab::StageName::PixelLight,
    ] {
        let (frame, _) = app::render(Figure::of(stage), &scene, &settings, None);
        assert_picture(&steps.join(format!("models-{}.png", stage.name())), &frame);
    }
    // rasterlab pixel-light --texture checker [--affine | --filter bilinear]
    let mut textured = rasterlab::scene::parse_scene("cornell").unwrap();
    rasterlab::scene::texture::apply_texture(
        &mut textured,
        &rasterlab::scene::texture::TextureSpec::Checker,
    )
    .unwrap();
    let pixel_light = rasterlab::StageName::PixelLight;
    for (name, figure, filter) in [
        ("perspective", Figure::of(pixel_light), Filter::Nearest),
        (
            "affine",
            Figure::with_interpolation(pixel_light, Some(true)),
            Filter::Nearest,
        ),
        ("bilinear", Figure::of(pixel_light), Filter::Bilinear),
    ] {
        let settings = Settings {
            filter,
            ..Settings::default()
        };
        let (frame, _) = app::render(figure, &textured, &settings, None);
        assert_picture(&steps.join(format!("texture-{name}.png")), &frame);
    }
    // rasterlab pixel-light --texture checker --dof 4.001,0.05 (and 2.2,0.05)
    for (name, focus) in [("back-wall", 4.001), ("near", 2.2)] {
        let settings = Settings {
            dof: Some(rasterlab::extensions::depth_of_field::DepthOfField {
                focus,
                aperture: 0.05,
            }),
            ..Settings::default()
        };
        let (frame, _) = app::render(Figure::of(pixel_light), &textured, &settings, None);
        assert_picture(&steps.join(format!("dof-{name}.png")), &frame);
    }
    // rasterlab pixel-light [--shadows [--pcf]] --light-power 8; raytrace --shadows
    let bright = Settings {
        light: rasterlab::Light {
            power: glam::Vec3::splat(8.0),
            ..rasterlab::Light::handout()
        },
        ..Settings::default()
    };
    for (name, shadows) in [
        ("none", Shadows::None),
        ("map", Shadows::Hard),
        ("pcf", Shadows::Pcf),
    ] {
        let figure = Figure::of(pixel_light).with_shadows(shadows);
        let (frame, _) = app::render(figure, &cornell_box(), &bright, None);
        assert_picture(&steps.join(format!("shadows-{name}.png")), &frame);
    }
    let rays = rasterlab::measure::raytrace::Options {
        shadows: true,
        ..Default::default()
    };
    let traced = rasterlab::measure::raytrace::raytrace(
        &cornell_box(),
        &bright.camera,
        &bright.light,
        &rays,
    );
    assert_picture(&steps.join("shadows-rays.png"), &traced.frame);
    // rasterlab pixel-light --normal-map bumps; raytrace --normal-map bumps
    let mut bumped = rasterlab::scene::parse_scene("cornell").unwrap();
    rasterlab::scene::texture::apply_normal_map(&mut bumped, rasterlab::scene::texture::bumps());
    let s = Settings::default();
    let (frame, _) = app::render(Figure::of(pixel_light), &bumped, &s, None);
    assert_picture(&steps.join("normal-map-bumps.png"), &frame);
    let traced =
        rasterlab::measure::raytrace::raytrace(&bumped, &s.camera, &s.light, &Default::default());
    assert_picture(&steps.join("normal-map-rays.png"), &traced.frame);
    // rasterlab pixel-light --texture checker --normal-map bumps [--parallax]
    //   --camera 0.3,0,-0.2 --yaw -30 --light 0,0,0.4 --light-power 2
    let close = Settings {
        camera: rasterlab::Camera {
            position: glam::Vec3::new(0.3, 0.0, -0.2),
            yaw: (-30f32).to_radians(),
            ..rasterlab::Camera::handout(500, 500)
        },
        light: rasterlab::Light {
            position: glam::Vec3::new(0.0, 0.0, 0.4),
            power: glam::Vec3::splat(2.0),
            ..rasterlab::Light::handout()
        },
        ..Settings::default()
    };
    for (name, parallax) in [("off", false), ("on", true)] {
        let mut scene = textured.clone();
        rasterlab::scene::texture::apply_normal_map(&mut scene, rasterlab::scene::texture::bumps());
        if parallax {
            rasterlab::scene::texture::apply_parallax(&mut scene);
        }
        let (frame, _) = app::render(Figure::of(pixel_light), &scene, &close, None);
        assert_picture(&steps.join(format!("parallax-{name}.png")), &frame);
    }
    // rasterlab depth --buffer
    let (depth, _) = app::render(
        Figure::of(rasterlab::StageName::Depth),
        &cornell_box(),
        &Settings::default(),
        None,
    );
    assert_picture(
        &steps.join("depth-buffer.png"),
        &app::depth_buffer_picture(&depth),
    );
    // rasterlab report: the heat maps (deterministic, unlike its times)
    let plan = rasterlab::app::report::Plan::full();
    let cornell = rasterlab::scene::parse_scene("cornell").unwrap();
    let view = rasterlab::app::report::view_for(&cornell).unwrap();
    for (name, picture) in rasterlab::app::report::heat_maps(&plan, &cornell, &view) {
        assert_picture(&docs().join("report").join(name), &picture);
    }
}

/// rasterlab animate filled; rasterlab animate depth: the GIFs byte for byte.
#[test]
fn committed_animations_match_the_code() {
    let dir = std::env::temp_dir().join(format!("rasterlab-test-{}-gif", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for stage in [rasterlab::StageName::Filled, rasterlab::StageName::Depth] {
        let name = format!("animate-{}.gif", stage.name());
        let out = dir.join(&name);
        app::animate_to_file(
            Figure::of(stage),
            &cornell_box(),
            &Settings::default(),
            &out,
            150,
        )
        .unwrap();
        let (made, committed) = (
            std::fs::read(&out).unwrap(),
            std::fs::read(steps().join(&name)).unwrap(),
        );
        assert!(
            made == committed,
            "steps/{name} is stale: rasterlab animate {} -o steps/{name}",
            stage.name()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
