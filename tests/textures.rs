//! Textures (#12): the checker on the box, perspective-correct against affine
//! texture coordinates, the two filters, a model's MTL map_Kd, and bad input.

use rasterlab::app::{self, Settings};
use rasterlab::extensions::texture::{Filter, Model};
use rasterlab::pipeline::Frame;
use rasterlab::scene::texture::{apply_texture, TextureSpec};
use rasterlab::scene::{load_obj, parse_scene, read_obj, Scene};
use rasterlab::{Figure, StageName};
use std::path::{Path, PathBuf};
use std::process::Command;

fn checker_box() -> Scene {
    let mut scene = parse_scene("cornell").unwrap();
    apply_texture(&mut scene, &TextureSpec::Checker).unwrap();
    scene
}

fn render<'a>(figure: Figure, model: impl Into<Model<'a>>, settings: &Settings) -> Frame {
    app::render(figure, model, settings, None).0
}

fn differing(a: &Frame, b: &Frame, rows: std::ops::Range<usize>) -> usize {
    let w = a.width as usize;
    rows.map(|y| {
        (0..w)
            .filter(|&x| a.color[y * w + x] != b.color[y * w + x])
            .count()
    })
    .sum()
}

/// Perspective-correct and affine texture coordinates agree where the surface
/// keeps one depth (the back wall, facing the camera) and part where it recedes
/// (floor, ceiling, side walls): the checker's squares warp.
#[test]
fn affine_texture_coordinates_warp_only_receding_surfaces() {
    let (mesh, s) = (checker_box(), Settings::default());
    let perspective = render(Figure::of(StageName::PixelLight), &mesh, &s);
    let affine = render(
        Figure::with_interpolation(StageName::PixelLight, Some(true)),
        &mesh,
        &s,
    );
    let total = differing(&perspective, &affine, 0..500);
    // The back wall, rows 130 to 210 between the side walls, above the blocks:
    // the same texels and light, up to one level of rounding (eq. 10 and 11 see
    // positions that differ in the last bits), or a texel flipped on a square's
    // boundary (76 of 18 400 pixels, measured).
    let channel_gap = |a: u32, b: u32| {
        (0..3)
            .map(|k| ((a >> (8 * k)) & 255).abs_diff((b >> (8 * k)) & 255))
            .max()
            .unwrap()
    };
    let close = |a: u32, b: u32| channel_gap(a, b) <= 1;
    let flips: Vec<(usize, usize)> = (130..210)
        .flat_map(|y| (135..365).map(move |x| (x, y)))
        .filter(|&(x, y)| !close(perspective.color[y * 500 + x], affine.color[y * 500 + x]))
        .collect();
    // The wall spans a whole number of pixels per square, so the squares'
    // boundaries fall on pixels, where rounding decides the side: each flip has,
    // next to it in the perspective image, the affine image's colour.
    for &(x, y) in &flips {
        let wanted = affine.color[y * 500 + x];
        let beside = [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)]
            .iter()
            .any(|&(u, v)| close(perspective.color[v * 500 + u], wanted));
        assert!(beside, "({x}, {y}) differs away from a square's boundary");
    }
    assert!(total > 40_000, "{total} pixels differ in all");
    assert!(
        flips.len() < 200,
        "{} back-wall pixels flipped",
        flips.len()
    );
}

/// Without --texture nothing changes: the lit stages on the plain box are the
/// committed figures (tests/figures.rs), and the box has no texture coordinates
/// to carry. With it, the blocks keep their colours exactly.
#[test]
fn the_checker_leaves_the_blocks_as_they_were() {
    let s = Settings::default();
    let plain = render(
        Figure::of(StageName::PixelLight),
        &rasterlab::cornell_box(),
        &s,
    );
    let textured = render(Figure::of(StageName::PixelLight), &checker_box(), &s);
    // The short (red) block's front face, around pixel (300, 400).
    let i = 400 * 500 + 300;
    assert_eq!(plain.color[i], textured.color[i]);
    assert_ne!(plain.color, textured.color);
}

