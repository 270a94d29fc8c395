//! `rasterlab view` in a real window under Xvfb: a key script walks and turns the
//! camera, moves the light and switches stages, and the screenshot must equal
//! what the stage subcommand renders from the camera and light the viewer reports.
//!
//! Needs `xvfb-run` (Debian's xvfb). `.ci/run` installs it when it can and runs
//! these with `--ignored`; a plain `cargo test` lists them as ignored.

mod common;
use common::temp_dir;
use rasterlab::image_io::read_rgb_png;
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
fn view(dir: &Path, args: &[&str]) -> Vec<String> {
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

fn assert_same_image(a: &Path, b: &Path) {
    let (wa, ha, pa) = read_rgb_png(a).unwrap();
    let (wb, hb, pb) = read_rgb_png(b).unwrap();
    assert_eq!((wa, ha), (wb, hb));
    let differing = pa
        .chunks(3)
        .zip(pb.chunks(3))
        .filter(|(x, y)| x != y)
        .count();
    assert_eq!(
        differing,
        0,
        "{} and {} differ in {differing} pixels",
        a.display(),
        b.display()
    );
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn scripted_viewer_matches_the_renderer() {
    let dir = temp_dir("viewer");
    let shot = dir.join("shot.png");
    // Turn right, walk in, move the light, look at the depth stage, save a
    // capture with c, then come back to pixel-light.
    let args = view(
        &dir,
        &[
            "--frames",
            "60",
            "--fps",
            "0",
            "--keys",
            "right*20,up*15,w*10,a*5,r*6,4,c,6",
            "--screenshot",
            shot.to_str().unwrap(),
        ],
    );
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

    let reference = dir.join("reference.png");
    let status = Command::new(bin())
        .args(&args)
        .args(["-o", reference.to_str().unwrap()])
        .status()
        .unwrap();
    assert!(status.success());
    assert_same_image(&shot, &reference);
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn seven_and_p_switch_interpolation() {
    let dir = temp_dir("viewer-affine");
    let shot = dir.join("shot.png");
    let args = view(
        &dir,
        &[
            "--frames",
            "5",
            "--fps",
            "0",
            "--keys",
            "7",
            "--screenshot",
            shot.to_str().unwrap(),
        ],
    );
    assert!(
        args.join(" ").starts_with("pixel-light --affine"),
        "{args:?}"
    );
    let reference = dir.join("reference.png");
    assert!(Command::new(bin())
        .args(&args)
        .args(["-o", reference.to_str().unwrap()])
        .status()
        .unwrap()
        .success());
    assert_same_image(&shot, &reference);
    // p on vertex-light turns perspective correction off.
    let args = view(
        &dir,
        &["vertex-light", "--frames", "3", "--fps", "0", "--keys", "p"],
    );
    assert!(
        args.join(" ").starts_with("vertex-light --affine"),
        "{args:?}"
    );
}

#[test]
#[ignore = "needs Xvfb; .ci/run runs it with --ignored"]
fn walking_through_the_back_wall() {
    // 250 frames of 1/60 s at 1 unit/s: 4.2 units forward, from z = -3.001 through
    // the back wall at z = 1, then turn to look back at it.
    let dir = temp_dir("viewer-walk");
    let shot = dir.join("shot.png");
    let args = view(
        &dir,
        &[
            "--frames",
            "300",
            "--fps",
            "0",
            "--keys",
            "up*250,left*45",
            "--screenshot",
            shot.to_str().unwrap(),
        ],
    );
    let reference = dir.join("reference.png");
    assert!(Command::new(bin())
        .args(&args)
        .args(["-o", reference.to_str().unwrap()])
        .status()
        .unwrap()
        .success());
    assert_same_image(&shot, &reference);
}
