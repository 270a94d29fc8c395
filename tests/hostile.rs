//! Input from strangers and shared folders (issue #18): planted links, special
//! files, files without end, sizes beyond memory, and messages that say what is
//! wrong. Each case is refused with one line, or drawn, never waited on or
//! aborted.

use crate::common;
use common::temp_dir;
use std::fs;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_rasterlab")
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The lines of stderr that are warnings.
fn warnings(o: &Output) -> Vec<&str> {
    std::str::from_utf8(&o.stderr)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("warning: "))
        .collect()
}

/// Runs the binary with `args`, killed after 20 s: a hang is a failure here.
fn run(args: &[&str]) -> Output {
    run_in(None, args)
}

fn run_in(dir: Option<&Path>, args: &[&str]) -> Output {
    let mut cmd = Command::new(bin());
    cmd.args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    if let Some(d) = dir {
        cmd.current_dir(d);
    }
    let mut child = cmd.spawn().unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(20) {
            child.kill().unwrap();
            panic!("{args:?} still running after 20 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// A failure with exit code `code` and one line that contains `needle`.
fn refused(o: &Output, code: i32, needle: &str) {
    let e = err(o);
    assert_eq!(o.status.code(), Some(code), "{e}");
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.contains(needle), "expected '{needle}' in: {e}");
}

fn is_root() -> bool {
    Command::new("id").arg("-u").output().unwrap().stdout == b"0\n"
}

/// Whether `runuser -u nobody` can run the binary (root, runuser, a reachable path).
fn nobody_can_run() -> bool {
    is_root()
        && Command::new("runuser")
            .args(["-u", "nobody", "--", bin(), "--version"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
}

/// [`nobody_can_run`], saying on standard error when the test is skipped.
fn nobody_can_run_or_say_skipped() -> bool {
    let can = nobody_can_run();
    if !can {
        eprintln!("skipped: not root, no runuser, or nobody cannot reach the binary");
    }
    can
}

/// The last process id the kernel handed out.
fn last_pid() -> u32 {
    fs::read_to_string("/proc/sys/kernel/ns_last_pid")
        .unwrap()
        .trim()
        .parse()
        .unwrap()
}

/// Plants, as `nobody` where the test runs as root (the attacker is another
/// user), links named as the old temporary files of `names` would be for the
/// next 400 process ids, all pointing at `victim`.
fn plant_links(dir: &Path, names: &[&str], victim: &Path) {
    let next = last_pid() + 1;
    let mut script = String::new();
    for pid in next..next + 400 {
        for name in names {
            script += &format!(
                "ln -s {} {}/.{name}.{pid}.tmp; ln -s {} {}/{name}.{pid}.tmp\n",
                victim.display(),
                dir.display(),
                victim.display(),
                dir.display()
            );
        }
    }
    run_as_nobody(&script);
}

/// Runs the shell `script` as `nobody` where the test runs as root (as the
/// test's user otherwise). The script goes in on standard input: it may be
/// longer than one argument may be.
fn run_as_nobody(script: &str) {
    let mut cmd = if nobody_can_run() {
        let mut c = Command::new("runuser");
        c.args(["-u", "nobody", "--", "sh", "-s"]);
        c
    } else {
        let mut c = Command::new("sh");
        c.arg("-s");
        c
    };
    let mut child = cmd.stdin(Stdio::piped()).spawn().unwrap();
    use std::io::Write;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(script.as_bytes())
        .unwrap();
    assert!(child.wait().unwrap().success());
}

/// In `root`: a folder `shared` with `mode`, where links are planted, and a
/// file `victim` (root's, "precious") that they point to.
fn shared_folder_and_victim(root: &Path, mode: u32) -> (PathBuf, PathBuf) {
    let shared = root.join("shared");
    fs::create_dir(&shared).unwrap();
    fs::set_permissions(&shared, fs::Permissions::from_mode(mode)).unwrap();
    let victim = root.join("victim");
    fs::write(&victim, b"precious").unwrap();
    fs::set_permissions(&victim, fs::Permissions::from_mode(0o644)).unwrap();
    (shared, victim)
}

#[test]
fn links_planted_for_the_next_process_ids_are_never_written_through() {
    let root = temp_dir("planted");
    // A folder anyone may write to, without the sticky bit: the attack's ground.
    let (shared, victim) = shared_folder_and_victim(&root, 0o777);
    let figures = shared.join("figures");
    let report = shared.join("report");
    fs::create_dir(&figures).unwrap();
    fs::create_dir(&report).unwrap();
    for d in [&figures, &report] {
        fs::set_permissions(d, fs::Permissions::from_mode(0o777)).unwrap();
    }
    plant_links(&shared, &["out.png", "d.obj", "d.mtl"], &victim);
    plant_links(&figures, &["fig2-points.png", "fig1-overview.png"], &victim);
    plant_links(&report, &["report.md", "report.csv"], &victim);
    let out = shared.join("out.png");
    let obj = shared.join("d.obj");
    let cases: [&[&str]; 4] = [
        &["depth", "--size", "8x6", "-o", out.to_str().unwrap()],
        &["export", "-o", obj.to_str().unwrap()],
        &["all", "--size", "8x6", "--out", figures.to_str().unwrap()],
        &["report", "--quick", "--out", report.to_str().unwrap()],
    ];
    for args in cases {
        let o = run(args);
        assert!(o.status.success(), "{args:?}: {}", err(&o));
        assert_eq!(fs::read(&victim).unwrap(), b"precious", "{args:?}");
    }
    for written in [
        out,
        obj,
        shared.join("d.mtl"),
        figures.join("fig2-points.png"),
        figures.join("fig1-overview.png"),
        report.join("report.md"),
    ] {
        let m = fs::symlink_metadata(&written).unwrap();
        assert!(
            m.file_type().is_file(),
            "{} is not a file",
            written.display()
        );
    }
    // No temporary file is left behind: only the planted links, and what was written.
    let left: Vec<_> = fs::read_dir(&shared)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| !fs::symlink_metadata(p).unwrap().file_type().is_symlink())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    let mut left = left;
    left.sort();
    assert_eq!(left, ["d.mtl", "d.obj", "figures", "out.png", "report"]);
}

#[test]
fn a_long_output_name_is_written() {
    let dir = temp_dir("long-name");
    // 250 bytes: legal on every Linux file system; the temporary name is short.
    let name = format!("{}.png", "a".repeat(246));
    let o = run_in(Some(&dir), &["points", "--size", "8x6", "-o", &name]);
    assert!(o.status.success(), "{}", err(&o));
    assert!(dir.join(&name).is_file());
}

#[test]
fn a_link_another_user_planted_at_the_output_is_not_followed() {
    if !nobody_can_run_or_say_skipped() {
        return;
    }
    let root = temp_dir("planted-at-output");
    // /tmp's mode: anyone may write, only the owner may remove.
    let (shared, victim) = shared_folder_and_victim(&root, 0o1777);
    // And a folder of root's, for a link to a folder.
    let figures = root.join("figures");
    fs::create_dir(&figures).unwrap();
    fs::write(figures.join("fig2-points.png"), b"precious").unwrap();
    run_as_nobody(&format!(
        "ln -s {v} {d}/out.png; ln -s {v} {d}/m.obj; ln -s {f} {d}/figs",
        v = victim.display(),
        f = figures.display(),
        d = shared.display()
    ));
    // Root's own link to the planted one.
    std::os::unix::fs::symlink("out.png", shared.join("again.png")).unwrap();
    let path = |name: &str| shared.join(name).to_str().unwrap().to_owned();
    let (out, again, obj) = (path("out.png"), path("again.png"), path("m.obj"));
    let o = run(&["depth", "--size", "8x6", "-o", &out]);
    refused(&o, 1, "is a symbolic link made by another user (uid ");
    // A chain of links is refused at the first one not to be trusted.
    let o = run(&["depth", "--size", "8x6", "-o", &again]);
    refused(&o, 1, "leads through");
    let o = run(&["export", "-o", &obj]);
    refused(&o, 1, "not followed");
    // A link to a folder, planted where `all` was told to write its figures.
    let o = run(&["all", "--size", "8x6", "--out", &path("figs")]);
    refused(&o, 1, "it is a symbolic link");
    // Nor is a folder made through it.
    let o = run(&["all", "--size", "8x6", "--out", &path("figs/new")]);
    refused(&o, 1, "it lies in");
    assert_eq!(fs::read_dir(&figures).unwrap().count(), 1);
    assert_eq!(
        fs::read(figures.join("fig2-points.png")).unwrap(),
        b"precious"
    );
    assert_eq!(fs::read(&victim).unwrap(), b"precious");
    // Nothing else was left in the folder: the links, as they were.
    let mut left: Vec<_> = fs::read_dir(&shared)
        .unwrap()
        .map(|e| e.unwrap().path())
        .inspect(|p| assert!(fs::symlink_metadata(p).unwrap().is_symlink()))
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["again.png", "figs", "m.obj", "out.png"]);
    // The user's own links, and root's, are followed as before (tests/output.rs).
}

#[test]
fn a_normal_user_gets_a_clean_refusal_in_a_folder_it_cannot_write() {
    if !nobody_can_run_or_say_skipped() {
        return;
    }
    let dir = temp_dir("nobody-closed");
    fs::set_permissions(&*dir, fs::Permissions::from_mode(0o755)).unwrap();
    let out = dir.join("x.obj");
    let o = Command::new("runuser")
        .args([
            "-u",
            "nobody",
            "--",
            bin(),
            "export",
            "-o",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    refused(&o, 1, "Permission denied");
    assert!(fs::read_dir(&*dir).unwrap().next().is_none());
}

/// A FIFO that nobody writes to, named `name` in `dir`.
fn fifo(dir: &Path, name: &str) {
    let path = dir.join(name);
    assert!(Command::new("mkfifo")
        .arg(&path)
        .status()
        .unwrap()
        .success());
}

#[test]
fn fifos_are_refused_at_once_not_waited_on() {
    let dir = temp_dir("fifos");
    fifo(&dir, "model.obj");
    fifo(&dir, "tiles.png");
    fifo(&dir, "rows.txt");
    fifo(&dir, "shot.png");
    // A model whose material library, and one whose texture, is a FIFO.
    fifo(&dir, "lib.mtl");
    fs::write(
        dir.join("a.obj"),
        "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    fs::write(dir.join("b.mtl"), "newmtl m\nKd 1 1 1\nmap_Kd tiles.png\n").unwrap();
    fs::write(
        dir.join("b.obj"),
        "mtllib b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let cases: [(&[&str], &str); 6] = [
        (
            &["depth", "--scene", "model.obj", "-o", "x.png"],
            "model.obj: a FIFO",
        ),
        (
            &["pixel-light", "--texture", "tiles.png", "-o", "x.png"],
            "a FIFO",
        ),
        (
            &["depth", "--scene", "a.obj", "-o", "x.png"],
            "lib.mtl: a FIFO",
        ),
        (
            &["pixel-light", "--scene", "b.obj", "-o", "x.png"],
            "a FIFO",
        ),
        (&["check", "shot.png"], "a FIFO"),
        (
            &["check", "rows", "rows.txt", "10,5", "5,10", "15,15"],
            "a FIFO",
        ),
    ];
    for (args, needle) in cases {
        let o = run_in(Some(&dir), args);
        // check says "trouble" with 2, as diff and cmp do.
        refused(&o, if args[0] == "check" { 2 } else { 1 }, needle);
        assert!(!dir.join("x.png").exists());
    }
}

#[test]
fn devices_and_files_without_newlines_are_refused() {
    let dir = temp_dir("endless");
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.obj")).unwrap();
    let o = run_in(Some(&dir), &["depth", "--scene", "zero.obj", "-o", "x.png"]);
    refused(&o, 1, "zero.obj: a device, not a regular file");
    // 3 MB without a newline: refused at the line's bound, not held whole.
    fs::write(dir.join("long.obj"), vec![b'v'; 3 << 20]).unwrap();
    let o = run_in(Some(&dir), &["depth", "--scene", "long.obj", "-o", "x.png"]);
    refused(&o, 1, "long.obj: line 1: longer than 1048576 bytes");
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.txt")).unwrap();
    let o = run_in(
        Some(&dir),
        &["check", "rows", "zero.txt", "10,5", "5,10", "15,15"],
    );
    refused(&o, 2, "cannot read zero.txt: a device");
}

/// `args` run under an address-space limit of 2 GB (`ulimit -v`), less than a 16384x16384 frame with its depth buffer (2 GiB).
fn run_in_2gb(dir: &Path, args: &str) -> Output {
    run_capped(dir, 2_000_000, args)
}

/// `args` run in `dir` under an address-space limit of `kb` kilobytes.
fn run_capped(dir: &Path, kb: u32, args: &str) -> Output {
    Command::new("sh")
        .current_dir(dir)
        .args(["-c", &format!("ulimit -v {kb} && exec {} {args}", bin())])
        .output()
        .unwrap()
}

#[test]
fn frames_larger_than_memory_are_refused_not_aborted() {
    let dir = temp_dir("memory");
    for args in [
        "stress",
        "depth --size 16384x16384 -o big.png",
        "raytrace --flat --size 16384x16384 -o big.png",
    ] {
        let o = run_in_2gb(&dir, args);
        refused(&o, 1, "out of memory");
        assert!(err(&o).contains(" MB"), "{}", err(&o));
        assert!(fs::read_dir(&*dir).unwrap().next().is_none(), "{args}");
    }
    // Every frame of an animation is kept and encoded: without a limit on the
    // address space, 16384x16384 ran for minutes towards 60 GB.
    let o = run_in(
        Some(&dir),
        &["animate", "depth", "--size", "16384x16384", "-o", "big.gif"],
    );
    refused(
        &o,
        2,
        "animate draws at most 2048 pixels a side, not 16384x16384 (it keeps and encodes every frame)",
    );
    assert!(fs::read_dir(&*dir).unwrap().next().is_none());
}

/// A PNG whose header says `w` x `h` (and whose pixels are missing).
fn png_header(path: &Path, w: u32, h: u32) {
    let mut bytes = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend(w.to_be_bytes());
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([8, 2, 0, 0, 0]);
    bytes.extend(13u32.to_be_bytes());
    bytes.extend(&ihdr);
    bytes.extend(common::crc32(&ihdr).to_be_bytes());
    // An IDAT chunk (empty zlib data) ends the header for the decoder.
    let idat = [b"IDAT".as_slice(), &[0x78, 0x9c, 0x03, 0, 0, 0, 0, 1]].concat();
    bytes.extend(8u32.to_be_bytes());
    bytes.extend(&idat);
    bytes.extend(common::crc32(&idat).to_be_bytes());
    bytes.extend([0, 0, 0, 0]);
    bytes.extend(b"IEND");
    bytes.extend(common::crc32(b"IEND").to_be_bytes());
    fs::write(path, bytes).unwrap();
}

#[test]
fn huge_images_are_refused_from_their_header() {
    let dir = temp_dir("huge-images");
    png_header(&dir.join("shot.png"), 20000, 20000);
    png_header(&dir.join("wide.png"), 12000, 12000);
    png_header(&dir.join("tiles.png"), 70000, 10);
    let o = run_in_2gb(&dir, "check shot.png");
    refused(
        &o,
        2,
        "20000x20000 is too large for a screenshot of the lab (at most 4096",
    );
    let o = run_in_2gb(&dir, "check wide.png");
    refused(&o, 2, "12000x12000 is too large");
    let o = run_in_2gb(&dir, "pixel-light --texture tiles.png -o x.png");
    refused(&o, 1, "70000x10 is too large for a texture (at most 16384");
}

#[test]
fn export_checks_both_files_before_writing_either() {
    let dir = temp_dir("export-both");
    fs::create_dir(dir.join("d.obj")).unwrap();
    let o = run_in(Some(&dir), &["export", "-o", "d.obj"]);
    refused(&o, 1, "d.obj: it is a folder");
    assert!(!dir.join("d.mtl").exists());
    // An existing MTL is not overwritten when the OBJ cannot be written.
    fs::write(dir.join("d.mtl"), "mine").unwrap();
    let o = run_in(Some(&dir), &["export", "-o", "d.obj"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(fs::read_to_string(dir.join("d.mtl")).unwrap(), "mine");
}

#[test]
fn a_missing_folder_is_named_without_the_temporary_file() {
    let o = run(&["points", "--size", "8x6", "-o", "/nonexistent-folder/x.png"]);
    refused(
        &o,
        1,
        "cannot write /nonexistent-folder/x.png: No such file or directory (os error 2)",
    );
    assert!(!err(&o).contains("rasterlab-"), "{}", err(&o));
}

#[test]
fn a_file_where_a_folder_goes_is_named_so() {
    let dir = temp_dir("not-a-folder");
    fs::write(dir.join("f"), "").unwrap();
    let o = run_in(Some(&dir), &["all", "--out", "f"]);
    refused(&o, 1, "cannot write f: not a folder");
    let o = run_in(Some(&dir), &["check", "--out", "f", "f"]);
    assert_eq!(o.status.code(), Some(2), "{}", err(&o));
}

/// The RGB bytes of a BMP the binary wrote (rows bottom up, no padding at
/// these widths).
fn bmp_pixels(path: &Path) -> Vec<[u8; 3]> {
    let bytes = fs::read(path).unwrap();
    bytes[54..]
        .chunks_exact(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect()
}

#[test]
fn the_longest_focal_length_accepted_still_draws_what_rays_see() {
    let dir = temp_dir("focal");
    // At f = 1e9 the view is a sliver of the back wall: one colour, as the rays say.
    for args in [
        "depth --focal 1e9 --size 100x100 -o d.bmp",
        "raytrace --flat --focal 1e9 --size 100x100 -o r.bmp",
    ] {
        let o = run_in(Some(&dir), &args.split(' ').collect::<Vec<_>>());
        assert!(o.status.success(), "{}", err(&o));
    }
    let (d, r) = (
        bmp_pixels(&dir.join("d.bmp")),
        bmp_pixels(&dir.join("r.bmp")),
    );
    assert_eq!(d, r);
    assert!(
        d.iter().all(|p| *p == d[0] && *p != [0, 0, 0]),
        "{:?}",
        d[0]
    );
    let o = run(&["depth", "--focal", "1.1e9"]);
    refused(&o, 2, "at most 1e9 pixels");
}

/// The share of pixels that are not black in a BMP.
fn drawn_share(path: &Path) -> f64 {
    let px = bmp_pixels(path);
    px.iter().filter(|p| **p != [0, 0, 0]).count() as f64 / px.len() as f64
}

#[test]
fn scenes_of_any_framable_size_are_drawn_and_others_refused() {
    let dir = temp_dir("scene-sizes");
    let triangle = |s: f32| format!("v 0 0 0\nv {s} 0 0\nv 0 {s} 0\nf 1 2 3\n");
    fs::write(dir.join("tiny.obj"), triangle(1e-3)).unwrap();
    fs::write(dir.join("huge.obj"), triangle(1e30)).unwrap();
    // A model a millimetre across: framed, with the near plane scaled, so drawn.
    let o = run_in(Some(&dir), &["depth", "--scene", "tiny.obj", "-o", "t.bmp"]);
    assert!(o.status.success(), "{}", err(&o));
    assert!(err(&o).contains("--near 0.00000"), "{}", err(&o));
    let share = drawn_share(&dir.join("t.bmp"));
    assert!(share > 0.1, "{share}");
    for args in [
        &["depth", "--scene", "huge.obj", "-o", "h.bmp"][..],
        &["report", "--quick", "--scene", "huge.obj", "--out", "r"][..],
    ] {
        let o = run_in(Some(&dir), args);
        refused(&o, 1, "larger than f32 can frame");
    }
    assert!(!dir.join("h.bmp").exists() && !dir.join("r").exists());
    // A floor grid is looked down on: more than a row of pixels.
    let o = run_in(Some(&dir), &["depth", "--scene", "grid:200", "-o", "g.bmp"]);
    assert!(o.status.success(), "{}", err(&o));
    assert!(err(&o).contains("--pitch -35"), "{}", err(&o));
    let share = drawn_share(&dir.join("g.bmp"));
    assert!(share > 0.15, "{share}");
}

#[test]
fn what_a_model_asks_for_and_does_not_get_is_said() {
    let dir = temp_dir("model-warnings");
    fs::write(
        dir.join("m.mtl"),
        "newmtl hot\nKd 2 -0.5 0.5\nnewmtl tiles\nKd 1 1 1\nmap_Kd -s 2 2 1 -bm 0.5 my tiles.png\n",
    )
    .unwrap();
    // A 2 x 1 texture: left black, right white.
    let texture = rasterlab::Frame {
        width: 2,
        height: 1,
        color: vec![0, 0x00ff_ffff],
        depth: Vec::new(),
    };
    rasterlab::app::image_io::write_image(&texture, &dir.join("my tiles.png")).unwrap();
    let model =
        "mtllib m.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
                 usemtl hot\nf 1/1 2/2 3/3\nusemtl nowhere\nf 1/1 3/3 4/4\nf 1 2\nf 3 4\n\
                 usemtl tiles\nf 1/1 2/2 3/3 4/4\n";
    fs::write(dir.join("m.obj"), model).unwrap();
    let o = run_in(
        Some(&dir),
        &["pixel-light", "--scene", "m.obj", "-o", "m.png"],
    );
    assert!(o.status.success(), "{}", err(&o));
    let warnings = warnings(&o);
    assert_eq!(
        warnings,
        [
            "warning: m.obj: line 12: usemtl nowhere: no material of that name in the material libraries: its faces are grey",
            "warning: m.obj: line 14: a face needs at least three corners: left out (and 1 more such faces)",
            "warning: m.obj: material hot: Kd 2 -0.5 0.5 is outside [0, 1]: clamped to it",
            "warning: m.obj: material tiles: map_Kd option -bm is not supported: left out",
        ]
    );
    // -s 2 2 1 scales the coordinates: the file name is what follows the options.
    let (mesh, maps, _) = rasterlab::scene::read_obj(&dir.join("m.obj")).unwrap();
    let tiles = maps
        .materials
        .iter()
        .position(|m| m.texture.is_some())
        .unwrap();
    let face = mesh
        .faces
        .iter()
        .find(|f| f.material as usize == tiles)
        .unwrap();
    let uvs: Vec<_> = face
        .vertices
        .iter()
        .map(|&i| mesh.uvs[i as usize])
        .collect();
    assert!(
        uvs.iter().any(|t| *t == glam::Vec2::new(2.0, 2.0)),
        "{uvs:?}"
    );
}

#[test]
fn a_black_image_is_told_apart_without_contradiction() {
    let dir = temp_dir("black");
    let black = rasterlab::Frame::new(500, 500);
    rasterlab::app::image_io::write_image(&black, &dir.join("black.png")).unwrap();
    let o = run_in(Some(&dir), &["check", "black.png"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.starts_with("black.png is not a lab 3 image: the closest stage, points (Figure 2), matches 100 % of the image's pixels within 16/255 but only 0 % of the pixels it draws; a lab 3 screenshot matches over 90 % of both."),
        "{text}"
    );
}

#[test]
fn typos_get_a_suggestion_on_the_one_line() {
    let o = run(&["pixel-light", "--afine"]);
    refused(
        &o,
        2,
        "error: unexpected argument '--afine' found; tip: a similar argument exists: '--affine'",
    );
    let o = run(&["pixl-light"]);
    refused(&o, 2, "'pixel-light'");
}

// A second adversarial review (after `ee1ab91`): 16 more cases, each below.

/// `sh -c SCRIPT` in `dir`, where `$B` is the binary.
fn shell(dir: &Path, script: &str) -> Output {
    Command::new("sh")
        .current_dir(dir)
        .env("B", bin())
        .args(["-c", script])
        .output()
        .unwrap()
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\n";

/// An MTL file at `path` of `count` materials `m0`, `m1`, ..., each of colour `kd`.
fn materials(path: &Path, count: usize, kd: &str) {
    let text: String = (0..count)
        .map(|i| format!("newmtl m{i}\nKd {kd}\n"))
        .collect();
    fs::write(path, text).unwrap();
}

#[test]
fn the_least_whole_number_is_no_way_past_the_coordinate_limit() {
    // `i32::MIN.abs()` is itself: it passed the check and asked for 25 GB.
    for args in [
        ["rows", "--", "0,-2147483648", "0,0", "5,5"].as_slice(),
        &[
            "explain",
            "line",
            "-o",
            "e.png",
            "--",
            "-2147483648,0",
            "5,5",
        ],
    ] {
        let o = run(args);
        refused(&o, 2, "coordinates must be within -10000..10000");
    }
}

#[test]
fn standard_streams_that_cannot_be_written_lose_only_their_messages() {
    let dir = temp_dir("streams");
    // stderr full or gone: the image is still written, with the usual status.
    let o = shell(&dir, "$B depth -o p.png 2>/dev/full");
    assert_eq!(o.status.code(), Some(0));
    assert!(dir.join("p.png").is_file());
    let o = shell(&dir, "$B depth --size 0x0 2>/dev/full");
    assert_eq!(o.status.code(), Some(2));
    // Sent to /dev/null, write-only or read-write (Python's subprocess.DEVNULL,
    // and what Rust's runtime puts in place of a closed stream): written, as asked.
    for script in [
        "$B rows 10,5 5,10 15,15 >/dev/null",
        "$B rows 10,5 5,10 15,15 1<>/dev/null",
    ] {
        let o = shell(&dir, script);
        assert_eq!(o.status.code(), Some(0), "{script}: {}", err(&o));
    }
}

#[test]
fn a_model_file_cannot_write_to_the_terminal() {
    let dir = temp_dir("escapes");
    let model = format!("{TRIANGLE}usemtl \u{1b}]0;TITLE\u{7}\u{1b}[2Jm\nf 1 2 3\n");
    fs::write(dir.join("esc.obj"), model).unwrap();
    let o = run_in(Some(&dir), &["depth", "--scene", "esc.obj", "-o", "o.png"]);
    assert!(o.status.success(), "{}", err(&o));
    assert!(!o.stderr.contains(&0x1b) && !o.stderr.contains(&0x07));
    assert!(
        err(&o).contains("usemtl \\u{1b}]0;TITLE\\u{7}\\u{1b}[2Jm: no material"),
        "{}",
        err(&o)
    );
}

#[test]
fn a_library_named_again_and_again_is_read_once() {
    let dir = temp_dir("mtllib-again");
    materials(&dir.join("many.mtl"), 2000, "0.5 0.5 0.5");
    // tobj kept each reading's materials: 1000 lines of 20 000 took 3 GB.
    let model = format!(
        "{}{TRIANGLE}usemtl m5\nf 1 2 3\n",
        "mtllib many.mtl\n".repeat(1000)
    );
    fs::write(dir.join("rep.obj"), model).unwrap();
    let o = run_in_2gb(&dir, "depth --scene rep.obj -o o.png");
    assert!(o.status.success(), "{}", err(&o));
    let (mesh, _, _) = rasterlab::scene::read_obj(&dir.join("rep.obj")).unwrap();
    assert_eq!(mesh.materials.len(), 2000);
}

#[test]
fn a_texture_name_of_thousands_of_parts_is_looked_for_briefly() {
    let dir = temp_dir("long-name");
    let name = format!("{}/t.png", vec!["x"; 16000].join("/"));
    fs::write(
        dir.join("q.mtl"),
        format!("newmtl m\nKd .5 .5 .5\nmap_Kd {name}\n"),
    )
    .unwrap();
    let model =
        format!("mtllib q.mtl\n{TRIANGLE}vt 0 0\nvt 1 0\nvt 1 1\nusemtl m\nf 1/1 2/2 3/3\n");
    fs::write(dir.join("q.obj"), model).unwrap();
    // 47 s before; `run` gives up after 20.
    let o = run_in(Some(&dir), &["depth", "--scene", "q.obj", "-o", "o.png"]);
    assert!(o.status.success(), "{}", err(&o));
    let warning = err(&o).lines().next().unwrap().to_string();
    assert!(warning.contains("x/x/.../x/x"), "{warning}");
    assert!(
        warning.ends_with("/t.png is not there: its Kd is drawn instead"),
        "{warning}"
    );
    assert!(warning.len() < 300, "{warning}");
}

#[test]
fn a_texture_larger_than_memory_is_refused_before_decoding() {
    let dir = temp_dir("big-texture");
    // The header alone: the room for it is asked for before its pixels are read.
    png_header(&dir.join("big.png"), 16384, 16384);
    let o = run_in_2gb(&dir, "pixel-light --texture big.png -o o.png");
    refused(
        &o,
        1,
        "texture big.png: out of memory: its 16384x16384 texels need 5369 MB",
    );
    // A model's textures in all are bounded too.
    fs::write(
        dir.join("m.mtl"),
        "newmtl a\nmap_Kd big.png\nnewmtl b\nmap_Kd big2.png\n",
    )
    .unwrap();
    png_header(&dir.join("big2.png"), 16384, 2);
    let model = format!("mtllib m.mtl\n{TRIANGLE}vt 0 0\nvt 1 0\nvt 1 1\nusemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 2/2 3/3\n");
    fs::write(dir.join("m.obj"), model).unwrap();
    let e = rasterlab::scene::read_obj(&dir.join("m.obj"))
        .map(|_| ())
        .unwrap_err();
    assert!(
        e.ends_with("material b: map_Kd big2.png: the model's textures would hold more than 268435456 texels in all: refused"),
        "{e}"
    );
}

#[test]
fn what_the_formats_allow_and_the_lab_does_not_draw_is_left_out() {
    let dir = temp_dir("formats");
    // Polylines (tobj filled `l 1 2 3` as a face), vertex colours on some
    // vertices, old Mac line ends, a line continued with a backslash.
    let cases = [
        ("l", format!("{TRIANGLE}l 1 2 3\nf 1 2 3\nl 1 2\n")),
        (
            "colours",
            "v 0 0 0 1 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n".to_string(),
        ),
        ("mac", "v 0 0 0\rv 1 0 0\rv 1 1 0\rf 1 2 3\r".to_string()),
        (
            "continued",
            "v 0 0 \\\n0\nv 1 0 0\nv 1 1 0\nf 1 2 \\\n3\n".to_string(),
        ),
    ];
    let (plain, _, _) = {
        fs::write(dir.join("plain.obj"), format!("{TRIANGLE}f 1 2 3\n")).unwrap();
        rasterlab::scene::read_obj(&dir.join("plain.obj")).unwrap()
    };
    for (name, text) in cases {
        let path = dir.join(format!("{name}.obj"));
        fs::write(&path, text).unwrap();
        let (mesh, _, warnings) = rasterlab::scene::read_obj(&path).unwrap();
        assert_eq!(mesh.positions, plain.positions, "{name}");
        assert_eq!(mesh.faces.len(), 1, "{name}");
        let expected: Vec<String> = match name {
            "l" => vec![format!(
                "{}: line 4: a polyline (l) is not drawn: left out (and 1 more such lines)",
                path.display()
            )],
            _ => Vec::new(),
        };
        assert_eq!(warnings, expected, "{name}");
    }
    // MTL statements of the format that the lab does not draw from: left out,
    // where `d -halo` or `illum 2.0` stopped the model with "material parse error".
    fs::write(
        dir.join("t.mtl"),
        "newmtl m\nKd .8 .2 .2\nd -halo 0.5\nKa spectral ident.rfl 1.0\nKd xyz 0.5 0.5 0.5\nillum 2.0\nillum\nNs\nmap_Ka\nbump\n",
    )
    .unwrap();
    let path = dir.join("t.obj");
    fs::write(
        &path,
        format!("mtllib t.mtl\n{TRIANGLE}usemtl m\nf 1 2 3\n"),
    )
    .unwrap();
    let (mesh, _, warnings) = rasterlab::scene::read_obj(&path).unwrap();
    assert_eq!(mesh.materials[0].color, glam::Vec3::new(0.8, 0.2, 0.2));
    assert_eq!(
        warnings,
        [format!(
            "{}: material library {}: line 5: Kd xyz is not supported: left out",
            path.display(),
            dir.join("t.mtl").display()
        )]
    );
}

#[test]
fn a_scenes_warnings_are_printed_up_to_a_bound() {
    let dir = temp_dir("many-warnings");
    materials(&dir.join("w.mtl"), 200, "2 .5 .5");
    fs::write(
        dir.join("w.obj"),
        format!("mtllib w.mtl\n{TRIANGLE}f 1 2 3\n"),
    )
    .unwrap();
    let o = run_in(Some(&dir), &["depth", "--scene", "w.obj", "-o", "o.png"]);
    assert!(o.status.success(), "{}", err(&o));
    let warnings = warnings(&o);
    assert_eq!(warnings.len(), 65);
    assert_eq!(
        warnings[64],
        "warning: and 136 more warnings about the scene"
    );
}

/// The handout's Figure 5 and Figure 7 as PNG files in `dir`.
fn figures(dir: &Path) -> (PathBuf, PathBuf) {
    let write = |stage, name: &str| {
        let path = dir.join(name);
        let frame = common::render(stage, false);
        rasterlab::app::image_io::write_image(&frame, &path).unwrap();
        path
    };
    (
        write(rasterlab::StageName::Depth, "fig5.png"),
        write(rasterlab::StageName::PixelLight, "fig7.png"),
    )
}

#[test]
fn check_writes_neither_over_a_screenshot_nor_one_heat_map_over_another() {
    let dir = temp_dir("check-outputs");
    let (fig5, _) = figures(&dir);
    fs::copy(&fig5, dir.join("a.png")).unwrap();
    let before = fs::read(dir.join("a.png")).unwrap();
    // `--csv *.png`: the first screenshot taken as the table's name.
    let o = run_in(
        Some(&dir),
        &["check", "--csv", "a.png", "fig5.png", "fig7.png"],
    );
    refused(&o, 2, "--csv a.png: the table's file name must end in .csv");
    assert_eq!(fs::read(dir.join("a.png")).unwrap(), before);
    fs::copy(&fig5, dir.join("y.csv")).unwrap();
    let o = run_in(
        Some(&dir),
        &["check", "--csv", "y.csv", "y.csv", "fig7.png"],
    );
    refused(&o, 2, "--csv y.csv: it is one of the files to check");
    // x.png and x.bmp handed in together: a heat map and expected image each.
    fs::create_dir(dir.join("hx")).unwrap();
    fs::copy(&fig5, dir.join("hx/x.png")).unwrap();
    let frame = common::render(rasterlab::StageName::Depth, false);
    rasterlab::app::image_io::write_image(&frame, &dir.join("hx/x.bmp")).unwrap();
    let o = run_in(Some(&dir), &["check", "hx/x.png", "hx/x.bmp", "--out", "o"]);
    assert!(o.status.success(), "{}", err(&o));
    let mut written: Vec<String> = fs::read_dir(dir.join("o"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    written.sort();
    assert_eq!(
        written,
        [
            "x-2-expected.png",
            "x-2-heat.png",
            "x-expected.png",
            "x-heat.png"
        ]
    );
}

#[test]
fn a_cut_short_jpeg_is_refused_and_one_with_bytes_after_its_end_read() {
    let dir = temp_dir("jpeg-cut");
    let frame = common::render(rasterlab::StageName::Depth, false);
    image::save_buffer_with_format(
        dir.join("whole.jpg"),
        &frame.to_rgb8(),
        frame.width,
        frame.height,
        image::ExtendedColorType::Rgb8,
        image::ImageFormat::Jpeg,
    )
    .unwrap();
    let whole = fs::read(dir.join("whole.jpg")).unwrap();
    fs::write(dir.join("cut.jpg"), &whole[..whole.len() / 2]).unwrap();
    let o = run_in(Some(&dir), &["check", "cut.jpg"]);
    refused(
        &o,
        2,
        "cannot read cut.jpg: a damaged or cut-short JPEG image (its end marker is missing)",
    );
    let o = run_in(
        Some(&dir),
        &["pixel-light", "--texture", "cut.jpg", "-o", "t.png"],
    );
    refused(&o, 1, "a damaged or cut-short JPEG image");
    // Some cameras append data after the end marker.
    fs::write(
        dir.join("more.jpg"),
        [whole.as_slice(), b"trailer"].concat(),
    )
    .unwrap();
    let o = run_in(Some(&dir), &["check", "more.jpg"]);
    assert!(err(&o).is_empty(), "{}", err(&o));
    let report = String::from_utf8_lossy(&o.stdout);
    assert!(report.contains("Figure 5"), "{report}");
}

#[test]
fn the_exact_figure_found_with_a_light_searched_from_elsewhere_passes() {
    let dir = temp_dir("fit-light-status");
    let (_, fig7) = figures(&dir);
    let o = run(&[
        "check",
        fig7.to_str().unwrap(),
        "--light",
        "0,0,-3.001",
        "--fit-light",
    ]);
    let report = String::from_utf8_lossy(&o.stdout);
    assert!(report.contains("Every pixel matches"), "{report}");
    assert_eq!(o.status.code(), Some(0), "{report}");
}

#[test]
fn a_huge_unreadable_rows_line_is_named_not_echoed() {
    let dir = temp_dir("rows-long");
    let line = format!("Start: ({}1.5,0). End: (1,0).\n", "9".repeat(100_000));
    fs::write(dir.join("rows.txt"), line).unwrap();
    let o = run_in(
        Some(&dir),
        &["check", "rows", "rows.txt", "10,5", "5,10", "15,15"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", err(&o));
    assert!(err(&o).len() < 400, "{}", err(&o).len());
    assert!(err(&o).contains("...9999"), "{}", err(&o));
}

#[test]
fn export_says_what_its_files_cannot_carry() {
    let dir = temp_dir("export-names");
    // ` lead.obj` would name ` lead.mtl`, which loading trims to `lead.mtl`.
    let o = run_in(Some(&dir), &["export", "-o", " lead.obj"]);
    refused(
        &o,
        1,
        "the .mtl beside it would be named in a way the OBJ cannot name it",
    );
    assert!(fs::read_dir(&*dir).unwrap().next().is_none());
    // A model's map_Kd is read, and not written back.
    let texture = rasterlab::Frame {
        width: 1,
        height: 1,
        color: vec![0x00ff_ffff],
        depth: Vec::new(),
    };
    rasterlab::app::image_io::write_image(&texture, &dir.join("t.png")).unwrap();
    fs::write(dir.join("m.mtl"), "newmtl m\nKd 1 1 1\nmap_Kd t.png\n").unwrap();
    let model =
        format!("mtllib m.mtl\n{TRIANGLE}vt 0 0\nvt 1 0\nvt 1 1\nusemtl m\nf 1/1 2/2 3/3\n");
    fs::write(dir.join("m.obj"), model).unwrap();
    let o = run_in(
        Some(&dir),
        &["export", "--scene", "m.obj", "-o", "back.obj"],
    );
    assert!(o.status.success(), "{}", err(&o));
    assert_eq!(
        err(&o).lines().next(),
        Some("warning: the scene's textures are not written: its .mtl gives each material its Kd only")
    );
}

// A third look, at the second review's fixes and beyond them.

#[test]
fn a_scene_named_with_control_characters_is_shown_escaped() {
    let dir = temp_dir("escaped-name");
    let name = "x\u{1b}]0;PWN\u{7}\u{1b}[2J.obj";
    fs::write(dir.join(name), format!("{TRIANGLE}f 1 2 3\n")).unwrap();
    let o = run_in(Some(&dir), &["depth", "--scene", name, "-o", "d.png"]);
    assert!(o.status.success(), "{}", err(&o));
    assert!(!o.stderr.contains(&0x1b) && !o.stderr.contains(&0x07));
    assert!(err(&o).starts_with("scene x\\u{1b}]0;PWN\\u{7}\\u{1b}[2J (1 triangles)"));
    let o = run_in(Some(&dir), &["depth", "--size", "5\rxa", "-o", "d.png"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!o.stderr.contains(&b'\r'), "{}", err(&o));
}

#[test]
fn a_fifo_read_slowly_gets_the_whole_image() {
    let dir = temp_dir("slow-fifo");
    let fifo_path = dir.join("fo");
    fifo(&dir, "fo");
    // A reader that opens at once and reads only later: the image (66 928
    // bytes) is more than a pipe holds, and the writer must wait for it.
    let reader = {
        let path = fifo_path.clone();
        std::thread::spawn(move || {
            let mut f = fs::File::open(path).unwrap();
            std::thread::sleep(Duration::from_millis(500));
            let mut bytes = Vec::new();
            std::io::Read::read_to_end(&mut f, &mut bytes).unwrap();
            bytes
        })
    };
    std::thread::sleep(Duration::from_millis(100));
    let o = run_in(Some(&dir), &["depth", "--size", "2000x2000", "-o", "fo"]);
    assert!(o.status.success(), "{}", err(&o));
    let through_fifo = reader.join().unwrap();
    let o = run_in(Some(&dir), &["depth", "--size", "2000x2000", "-o", "d.png"]);
    assert!(o.status.success(), "{}", err(&o));
    assert!(through_fifo.len() > 65_536);
    assert_eq!(through_fifo, fs::read(dir.join("d.png")).unwrap());
}

#[test]
fn what_is_made_from_a_frame_is_counted_in_the_memory_asked_for() {
    let dir = temp_dir("memory-more");
    // 12000 x 12000 at 11 bytes a pixel fits in 2 GB; its depth buffer's
    // picture (4 more) does not, nor depth of field's sums (24 more) at 9000.
    for (args, size) in [
        ("depth --buffer --size 12000x12000 -o b.bmp", "12000x12000"),
        (
            "pixel-light --dof 4,0.05 --size 9000x9000 -o b.bmp",
            "9000x9000",
        ),
    ] {
        let o = run_in_2gb(&dir, args);
        refused(
            &o,
            1,
            &format!("out of memory: drawing and writing a {size} image needs"),
        );
        assert!(fs::read_dir(&*dir).unwrap().next().is_none(), "{args}");
    }
}

#[test]
fn the_files_of_a_model_are_bounded_in_lines_and_a_bare_map_kd_left_out() {
    let dir = temp_dir("model-bounds");
    // Four million blank lines and one more: a library past its bound.
    let blank = "\n".repeat(1 << 22);
    fs::write(
        dir.join("blank.mtl"),
        format!("newmtl m\n{blank}Kd 1 1 1\n"),
    )
    .unwrap();
    let path = dir.join("m.obj");
    fs::write(&path, format!("mtllib blank.mtl\n{TRIANGLE}f 1 2 3\n")).unwrap();
    let e = rasterlab::scene::read_obj(&path).map(|_| ()).unwrap_err();
    assert!(
        e.ends_with("line 4194306: more than 64 MB or 4194304 lines: too large to load"),
        "{e}"
    );
    fs::write(dir.join("bare.mtl"), "newmtl m\nKd 1 0 0\nmap_Kd\n").unwrap();
    fs::write(
        &path,
        format!("mtllib bare.mtl\n{TRIANGLE}usemtl m\nf 1 2 3\n"),
    )
    .unwrap();
    let (mesh, _, warnings) = rasterlab::scene::read_obj(&path).unwrap();
    assert_eq!(mesh.materials[0].color, glam::Vec3::X);
    assert!(
        warnings[0].ends_with("bare.mtl: line 3: map_Kd names no file: left out"),
        "{warnings:?}"
    );
    // A texture past the side allowed is refused for that, not for memory.
    png_header(&dir.join("huge.png"), 20000, 20000);
    let o = run_in_2gb(&dir, "pixel-light --texture huge.png -o x.png");
    refused(
        &o,
        1,
        "20000x20000 is too large for a texture (at most 16384",
    );
}

#[test]
fn a_report_without_light_compares_no_error_to_none() {
    let dir = temp_dir("report-unlit");
    let o = run_in(
        Some(&dir),
        &["report", "--quick", "--light-power", "0", "--out", "r"],
    );
    assert!(o.status.success(), "{}", err(&o));
    let report = fs::read_to_string(dir.join("r/report.md")).unwrap();
    // The tables' PSNR of an image equal to its reference is infinite; the
    // sentences compare errors in words.
    assert!(!report.contains("inf times"), "{report}");
    assert!(report.contains("its interior error is the same (RMSE 0.00 against 0.00)"));
    assert!(report.contains("(Figure 8) leaves the interior error as it is (RMSE 0.00"));
}

#[test]
fn help_that_cannot_be_written_fails() {
    let dir = temp_dir("help-full");
    for script in ["$B --help >/dev/full", "$B depth --help >/dev/full"] {
        let o = shell(&dir, script);
        assert_eq!(o.status.code(), Some(1), "{script}");
    }
}

// A fourth look (after `e3c5418`): the cases below.

/// A PNG at `path`: 8x8 grey pixels after an iCCP chunk whose profile, stored
/// without compression, inflates to `profile` zero bytes.
fn png_with_profile(path: &Path, profile: usize) {
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = !0u32;
        for &b in bytes {
            crc ^= b as u32;
            for _ in 0..8 {
                crc = (crc >> 1) ^ (0xEDB8_8320 & (crc & 1).wrapping_neg());
            }
        }
        !crc
    }
    fn chunk(out: &mut Vec<u8>, kind: &[u8], data: &[u8]) {
        out.extend((data.len() as u32).to_be_bytes());
        let start = out.len();
        out.extend(kind);
        out.extend(data);
        let crc = crc32(&out[start..]);
        out.extend(crc.to_be_bytes());
    }
    /// A zlib stream of `data` in stored blocks.
    fn stored(data: &[u8]) -> Vec<u8> {
        let mut z = vec![0x78, 0x01];
        let blocks: Vec<&[u8]> = data.chunks(65535).collect();
        for (i, block) in blocks.iter().enumerate() {
            z.push((i + 1 == blocks.len()) as u8);
            let n = block.len() as u16;
            z.extend(n.to_le_bytes());
            z.extend((!n).to_le_bytes());
            z.extend(*block);
        }
        let (mut a, mut b) = (1u32, 0u32);
        for &x in data {
            a = (a + x as u32) % 65521;
            b = (b + a) % 65521;
        }
        z.extend((b << 16 | a).to_be_bytes());
        z
    }
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut header = Vec::new();
    header.extend(8u32.to_be_bytes());
    header.extend(8u32.to_be_bytes());
    header.extend([8, 2, 0, 0, 0]);
    chunk(&mut png, b"IHDR", &header);
    let mut iccp = b"profile\0\0".to_vec();
    iccp.extend(stored(&vec![0; profile]));
    chunk(&mut png, b"iCCP", &iccp);
    let rows: Vec<u8> = (0..8)
        .flat_map(|_| [0].into_iter().chain([128; 24]))
        .collect();
    chunk(&mut png, b"IDAT", &stored(&rows));
    chunk(&mut png, b"IEND", &[]);
    fs::write(path, png).unwrap();
}

#[test]
fn images_with_nothing_to_read_or_too_much_metadata_are_refused() {
    let dir = temp_dir("fourth-images");
    // A GIF whose screen is 0 x 0 (the check panicked drawing a 0x0 depth buffer).
    let mut gif = b"GIF89a\0\0\0\0\x80\0\0\0\0\0\xff\xff\xff,".to_vec();
    gif.extend([0, 0, 0, 0, 1, 0, 1, 0, 0, 2, 2, 0x44, 1, 0, b';']);
    fs::write(dir.join("empty.gif"), gif).unwrap();
    let o = run_in(Some(&dir), &["check", "empty.gif"]);
    refused(&o, 2, "cannot read empty.gif: the image is empty (0x0)");
    // A colour profile of 17 MB on an 8x8 texture: refused before it is all
    // inflated (2 MB of profile inflated to 2 GB aborted under a memory cap).
    png_with_profile(&dir.join("profile.png"), 17 << 20);
    for args in [
        &["pixel-light", "--texture", "profile.png", "-o", "x.png"][..],
        &["check", "profile.png"],
    ] {
        let o = run_in(Some(&dir), args);
        let e = err(&o);
        assert!(!o.status.success(), "{args:?}");
        assert!(
            e.contains("a PNG image whose metadata (a colour profile or text) inflates past 16 MB"),
            "{args:?}: {e}"
        );
    }
    // A small profile is read past as before.
    png_with_profile(&dir.join("small.png"), 3000);
    let o = run_in(
        Some(&dir),
        &["pixel-light", "--texture", "small.png", "-o", "x.png"],
    );
    assert!(o.status.success(), "{}", err(&o));
}

#[test]
fn a_file_size_limit_is_an_error_and_leaves_no_temporary_file() {
    let dir = temp_dir("fourth-fsize");
    // 50 blocks of 1 KB: a 3000x3000 PNG does not fit (SIGXFSZ killed the
    // process silently, exit 153, and left the temporary file).
    let o = shell(
        &dir,
        "ulimit -f 50 && exec $B pixel-light --size 3000x3000 -o big.png",
    );
    let e = err(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("big.png") && e.contains("File too large"), "{e}");
    let left: Vec<_> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn a_folder_made_for_files_that_could_not_be_written_is_taken_away() {
    let dir = temp_dir("fifth-folder");
    fs::create_dir(dir.join("kept")).unwrap();
    // Under 50 blocks of 1 KB the 2000x2000 figures do not fit: the folders
    // all made (out, and out/figures inside it) go, one already there stays.
    for out in ["out/figures", "kept/figures"] {
        let o = shell(
            &dir,
            &format!("ulimit -f 50 && exec $B all --size 2000x2000 --out {out}"),
        );
        let e = err(&o);
        assert_eq!(o.status.code(), Some(1), "{e}");
        assert!(e.contains("File too large"), "{e}");
    }
    let mut left: Vec<_> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    left.sort();
    assert_eq!(left, ["kept"]);
    assert_eq!(fs::read_dir(dir.join("kept")).unwrap().count(), 0);
}

#[test]
fn an_output_over_another_users_file_takes_no_set_id_or_stranger_mode() {
    use std::os::unix::fs::{chown, MetadataExt};
    if !is_root() {
        eprintln!("skipped: not root");
        return;
    }
    let dir = temp_dir("fourth-mode");
    // nobody's file, set-user-ID, set-group-ID and writable by all: root's
    // output replacing it was all of those, and root's.
    let theirs = dir.join("theirs.png");
    fs::write(&theirs, b"x").unwrap();
    chown(&theirs, Some(65534), Some(65534)).unwrap();
    fs::set_permissions(&theirs, fs::Permissions::from_mode(0o6777)).unwrap();
    // Root's own, set-user-ID: keeps its other bits.
    let ours = dir.join("ours.png");
    fs::write(&ours, b"x").unwrap();
    fs::set_permissions(&ours, fs::Permissions::from_mode(0o4750)).unwrap();
    let fresh = dir.join("fresh.png");
    for out in [&theirs, &ours, &fresh] {
        let o = run(&["depth", "--size", "8x6", "-o", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", err(&o));
    }
    let mode = |p: &Path| fs::metadata(p).unwrap().mode() & 0o7777;
    assert_eq!(fs::metadata(&theirs).unwrap().uid(), 0);
    assert_eq!(
        mode(&theirs),
        mode(&fresh),
        "a stranger's file gets a new file's mode"
    );
    assert_eq!(mode(&fresh) & 0o7000, 0);
    assert_eq!(mode(&ours), 0o750);
}

#[test]
fn a_signal_while_writing_removes_the_temporary_file() {
    use std::os::unix::process::ExitStatusExt;
    let dir = temp_dir("fourth-signals");
    let temporaries = || {
        fs::read_dir(&dir)
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .file_name()
                    .to_string_lossy()
                    .ends_with(".tmp")
            })
            .count()
    };
    // Ctrl-C and kill while the PNG is being written (the temporary file was
    // left, empty or cut short, every time). The write takes a few tens of
    // milliseconds: tried until a signal lands inside it.
    for signal in [libc::SIGINT, libc::SIGTERM] {
        let mut landed = false;
        for _ in 0..20 {
            let mut child = Command::new(bin())
                .args(["pixel-light", "--size", "4000x4000", "-o", "big.png"])
                .current_dir(&dir)
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .unwrap();
            let start = Instant::now();
            while child.try_wait().unwrap().is_none() && temporaries() == 0 {
                assert!(start.elapsed() < Duration::from_secs(60));
                std::thread::sleep(Duration::from_micros(500));
            }
            // SAFETY: kill only sends a signal to the child, by its id.
            unsafe { libc::kill(child.id() as i32, signal) };
            let status = child.wait().unwrap();
            assert_eq!(temporaries(), 0, "signal {signal}: {status:?}");
            if status.signal() == Some(signal) {
                landed = true;
                break;
            }
            let _ = fs::remove_file(dir.join("big.png"));
        }
        assert!(landed, "signal {signal} never reached a write");
    }
}

#[test]
fn negative_whole_numbers_and_numbers_past_f32_are_named() {
    // "unexpected argument '-1' found" before, where other options gave the range.
    let o = run(&["raytrace", "--samples", "-1"]);
    refused(&o, 2, "expected a whole number from 1 to 16, got '-1'");
    let o = run(&["animate", "depth", "--delay", "-1"]);
    refused(&o, 2, "expected a whole number from 10 to 10000, got '-1'");
    // "a number is NaN or infinite" before: it is neither.
    let dir = temp_dir("fourth-numbers");
    fs::write(
        dir.join("big.obj"),
        "v 1e39 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n",
    )
    .unwrap();
    let o = run_in(Some(&dir), &["depth", "--scene", "big.obj", "-o", "x.png"]);
    refused(
        &o,
        1,
        "big.obj: line 1: 1e39 is past the largest number a coordinate holds (about 3.4e38)",
    );
}

// A fifth look (after `72a5a0d`): what the fourth left as it was.

#[test]
fn all_and_check_refuse_what_memory_cannot_hold_rather_than_abort() {
    let dir = temp_dir("fifth-memory");
    // Aborted in the overview's grid before, after fig2 to fig8 were written.
    for kb in [300_000, 390_000] {
        let o = run_capped(&dir, kb, "all --size 2048x2048 --focal 2048 --out figs");
        refused(&o, 1, "out of memory");
        assert!(err(&o).contains(" MB"), "{}", err(&o));
        let left = fs::read_dir(&*dir).unwrap().flat_map(|d| {
            let d = d.unwrap().path();
            match d.is_dir() {
                true => fs::read_dir(d)
                    .unwrap()
                    .map(|e| e.unwrap().path())
                    .collect(),
                false => vec![d],
            }
        });
        assert_eq!(left.count(), 0, "under {kb} KB");
    }
    // Aborted in a hypothesis's frame before.
    let o = run_in(
        Some(&dir),
        &[
            "pixel-light",
            "--size",
            "4096x4096",
            "--focal",
            "4096",
            "-o",
            "big.png",
        ],
    );
    assert!(o.status.success(), "{}", err(&o));
    let o = run_capped(&dir, 1_000_000, "check big.png");
    refused(
        &o,
        2,
        "cannot check big.png: out of memory: a 4096x4096 screenshot needs about 1343 MB to check",
    );
}

#[test]
fn all_and_report_write_every_file_or_none() {
    let dir = temp_dir("fifth-all-or-none");
    let figs = dir.join("figs");
    fs::create_dir(&figs).unwrap();
    fs::write(figs.join("fig2-points.png"), "mine").unwrap();
    // The fourth of seven figures cannot be written: before, fig2 to fig4
    // were new and fig5 on old.
    fs::create_dir(figs.join("fig5-depth.png")).unwrap();
    let o = run_in(Some(&dir), &["all", "--out", "figs"]);
    refused(&o, 1, "fig5-depth.png: it is a folder");
    let mut left: Vec<_> = fs::read_dir(&figs)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    left.sort();
    assert_eq!(left, ["fig2-points.png", "fig5-depth.png"]);
    assert_eq!(
        fs::read_to_string(figs.join("fig2-points.png")).unwrap(),
        "mine"
    );
    // The report's last file, after a minute of measuring.
    let out = dir.join("report");
    fs::create_dir(&out).unwrap();
    fs::write(out.join("report.md"), "mine").unwrap();
    fs::create_dir(out.join("heat-fig7-vs-fig8.png")).unwrap();
    let o = run_in(Some(&dir), &["report", "--quick", "--out", "report"]);
    refused(&o, 1, "heat-fig7-vs-fig8.png: it is a folder");
    assert_eq!(fs::read_to_string(out.join("report.md")).unwrap(), "mine");
    assert_eq!(fs::read_dir(&out).unwrap().count(), 2);
}

#[test]
fn check_says_which_folders_it_does_not_look_into() {
    // Passed over without a word before.
    let dir = temp_dir("fifth-deep");
    let mut deep = dir.join("course");
    for k in 1..=18 {
        deep = deep.join(format!("d{k}"));
    }
    fs::create_dir_all(&deep).unwrap();
    fs::create_dir_all(dir.join("course/d1/e2")).unwrap();
    let figure = Path::new(env!("CARGO_MANIFEST_DIR")).join("steps/fig5-depth.png");
    fs::copy(&figure, deep.join("shot.png")).unwrap();
    fs::copy(&figure, dir.join("course/d1/shot.png")).unwrap();
    // A link to a folder made a row "unreadable ... a folder, not a regular
    // file" and the exit status 1.
    std::os::unix::fs::symlink("..", dir.join("course/d1/up")).unwrap();
    let o = run_in(Some(&dir), &["check", "course"]);
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("1 files: matches 1"), "{out}");
    let deep: String = (1..=17).map(|k| format!("/d{k}")).collect();
    assert_eq!(
        warnings(&o),
        [
            format!("warning: course{deep} is more than 16 folders down: not looked into"),
            "warning: course/d1/up is a link to a folder: not followed".to_string()
        ]
    );
}

#[test]
fn models_and_scenes_larger_than_memory_are_refused_not_aborted() {
    let dir = temp_dir("fifth-model-memory");
    // Aborted in tobj (exit 134) under 150 to 300 MB before.
    let o = run_in(
        Some(&dir),
        &["export", "--scene", "grid:1000000", "-o", "g.obj"],
    );
    assert!(o.status.success(), "{}", err(&o));
    let o = run_capped(&dir, 250_000, "depth --size 64x64 --scene g.obj -o x.png");
    refused(
        &o,
        1,
        "g.obj: out of memory: its 94 MB need about 376 MB to load",
    );
    let o = run_capped(
        &dir,
        300_000,
        "depth --size 64x64 --scene sphere:4000000 -o x.png",
    );
    refused(
        &o,
        1,
        "out of memory: scene sphere:4000000 needs about 320 MB",
    );
    assert!(!dir.join("x.png").exists());
}

#[test]
fn standard_output_by_its_system_name_is_written_into_a_redirected_file() {
    // "its name has no ending to choose the image format by" before.
    let dir = temp_dir("fifth-stdout");
    let o = Command::new("sh")
        .current_dir(&*dir)
        .args([
            "-c",
            &format!("exec {} depth -o /dev/stdout > s.png", bin()),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", err(&o));
    let o = run_in(Some(&dir), &["depth", "-o", "f.png"]);
    assert!(o.status.success(), "{}", err(&o));
    assert_eq!(
        fs::read(dir.join("s.png")).unwrap(),
        fs::read(dir.join("f.png")).unwrap()
    );
}

#[test]
fn check_reads_a_window_dump_without_alpha_and_not_its_own_pictures() {
    let dir = temp_dir("fifth-check");
    let figure = Path::new(env!("CARGO_MANIFEST_DIR")).join("steps/fig5-depth.png");
    // An OpenGL read-back: Figure 5's colours, alpha 0 everywhere. Seen over
    // white before: "one colour, (255, 255, 255)".
    let rgb = image::open(&figure).unwrap().to_rgb8();
    let mut rgba = image::RgbaImage::new(rgb.width(), rgb.height());
    for (o, p) in rgba.pixels_mut().zip(rgb.pixels()) {
        *o = image::Rgba([p[0], p[1], p[2], 0]);
    }
    rgba.save(dir.join("dump.png")).unwrap();
    let o = run_in(Some(&dir), &["check", "dump.png"]);
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    // `--out` the folder being checked: the second run checked the first's
    // heat map and expected image as students' files.
    fs::create_dir(dir.join("course")).unwrap();
    fs::copy(&figure, dir.join("course/shot.png")).unwrap();
    for _ in 0..2 {
        let o = run_in(Some(&dir), &["check", "course", "--out", "course"]);
        assert_eq!(o.status.code(), Some(0), "{}", err(&o));
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(out.contains("\n1 files: matches 1,"), "{out}");
    }
    assert_eq!(fs::read_dir(dir.join("course")).unwrap().count(), 3);
}

#[test]
fn valid_images_in_forms_not_read_are_not_called_damaged() {
    // "a damaged or cut-short JPEG image (... can only parse 8-bit images ...)"
    // before, and so for the BMPs.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/unusual");
    for (file, form) in [
        ("jpeg-12-bit.jpg", "a JPEG image in a form not read here ("),
        ("bmp-os2-v2.bmp", "a BMP image in a form not read here ("),
        (
            "bmp-jpeg-compressed.bmp",
            "a BMP image in a form not read here (",
        ),
    ] {
        let path = dir.join(file).display().to_string();
        let o = run(&["check", &path]);
        refused(&o, 2, &format!("cannot read {path}: {form}"));
        let o = run(&["pixel-light", "--texture", &path, "-o", "/dev/null"]);
        refused(&o, 1, form);
    }
}
