//! A benchmark sitting kept in the repository: with `RASTERLAB_RECORD=1` a bench
//! writes its medians to `docs/bench/NAME-BUILD.tsv`, which the pages' generated
//! blocks are made from and `tests/benched.rs` holds them to. `benches/sitting.sh`
//! runs the whole sitting, both builds.

use rasterlab::app::Settings;
use std::path::Path;

/// The handout's view at `size`, the focal length the image's height (500 at
/// 500x500, as the handout's figures).
pub fn settings(size: (u32, u32)) -> Settings {
    Settings {
        camera: rasterlab::Camera {
            focal: size.1 as f32,
            ..rasterlab::Camera::handout(size.0, size.1)
        },
        ..Settings::default()
    }
}

/// Which build this is: "native" when compiled with AVX2 (`-C target-cpu=native`
/// here), "default" for the x86-64 baseline.
pub fn build() -> &'static str {
    if cfg!(target_feature = "avx2") {
        "native"
    } else {
        "default"
    }
}

/// Whether this run should be written down: `RASTERLAB_RECORD` is set and the
/// benchmarks really ran (not `cargo test`'s single pass).
pub fn recording() -> bool {
    std::env::var_os("RASTERLAB_RECORD").is_some() && std::env::args().any(|a| a == "--bench")
}

fn git(args: &[&str]) -> String {
    std::process::Command::new("git")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default()
}

/// Writes `rows` (a case and its values, named by `columns`) to
/// `docs/bench/NAME-BUILD.tsv`, headed by the commit measured and the date. Code
/// with changes not yet committed (in what the benches build) is named
/// `COMMIT+changes`.
pub fn record(name: &str, columns: &[&str], rows: &[(String, Vec<f64>)]) {
    write(name, &header(columns), rows);
}

/// The sitting's first two lines: the commit and date, and the columns.
pub fn header(columns: &[&str]) -> String {
    let mut commit = git(&["rev-parse", "--short=7", "HEAD"]);
    let built = ["src", "benches", "Cargo.toml", "Cargo.lock"];
    let status = [
        &["status", "--porcelain", "--untracked-files=no", "--"][..],
        &built,
    ]
    .concat();
    if !git(&status).is_empty() {
        commit.push_str("+changes");
    }
    let date = std::process::Command::new("date")
        .args(["-u", "+%Y-%m-%d"])
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    format!(
        "# commit {commit}, {date}, {} build, one thread unless the case says\ncase\t{}\n",
        build(),
        columns.join("\t")
    )
}

/// Where the sitting's `NAME` file of this build is.
pub fn path(name: &str) -> std::path::PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/bench");
    dir.join(format!("{name}-{}.tsv", build()))
}

/// `header` and `rows` written to [`path`] through a temporary file.
pub fn write(name: &str, header: &str, rows: &[(String, Vec<f64>)]) {
    let mut csv = header.to_string();
    for (case, values) in rows {
        assert!(!case.contains('\t'), "a tab in {case}");
        let values: Vec<String> = values.iter().map(|v| format!("{v:.4}")).collect();
        csv.push_str(&format!("{case}\t{}\n", values.join("\t")));
    }
    let path = path(name);
    std::fs::create_dir_all(path.parent().expect("docs/bench")).expect("docs/bench");
    let temporary = path.with_extension("tsv.new");
    std::fs::write(&temporary, csv).expect("the sitting written");
    std::fs::rename(&temporary, &path).expect("the sitting renamed into place");
    eprintln!("recorded {}", path.display());
}