/// Nearest sampling gives each pixel one of the checker's two shades (times the
/// light); bilinear sampling blends them, so it has more distinct colours.
#[test]
fn bilinear_blends_what_nearest_keeps_apart() {
    let mesh = checker_box();
    let distinct = |filter: Filter| {
        let s = Settings {
            filter,
            light: only_indirect(),
            ..Settings::default()
        };
        // Only indirect light: each pixel is ρ itself times 1.
        let frame = render(Figure::of(StageName::PixelLight), &mesh, &s);
        let back_wall: std::collections::BTreeSet<u32> = (130..210)
            .flat_map(|y| (135..365).map(move |x| y * 500 + x))
            .map(|i| frame.color[i])
            .collect();
        back_wall.len()
    };
    assert_eq!(distinct(Filter::Nearest), 2, "white and its quarter");
    assert!(distinct(Filter::Bilinear) > 20);
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rasterlab-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A square facing the camera, textured by map_Kd with a 2 x 2 image: red and
/// green on top, blue and white below.
fn write_textured_square(dir: &Path, texture: Option<&str>) -> PathBuf {
    let obj = "mtllib square.mtl\nusemtl tiles\n\
        v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n\
        vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
        f 1/1 2/2 3/3 4/4\n";
    std::fs::write(dir.join("square.obj"), obj).unwrap();
    let mtl = format!(
        "newmtl tiles\nKd 0.5 0.5 0.5\n{}",
        texture.map_or(String::new(), |t| format!("map_Kd {t}\n"))
    );
    std::fs::write(dir.join("square.mtl"), mtl).unwrap();
    let image = image::RgbImage::from_fn(2, 2, |x, y| {
        image::Rgb(match (x, y) {
            (0, 0) => [255, 0, 0],
            (1, 0) => [0, 255, 0],
            (0, 1) => [0, 0, 255],
            _ => [255, 255, 255],
        })
    });
    image.save(dir.join("tiles.png")).unwrap();
    dir.join("square.obj")
}

/// The square of `obj`, with the one texture its map_Kd names.
fn textured_square(obj: &Path) -> Scene {
    let (mesh, maps, _) = read_obj(obj).unwrap();
    assert_eq!(maps.images.len(), 1);
    Scene {
        name: "square".into(),
        mesh,
        maps,
        is_box: false,
        pitch: 0.0,
        warnings: Vec::new(),
    }
}

/// The handout's view lit by the indirect light alone: a texel's colour as it is.
fn texels_as_they_are() -> Settings {
    Settings {
        light: only_indirect(),
        ..Settings::default()
    }
}

#[test]
fn a_models_map_kd_is_its_texture() {
    let dir = temp_dir("map-kd");
    let mut scene = textured_square(&write_textured_square(&dir, Some("tiles.png")));
    let s = texels_as_they_are();
    let frame = render(Figure::of(StageName::PixelLight), &scene, &s);
    // The square spans pixels 83 to 416 (f / 3 = 166.7 about the centre).
    let at = |x: usize, y: usize| frame.color[y * 500 + x];
    let rgb = |c: u32| [(c >> 16) & 255, (c >> 8) & 255, c & 255];
    assert_eq!(rgb(at(150, 150)), [255, 0, 0], "top left: red");
    assert_eq!(rgb(at(350, 150)), [0, 255, 0], "top right: green");
    assert_eq!(rgb(at(150, 350)), [0, 0, 255], "bottom left: blue");
    assert_eq!(rgb(at(350, 350)), [255, 255, 255], "bottom right: white");
    // --texture none leaves the model's own texture out: Kd's grey.
    apply_texture(&mut scene, &TextureSpec::parse("none")).unwrap();
    let frame = render(Figure::of(StageName::PixelLight), &scene, &s);
    assert_eq!(rgb(frame.color[150 * 500 + 150]), [128, 128, 128]);
    // Without map_Kd, the same square is Kd's grey.
    std::fs::remove_file(dir.join("square.obj")).unwrap();
    let plain = load_obj(&write_textured_square(&dir, None)).unwrap();
    let frame = render(Figure::of(StageName::PixelLight), &plain, &s);
    assert_eq!(rgb(frame.color[150 * 500 + 150]), [128, 128, 128]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Public models ship JPEG textures: map_Kd naming one is read like a PNG.
/// A 64 x 64 JPEG of the same four tiles, whose flat middles a JPEG keeps
/// within a few levels.
#[test]
fn a_models_jpeg_map_kd_is_read() {
    let dir = temp_dir("map-kd-jpeg");
    let obj = write_textured_square(&dir, Some("tiles.jpg"));
    let tiles = image::open(dir.join("tiles.png")).unwrap().to_rgb8();
    let big = image::imageops::resize(&tiles, 64, 64, image::imageops::FilterType::Nearest);
    big.save(dir.join("tiles.jpg")).unwrap();
    let frame = render(
        Figure::of(StageName::PixelLight),
        &textured_square(&obj),
        &texels_as_they_are(),
    );
    let rgb = |c: u32| [(c >> 16) & 255, (c >> 8) & 255, c & 255];
    let near = |x: usize, y: usize, want: [u32; 3]| {
        let got = rgb(frame.color[y * 500 + x]);
        assert!(
            (0..3).all(|k| got[k].abs_diff(want[k]) <= 8),
            "({x}, {y}): {got:?} against {want:?}"
        );
    };
    near(150, 150, [255, 0, 0]);
    near(350, 150, [0, 255, 0]);
    near(150, 350, [0, 0, 255]);
    near(350, 350, [255, 255, 255]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A model made on another machine names its textures as that machine had
/// them: a Windows path, an absolute one from the author's disk, another case.
/// Each is found beside the model, with a warning that says where.
#[test]
fn a_map_kd_written_on_another_machine_is_found_beside_the_model() {
    let dir = temp_dir("map-kd-elsewhere");
    let obj = write_textured_square(&dir, None);
    std::fs::create_dir_all(dir.join("Textures")).unwrap();
    std::fs::rename(dir.join("tiles.png"), dir.join("Textures/Tiles.png")).unwrap();
    for written in [
        r"Textures\Tiles.png",
        r"C:\Users\ann\Desktop\box\Textures\Tiles.png",
        "textures/tiles.PNG",
    ] {
        std::fs::write(
            dir.join("square.mtl"),
            format!("newmtl tiles\nKd 0.5 0.5 0.5\nmap_Kd {written}\n"),
        )
        .unwrap();
        let (_, maps, warnings) = read_obj(&obj).unwrap();
        assert_eq!(maps.images.len(), 1, "{written}");
        let found = dir.join("Textures").join("Tiles.png");
        assert_eq!(
            warnings,
            [format!(
                "{}: material tiles: map_Kd {written} is not there: read {} instead",
                obj.display(),
                found.display()
            )],
            "{written}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_map_kd_pointing_nowhere_is_drawn_in_its_kd_with_a_warning() {
    let dir = temp_dir("map-kd-missing");
    let obj = write_textured_square(&dir, Some("missing.png"));
    let (_, maps, warnings) = read_obj(&obj).unwrap();
    assert!(maps.images.is_empty());
    let warning = format!(
        "{}: material tiles: map_Kd missing.png is not there: its Kd is drawn instead",
        obj.display()
    );
    assert_eq!(warnings, std::slice::from_ref(&warning));
    // From the command line: the warning, and the image in Kd's grey.
    let out = dir.join("out.png");
    let o = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args([
            "pixel-light",
            "--indirect",
            "1",
            "--light-power",
            "0",
            "--scene",
        ])
        .arg(&obj)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains(&format!("warning: {warning}")), "{stderr}");
    let image = image::open(&out).unwrap().to_rgb8();
    assert_eq!(image.get_pixel(250, 250).0, [128, 128, 128]);
    // A map_Kd that is there but no image is still refused, on one line.
    let obj = write_textured_square(&dir, Some("broken.png"));
    std::fs::write(dir.join("broken.png"), "not an image").unwrap();
    let e = load_obj(&obj).unwrap_err();
    assert!(e.contains("map_Kd") && e.contains("broken.png"), "{e}");
    assert!(!e.contains('\n'));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn texture_options_are_refused_where_nothing_reads_them() {
    let o = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(["depth", "--texture", "checker", "-o", "-"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("unexpected argument '--texture'"), "{e}");
    assert!(
        e.contains("tip: --texture is an option of vertex-light, pixel-light, raytrace"),
        "{e}"
    );
    let o = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(["pixel-light", "--texture", "/no/such/image.png", "-o", "-"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.starts_with("error: texture /no/such/image.png: "), "{e}");
    assert_eq!(e.lines().count(), 1);
}

/// The ray tracer reads the same texture at each hit. The edge rasterizer samples
/// pixel centres as the rays do, so the two agree but for 238 pixels (measured;
/// edges and squares' boundaries that pass through a pixel's centre); the
/// handout's rows shift vertices, and with them every square's boundary, by up to
/// 1.5 pixels (15 406 pixels, measured). The untextured box differs on most walls.
#[test]
fn the_ray_tracer_reads_the_same_texture() {
    use rasterlab::app::figure::Raster;
    use rasterlab::measure::raytrace::{raytrace, Options};
    let (mesh, s) = (checker_box(), Settings::default());
    let rows = render(Figure::of(StageName::PixelLight), &mesh, &s);
    let edge = render(
        Figure::of(StageName::PixelLight).with_raster(Raster::Edge),
        &mesh,
        &s,
    );
    let (camera, light) = (s.camera, s.light);
    let traced = raytrace(&mesh, &camera, &light, &Options::default()).frame;
    let plain = raytrace(
        &rasterlab::cornell_box(),
        &camera,
        &light,
        &Options::default(),
    )
    .frame;
    // Pixels where some channel differs by more than 8 levels.
    let far = |a: &Frame, b: &Frame| {
        let gap = |x: u32, y: u32, k: u32| ((x >> (8 * k)) & 255).abs_diff((y >> (8 * k)) & 255);
        a.color
            .iter()
            .zip(&b.color)
            .filter(|(&x, &y)| (0..3).any(|k| gap(x, y, k) > 8))
            .count()
    };
    let edge_far = far(&edge, &traced);
    assert!(edge_far < 400, "{edge_far} pixels differ (edge)");
    let rows_far = far(&rows, &traced);
    assert!(rows_far < 20_000, "{rows_far} pixels differ (rows)");
    let untextured = far(&edge, &plain);
    assert!(
        untextured > 60_000,
        "{untextured}: the texture changes the image"
    );
}

/// No direct light and an indirect light of 1: each pixel is its ρ.
fn only_indirect() -> rasterlab::Light {
    rasterlab::Light {
        power: glam::Vec3::ZERO,
        indirect: glam::Vec3::ONE,
        ..rasterlab::Light::handout()
    }
}
