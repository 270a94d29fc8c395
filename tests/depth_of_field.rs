//! Depth of field (#12): a post-process on the colour and 1/z buffers whose blur
//! follows the circle of confusion.

use rasterlab::app::{self, Settings};
use rasterlab::extensions::depth_of_field::DepthOfField;
use rasterlab::{Figure, StageName};

/// Pixel-light on the checker box, whose squares' edges show any blur.
fn draw(dof: Option<DepthOfField>) -> rasterlab::Frame {
    use rasterlab::scene::texture::{apply_texture, TextureSpec};
    let mut scene = rasterlab::scene::parse_scene("cornell").unwrap();
    apply_texture(&mut scene, &TextureSpec::Checker).unwrap();
    let s = Settings {
        dof,
        ..Settings::default()
    };
    app::render(Figure::of(StageName::PixelLight), &scene, &s, None).0
}

#[test]
fn the_focused_depth_stays_sharp_and_the_rest_blurs() {
    let sharp = draw(None);
    // The back wall lies at depth 4.001 (camera at z = -3.001, wall at z = 1).
    let focused = draw(Some(DepthOfField {
        focus: 4.001,
        aperture: 0.05,
    }));
    // Every back-wall pixel whose square of confusion is a single pixel keeps its
    // colour: the middle of the wall, above the blocks.
    let i = 170 * 500 + 250;
    assert_eq!(focused.color[i], sharp.color[i]);
    // The floor's nearest rows (depth about 2) are spread over
    // 500 * 0.05 * |1/2 - 1/4| = 6 pixels either side: they change.
    let near_floor = (480..500)
        .flat_map(|y| (0..500).map(move |x| y * 500 + x))
        .filter(|&i| focused.color[i] != sharp.color[i])
        .count();
    assert!(
        near_floor > 5_000,
        "{near_floor} of 10 000 near-floor pixels changed"
    );
}

#[test]
fn a_pinhole_changes_nothing() {
    let pinhole = Some(DepthOfField {
        focus: 2.0,
        aperture: 0.0,
    });
    assert_eq!(draw(pinhole).color, draw(None).color);
}

#[test]
fn dof_is_refused_without_a_depth_buffer_and_checked() {
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_rasterlab"))
            .args(args)
            .output()
            .unwrap()
    };
    let o = run(&["filled", "--dof", "3,0.1", "-o", "-"]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("unexpected argument '--dof'"), "{e}");
    assert!(
        e.contains("tip: --dof is an option of depth, vertex-light, pixel-light"),
        "{e}"
    );
    for bad in ["0,0.1", "3,-1", "3", "x,1", "inf,1"] {
        let o = run(&["pixel-light", "--dof", bad, "-o", "-"]);
        assert_eq!(o.status.code(), Some(2), "--dof {bad}");
        assert_eq!(String::from_utf8_lossy(&o.stderr).lines().count(), 1);
    }
}
