//! The command line: help, options, timing output, and bad input that must give a
//! one-line error and the right exit code, never a panic or a half-written file.

use crate::common;
use common::temp_dir;
use std::process::{Command, Output};

fn rasterlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(args)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Asserts a usage error: exit code 2, and exactly one line on stderr that
/// contains `needle`.
fn usage_error(args: &[&str], needle: &str) {
    let o = rasterlab(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
}

#[test]
fn every_subcommand_explains_itself() {
    for (cmd, words) in [
        ("points", "Section 2"),
        ("wireframe", "Section 3"),
        ("filled", "Section 4"),
        ("depth", "Section 5"),
        ("vertex-light", "Section 6.1"),
        ("pixel-light", "Section 6.2"),
        ("all", "fig1-overview.png"),
        ("rows", "ComputePolygonRows"),
        ("raytrace", "--shadows"),
        ("report", "error-vs-time.png"),
        ("stress", "hard cases"),
        ("view", "--keys"),
        ("check", "screenshot"),
    ] {
        let o = rasterlab(&[cmd, "--help"]);
        assert!(o.status.success(), "{cmd}");
        let text = String::from_utf8(o.stdout).unwrap();
        assert!(text.contains(words), "{cmd} --help: {text}");
        let interpolates = ["vertex-light", "pixel-light", "view"].contains(&cmd);
        assert_eq!(text.contains("--affine"), interpolates, "{cmd} --help");
        let draws = !["rows", "report", "stress"].contains(&cmd);
        for opt in ["--size", "--focal", "--camera", "--yaw", "--pitch"] {
            assert_eq!(text.contains(opt), draws, "{cmd} --help and {opt}");
        }
        // The light only where something is lit.
        let lit = [
            "vertex-light",
            "pixel-light",
            "all",
            "raytrace",
            "view",
            "report",
            "check",
        ];
        assert_eq!(
            text.contains("--light-power"),
            lit.contains(&cmd),
            "{cmd} --help and --light-power"
        );
    }
}

/// Each stage lists only what it reads: points 14 options and --help, no light,
/// no lines, no interpolation; each later section adds its own.
#[test]
fn each_stage_lists_only_the_options_it_reads() {
    let options = |cmd: &str| -> Vec<String> {
        let o = rasterlab(&[cmd, "--help"]);
        String::from_utf8(o.stdout)
            .unwrap()
            .lines()
            .filter(|l| l.starts_with("  -") || l.starts_with("      --"))
            .map(|l| {
                l.split_whitespace()
                    .find(|w| w.starts_with("--"))
                    .unwrap()
                    .to_string()
            })
            .collect()
    };
    let points = options("points");
    assert_eq!(points.len(), 15, "{points:?}");
    let added = |cmd: &str, before: &[String]| -> Vec<String> {
        let mut new: Vec<String> = options(cmd)
            .into_iter()
            .filter(|o| !before.contains(o))
            .collect();
        new.sort();
        new
    };
    assert_eq!(added("wireframe", &points), ["--lines"]);
    let filled = options("filled");
    assert_eq!(added("depth", &filled), ["--buffer", "--dof"]);
    let depth = options("depth");
    assert_eq!(
        added("vertex-light", &depth),
        [
            "--affine",
            "--filter",
            "--indirect",
            "--interpolation",
            "--light",
            "--light-power",
            "--pcf",
            "--shadows",
            "--texture"
        ]
    );
    assert_eq!(
        added("pixel-light", &options("vertex-light")),
        ["--normal-map", "--parallax"]
    );
}

#[test]
fn bad_arguments_are_one_line_usage_errors() {
    usage_error(&["teapot"], "teapot");
    usage_error(&["points", "--size", "0x0"], "from 1 to 16384");
    usage_error(&["points", "--size", "500"], "WIDTHxHEIGHT");
    usage_error(&["points", "--camera", "1,2"], "three numbers");
    usage_error(&["points", "--camera", "1,x,2"], "'x' is not a number");
    usage_error(
        &["pixel-light", "--light", "0,inf,0"],
        "not a finite number",
    );
    usage_error(&["points", "--focal", "0"], "greater than 0");
    usage_error(&["points", "--time", "0"], "--time");
    usage_error(
        &["points", "--size", "-5x5"],
        "each side must be from 1 to 16384 pixels, got '-5x5'",
    );
    usage_error(&["points", "--time", "-1"], "from 1 to 100000, got '-1'");
    usage_error(&["view", "--fps", "-1"], "from 0 to 1000, got '-1'");
    usage_error(&["view", "--frames", "0"], "from 1 to");
    usage_error(&["view", "--keys", "8"], "unknown key '8'");
    usage_error(&["points", "-o", "x.jpg"], "'x.jpg': images are written as PNG or BMP, not .jpg; name the file .png or .bmp, or give - for standard output");
    usage_error(
        &["points", "-o", "x"],
        "'x': its name has no ending to choose the image format by; name the file .png or .bmp",
    );
    usage_error(
        &["pixel-light", "--affine", "--interpolation", "perspective"],
        "cannot be used with",
    );
    usage_error(&["rows"], "X,Y");
    usage_error(&["rows", "1,2", "3"], "expected a pixel X,Y");
}

#[test]
fn options_a_stage_does_not_take_are_refused_with_where_they_belong() {
    for (args, needle) in [
        (
            &["points", "--light", "0,0,0"][..],
            "unexpected argument '--light' found; tip: --light is an option of vertex-light, pixel-light, all, raytrace, report, view, animate vertex-light, animate pixel-light, check",
        ),
        (
            &["depth", "--light-power", "2"][..],
            "tip: --light-power is an option of vertex-light, pixel-light",
        ),
        (
            &["filled", "--affine"][..],
            "tip: --affine is an option of vertex-light, pixel-light, view, animate vertex-light, animate pixel-light",
        ),
        (&["depth", "--texture", "checker"][..], "tip: --texture is an option of"),
        (&["raytrace", "--affine"][..], "unexpected argument '--affine'"),
        (
            &["raytrace", "--flat", "--indirect", "0.2"][..],
            "the argument '--flat' cannot be used with '--indirect <N>'",
        ),
        (
            &["filled", "--lines", "bresenham", "--raster", "edge"][..],
            "--lines does nothing for filled --raster edge",
        ),
        (
            &["pixel-light", "--parallax"][..],
            "the following required arguments were not provided: --normal-map",
        ),
        // Typos: the option meant, or the subcommand.
        (
            &["depth", "--afine"][..],
            "tip: did you mean --affine? an option of vertex-light, pixel-light",
        ),
        (&["pixl-light"][..], "'pixel-light'"),
    ] {
        usage_error(args, needle);
    }
}

#[test]
fn default_names_say_what_the_image_is() {
    let dir = temp_dir("names");
    for (args, file) in [
        (&["pixel-light", "--affine"][..], "pixel-light-affine.png"),
        (&["pixel-light"][..], "pixel-light.png"),
        (&["vertex-light"][..], "vertex-light.png"),
        (
            &["vertex-light", "--interpolation", "perspective"][..],
            "vertex-light-perspective.png",
        ),
        (
            &["vertex-light", "--interpolation", "affine"][..],
            "vertex-light.png",
        ),
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
            .args(args)
            .args(["--size", "16x16"])
            .current_dir(&*dir)
            .output()
            .unwrap();
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        assert!(dir.join(file).exists(), "{args:?} wrote {}", stderr(&o));
        std::fs::remove_file(dir.join(file)).unwrap();
    }
}

#[test]
fn an_unwritable_path_is_a_one_line_failure_and_leaves_no_file() {
    let dir = temp_dir("unwritable");
    let target = dir.join("no-such-folder").join("x.png");
    let o = rasterlab(&["points", "-o", target.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("error: cannot write "), "{err}");
    assert!(err.contains("x.png"), "{err}");
    assert!(!target.exists());
    // A folder where the file should go: refused, nothing left behind.
    let folder = dir.join("f.png");
    std::fs::create_dir(&folder).unwrap();
    let o = rasterlab(&["filled", "-o", folder.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("it is a folder"), "{}", stderr(&o));
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, ["f.png"], "{left:?}");
}

#[test]
fn negative_vectors_and_timing() {
    let dir = temp_dir("timing");
    let out = dir.join("p.png");
    let o = rasterlab(&[
        "pixel-light",
        "--camera",
        "-0.5,0,-2",
        "--yaw",
        "-10",
        "--size",
        "64x48",
        "--time",
        "3",
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    let line = err.lines().find(|l| l.starts_with("render: ")).expect(&err);
    // render: median 0.84 ms (min 0.80 ms, max 0.95 ms, 3 runs)
    let words: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(words[1], "median");
    assert_eq!(
        (words[3], words[4], words[6], words[7], words[9], words[10], words[11]),
        ("ms", "(min", "ms,", "max", "ms,", "3", "runs)"),
        "{line}"
    );
    for i in [2, 5, 8] {
        assert!(words[i].parse::<f64>().is_ok(), "{line}");
    }
    let (w, h, _) = rasterlab::app::image_io::read_rgb(&out).unwrap();
    assert_eq!((w, h), (64, 48));
}

#[test]
fn all_writes_every_figure_and_the_overview() {
    let dir = temp_dir("all");
    let o = rasterlab(&["all", "--out", dir.to_str().unwrap(), "--size", "40x30"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "fig1-overview.png",
            "fig2-points.png",
            "fig3-wireframe.png",
            "fig4-filled.png",
            "fig5-depth.png",
            "fig6-vertex-light.png",
            "fig7-pixel-light.png",
            "fig8-pixel-light-affine.png",
        ]
    );
    let (w, h, _) = rasterlab::app::image_io::read_rgb(&dir.join("fig1-overview.png")).unwrap();
    assert_eq!((w, h), (4 * 40 + 3 * 8, 2 * (30 + 28) + 8));
}

#[test]
fn the_viewer_without_a_display_says_so() {
    let o = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(["view", "--frames", "1"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("error: no display"), "{err}");
    assert!(err.contains("rasterlab all --out"), "{err}");
    usage_error(&["view", "teapot"], "unknown stage 'teapot'");
    usage_error(&["view", "--keys", "jump*3"], "unknown key 'jump'");
}

/// A long command tells a terminal how far along it is, on standard error, and
/// tells a pipe nothing: there only what it produces and what it wrote.
#[test]
fn progress_is_shown_on_a_terminal_only() {
    let dir = temp_dir("progress");
    let root = env!("CARGO_MANIFEST_DIR");
    std::fs::copy(format!("{root}/steps/fig5-depth.png"), dir.join("a.png")).unwrap();
    std::fs::write(dir.join("b.png"), b"not an image").unwrap();
    let folder = dir.to_str().unwrap();
    let piped = rasterlab(&["check", folder]);
    assert_eq!(piped.status.code(), Some(1), "{}", stderr(&piped));
    assert_eq!(stderr(&piped), "", "nothing but the table when piped");
    // util-linux's script(1) runs the command on a pseudo-terminal (Debian has it
    // in every install); -e passes the exit status on.
    let bin = env!("CARGO_BIN_EXE_rasterlab");
    let on_terminal = Command::new("script")
        .args([
            "-qec",
            &format!("{bin} check {folder} 2>&1 >/dev/null"),
            "/dev/null",
        ])
        .output()
        .expect("script(1) from util-linux");
    let shown = String::from_utf8_lossy(&on_terminal.stdout).replace('\r', "");
    assert_eq!(on_terminal.status.code(), Some(1), "{shown}");
    let mut lines: Vec<&str> = shown.lines().collect();
    lines.sort();
    assert_eq!(lines.len(), 2, "{shown}");
    assert!(lines[0].starts_with(&format!("[1/2] {folder}/")), "{shown}");
    assert!(lines[1].starts_with(&format!("[2/2] {folder}/")), "{shown}");
    assert!(shown.contains("/a.png: matches"), "{shown}");
    assert!(shown.contains("/b.png: unreadable"), "{shown}");
}
