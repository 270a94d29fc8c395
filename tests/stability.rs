//! The stress catalogue through the binary, and bad input that must be refused.

use crate::common;
use std::process::Command;

fn rasterlab(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn every_stress_case_passes() {
    let o = rasterlab(&["stress", "--quick"]);
    let table = String::from_utf8(o.stdout).unwrap();
    assert!(
        o.status.success(),
        "{table}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let rows: Vec<&str> = table
        .lines()
        .filter(|l| l.starts_with("| ") && l.ends_with(" |"))
        .collect();
    let cases: Vec<&&str> = rows
        .iter()
        .filter(|l| l.ends_with("| ok |") || l.ends_with("| FAIL |"))
        .collect();
    assert!(cases.len() >= 50, "{table}");
    for row in &cases {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        // | case | stage | NaN/inf | panic | error | compared | bound | ms | result |
        assert_eq!(cells[3], "0", "non-finite values: {row}");
        assert_eq!(cells[4], "no", "panicked: {row}");
        if cells[5] != "-" {
            assert!(
                cells[6].parse::<usize>().unwrap() > 0,
                "compared no pixels: {row}"
            );
        }
        assert_eq!(cells[9], "ok", "{row}");
    }
    // The long-span table: the core's drift stays under 0.03 px at every length,
    // while the running sum alone passes a pixel by 32000 steps.
    let drift: Vec<Vec<&str>> = table
        .lines()
        .filter(|l| l.contains(" px |"))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    assert_eq!(drift.len(), 7, "{table}");
    for cells in &drift {
        let px = |i: usize| cells[i].trim_end_matches(" px").parse::<f64>().unwrap();
        assert!(
            px(4) <= 0.03 || cells[1] == "10000000",
            "core drift {}: {cells:?}",
            px(4)
        );
        if cells[1] == "32000" {
            assert!(px(2) > 1.0, "{cells:?}");
        }
    }
}

#[test]
fn bad_numbers_are_refused_before_drawing() {
    for (args, needle) in [
        (
            vec!["pixel-light", "--camera", "nan,0,0"],
            "not a finite number",
        ),
        (
            vec!["pixel-light", "--light", "0,-inf,0"],
            "not a finite number",
        ),
        (vec!["pixel-light", "--yaw", "NaN"], "not a finite number"),
        (vec!["pixel-light", "--near", "0"], "greater than 0"),
        (vec!["pixel-light", "--near", "-1"], "greater than 0"),
        (vec!["pixel-light", "--focal", "-500"], "greater than 0"),
        (vec!["pixel-light", "--size", "0x10"], "from 1 to 16384"),
        (vec!["pixel-light", "--size", "16385x2"], "from 1 to 16384"),
        // A side too large for any integer type is still a side too long.
        (
            vec!["pixel-light", "--size", "99999999999x2"],
            "from 1 to 16384",
        ),
        (
            vec!["pixel-light", "--size", "4294967296x1"],
            "from 1 to 16384",
        ),
        (
            vec!["pixel-light", "--size", "12ax2"],
            "'12a' is not a whole number",
        ),
        (
            vec!["pixel-light", "--light-power", "-1"],
            "must be at least 0",
        ),
        (
            vec!["pixel-light", "--indirect", "-1"],
            "must be at least 0",
        ),
        (
            vec!["check", "x.png", "--indirect", "-0.5"],
            "must be at least 0",
        ),
        (vec!["depth", "--focal", "1e28"], "at most 1e9 pixels"),
        (
            vec!["check", "x.png", "--focal", "1e12"],
            "at most 1e9 pixels",
        ),
    ] {
        let o = rasterlab(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn no_clip_draws_wrong_but_safely() {
    let dir = common::temp_dir("noclip");
    let (clipped, unclipped) = (dir.join("clip.png"), dir.join("noclip.png"));
    let pose = ["--camera", "0.3,0.2,-0.9", "--yaw", "40"];
    for (out, extra) in [(&clipped, None), (&unclipped, Some("--no-clip"))] {
        let mut args = vec!["filled", "-o", out.to_str().unwrap()];
        args.extend(pose);
        args.extend(extra);
        assert!(rasterlab(&args).status.success());
    }
    let (_, _, a) = rasterlab::app::image_io::read_rgb(&clipped).unwrap();
    let (_, _, b) = rasterlab::app::image_io::read_rgb(&unclipped).unwrap();
    // The unclipped frame paints a corner-behind-the-camera triangle across the
    // view: a large share of its pixels differ from the clipped one.
    let differing = a.chunks(3).zip(b.chunks(3)).filter(|(p, q)| p != q).count();
    assert!(differing > 50_000, "{differing}");
}
