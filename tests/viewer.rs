//! `rasterlab view` in a real window under Xvfb: a key script walks and turns the
//! camera, moves the light and switches stages, and the screenshot must equal
//! what the stage subcommand renders from the camera and light the viewer reports.
//!
//! Needs `xvfb-run` (Debian's xvfb). `.ci/run` installs it when it can and runs
//! these with `--ignored`; a plain `cargo test` lists them as ignored.

mod common;
use common::temp_dir;
use rasterlab::app::image_io::read_rgb;
use std::path::Path;
use std::process::Command;

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_rasterlab")
}

fn have_xvfb() -> bool {
    Command::new("sh")
        .args(["-c", "command -v xvfb-run"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false)
}

/// Runs the viewer under Xvfb in `dir`; returns the arguments of the render
/// command it prints for its last frame.
fn view<S: AsRef<std::ffi::OsStr>>(dir: &Path, args: &[S]) -> Vec<String> {
    assert!(
        have_xvfb(),
        "xvfb-run not found: install Debian's xvfb and xauth to run this test"
    );
    let out = Command::new("xvfb-run")
        .args(["-a", bin(), "view"])
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{err}");
    let line = err
        .lines()
        .find_map(|l| l.strip_prefix("view: last frame: rasterlab "))
        .unwrap_or_else(|| panic!("no reproducing command in: {err}"));
    line.split_whitespace().map(String::from).collect()
}

/// Renders the viewer's reported last frame with the stage subcommand and asserts
/// it equals the viewer's screenshot, pixel for pixel.
fn assert_renderer_agrees(dir: &Path, args: &[String], shot: &Path) {
    let reference = dir.join("reference.png");
    let status = Command::new(bin())
        .args(args)
        .args(["-o", reference.to_str().unwrap()])
        .status()
        .unwrap();
    assert!(status.success(), "{args:?}");
    let (wa, ha, pa) = read_rgb(shot).unwrap();
    let (wb, hb, pb) = read_rgb(&reference).unwrap();
    assert_eq!((wa, ha), (wb, hb));
    let differing = pa
        .chunks(3)
        .zip(pb.chunks(3))
        .filter(|(x, y)| x != y)
        .count();
    assert_eq!(
        differing,
        0,
        "the viewer's frame and `rasterlab {}` differ in {differing} pixels",
        args.join(" ")
    );
}

fn script(keys: &str, frames: &str, shot: &Path) -> Vec<String> {
    [
        "--frames",
        frames,
        "--fps",
        "0",
        "--keys",
        keys,
        "--screenshot",
        shot.to_str().unwrap(),
    ]
    .map(String::from)
    .to_vec()
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn scripted_viewer_matches_the_renderer() {
    let dir = temp_dir("viewer");
    let shot = dir.join("shot.png");
    // Turn right, walk in, move the light, look at the depth stage, save a
    // capture with c, then come back to pixel-light.
    let keys = script("right*20,up*15,w*10,a*5,r*6,4,c,6", "60", &shot);
    let args = view(&dir, &keys);
    let joined = args.join(" ");
    assert!(joined.starts_with("pixel-light --size 500x500"), "{joined}");
    // 20 frames of 1/60 s at 60 degrees/s: 20 degrees of yaw, give or take f32 sums.
    let yaw: f32 = args[args.iter().position(|a| a == "--yaw").unwrap() + 1]
        .parse()
        .unwrap();
    assert!((yaw - 20.0).abs() < 1e-3, "{joined}");
    assert!(
        !joined.contains("--camera 0,0,-3.001"),
        "the camera did not move: {joined}"
    );
    assert!(
        !joined.contains("--light 0,-0.5,-0.7"),
        "the light did not move: {joined}"
    );
    assert!(
        dir.join("rasterlab-depth-1.png").exists(),
        "c saved no capture"
    );
    assert_renderer_agrees(&dir, &args, &shot);
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn seven_and_p_switch_interpolation() {
    let dir = temp_dir("viewer-affine");
    let shot = dir.join("shot.png");
    let keys = script("7", "5", &shot);
    let args = view(&dir, &keys);
    assert!(
        args.join(" ").starts_with("pixel-light --affine"),
        "{args:?}"
    );
    assert_renderer_agrees(&dir, &args, &shot);
    // p on vertex-light (affine by default, as section 6.1) turns perspective
    // correction on, and the renderer agrees with the window.
    let shot = dir.join("vertex.png");
    let mut keys: Vec<String> = ["vertex-light", "--frames", "3", "--fps", "0", "--keys", "p"]
        .map(String::from)
        .to_vec();
    keys.extend(["--screenshot".into(), shot.to_str().unwrap().into()]);
    let args = view(&dir, &keys);
    assert!(
        args.join(" ")
            .starts_with("vertex-light --interpolation perspective"),
        "{args:?}"
    );
    assert_renderer_agrees(&dir, &args, &shot);
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn walking_through_the_back_wall() {
    // 250 frames of 1/60 s at 1 unit/s: 4.2 units forward, from z = -3.001 through
    // the back wall at z = 1, then a 45 degree turn to the left.
    let dir = temp_dir("viewer-walk");
    let shot = dir.join("shot.png");
    let keys = script("up*250,left*45", "300", &shot);
    let args = view(&dir, &keys);
    assert_renderer_agrees(&dir, &args, &shot);
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn t_and_b_toggle_the_checker_and_bilinear_filtering() {
    let dir = temp_dir("viewer-texture");
    let shot = dir.join("shot.png");
    let keys = script("t,b", "4", &shot);
    let args = view(&dir, &keys);
    let joined = args.join(" ");
    assert!(joined.contains("--texture checker"), "{joined}");
    assert!(joined.contains("--filter bilinear"), "{joined}");
    assert_renderer_agrees(&dir, &args, &shot);
    // t again: the plain box, as the renderer draws it without --texture.
    let shot = dir.join("plain.png");
    let keys = script("t,none,t", "4", &shot);
    let args = view(&dir, &keys);
    assert!(!args.join(" ").contains("--texture"), "{args:?}");
    assert_renderer_agrees(&dir, &args, &shot);
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn g_focuses_depth_of_field_on_the_centre() {
    let dir = temp_dir("viewer-dof");
    let shot = dir.join("shot.png");
    // One frame first: g focuses on what the last frame drew.
    let keys = script("none,g", "3", &shot);
    let args = view(&dir, &keys);
    let joined = args.join(" ");
    // The centre pixel shows the tall block's front face, 3.054 from the camera;
    // the lens is a fiftieth of that.
    assert!(joined.contains("--dof 3.054"), "{joined}");
    assert_renderer_agrees(&dir, &args, &shot);
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn m_cycles_shadows_and_moving_the_light_moves_them() {
    let dir = temp_dir("viewer-shadows");
    let shot = dir.join("shot.png");
    // Shadows, then filtered ones; then the light moves left.
    let keys = script("m,none,m,a*10", "14", &shot);
    let args = view(&dir, &keys);
    let joined = args.join(" ");
    assert!(joined.contains("--shadows --pcf"), "{joined}");
    assert_renderer_agrees(&dir, &args, &shot);
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn n_toggles_the_bumps() {
    let dir = temp_dir("viewer-normal-map");
    let shot = dir.join("shot.png");
    let keys = script("n", "3", &shot);
    let args = view(&dir, &keys);
    assert!(args.join(" ").contains("--normal-map bumps"), "{args:?}");
    assert_renderer_agrees(&dir, &args, &shot);
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn k_puts_on_parallax_with_the_bumps() {
    let dir = temp_dir("viewer-parallax");
    let shot = dir.join("shot.png");
    let keys = script("t,none,k", "4", &shot);
    let args = view(&dir, &keys);
    let joined = args.join(" ");
    assert!(joined.contains("--normal-map bumps --parallax"), "{joined}");
    assert!(joined.contains("--texture checker"), "{joined}");
    assert_renderer_agrees(&dir, &args, &shot);
}
