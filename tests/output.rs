//! Where images go: regular files through a temporary file and a rename, the
//! user's own symbolic links followed to their targets, devices and FIFOs
//! written in place, `-` to standard output, the format from the name; the same
//! as a normal user.

use crate::common;
use common::temp_dir;
use std::fs;
use std::io::Read;
use std::os::unix::fs::{FileTypeExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

const PNG_MAGIC: &[u8] = b"\x89PNG\r\n\x1a\n";

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_rasterlab")
}

/// `rasterlab points --size 8x6 -o OUT`, run as `user` when given (via runuser).
fn points_to(out: &Path, user: Option<&str>) -> Output {
    let args = ["points", "--size", "8x6", "-o", out.to_str().unwrap()];
    let mut cmd = match user {
        Some(u) => {
            let mut c = Command::new("runuser");
            c.args(["-u", u, "--", bin()]);
            c
        }
        None => Command::new(bin()),
    };
    cmd.args(args).output().unwrap()
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn is_png_of(bytes: &[u8], w: u32, h: u32) -> bool {
    bytes.starts_with(PNG_MAGIC)
        && u32::from_be_bytes(bytes[16..20].try_into().unwrap()) == w
        && u32::from_be_bytes(bytes[20..24].try_into().unwrap()) == h
}

/// The cases that a normal user meets as well as root: a symbolic link, a FIFO
/// and standard output.
fn links_fifos_and_stdout(dir: &Path, user: Option<&str>) {
    // A link to an existing file: the file is replaced, the link stays a link.
    let target = dir.join("target.png");
    fs::write(&target, b"old").unwrap();
    let link = dir.join("link.png");
    std::os::unix::fs::symlink("target.png", &link).unwrap();
    let o = points_to(&link, user);
    assert!(o.status.success(), "{}", err(&o));
    assert!(fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(is_png_of(&fs::read(&target).unwrap(), 8, 6));
    // A dangling link: its target is created.
    let dangling = dir.join("dangling.png");
    std::os::unix::fs::symlink("made.png", &dangling).unwrap();
    let o = points_to(&dangling, user);
    assert!(o.status.success(), "{}", err(&o));
    assert!(is_png_of(&fs::read(dir.join("made.png")).unwrap(), 8, 6));

    // A FIFO: written into, and still a FIFO afterwards.
    let fifo = dir.join("pipe.png");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    fs::set_permissions(&fifo, fs::Permissions::from_mode(0o666)).unwrap();
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            fs::File::open(fifo)
                .unwrap()
                .read_to_end(&mut bytes)
                .unwrap();
            bytes
        })
    };
    let o = points_to(&fifo, user);
    assert!(o.status.success(), "{}", err(&o));
    assert!(is_png_of(&reader.join().unwrap(), 8, 6));
    assert!(fs::metadata(&fifo).unwrap().file_type().is_fifo());

    // Standard output.
    let o = points_to(Path::new("-"), user);
    assert!(o.status.success(), "{}", err(&o));
    assert!(is_png_of(&o.stdout, 8, 6));
    assert!(err(&o).contains("wrote standard output"), "{}", err(&o));
}

#[test]
fn links_fifos_and_standard_output() {
    let dir = temp_dir("output");
    links_fifos_and_stdout(&dir, None);
}

#[test]
fn links_fifos_and_standard_output_as_a_normal_user() {
    // Only root can switch user; as a normal user the test above already is this.
    let root = Command::new("id").arg("-u").output().unwrap().stdout == b"0\n";
    let runuser = Command::new("runuser")
        .arg("--help")
        .stdout(Stdio::null())
        .status();
    if !root || runuser.is_err() {
        eprintln!("skipped: not root, or no runuser");
        return;
    }
    let dir = temp_dir("output-nobody");
    fs::set_permissions(&*dir, fs::Permissions::from_mode(0o777)).unwrap();
    // The binary must be reachable by that user.
    let reachable = Command::new("runuser")
        .args(["-u", "nobody", "--", bin(), "--version"])
        .output()
        .unwrap();
    if !reachable.status.success() {
        eprintln!("skipped: nobody cannot run {}", bin());
        return;
    }
    links_fifos_and_stdout(&dir, Some("nobody"));
    // And a folder that user may not write to: a one-line failure, nothing written.
    let closed = dir.join("closed");
    fs::create_dir(&closed).unwrap();
    fs::set_permissions(&closed, fs::Permissions::from_mode(0o755)).unwrap();
    let o = points_to(&closed.join("x.png"), Some("nobody"));
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    assert_eq!(err(&o).lines().count(), 1, "{}", err(&o));
    assert!(fs::read_dir(&closed).unwrap().next().is_none());
}

#[test]
fn dev_stdout_into_a_pipe_is_standard_output() {
    // /dev/stdout leads to /proc/self/fd/1, whose target ("pipe:[...]") is no path.
    let o = points_to(Path::new("/dev/stdout"), None);
    assert!(o.status.success(), "{}", err(&o));
    assert!(is_png_of(&o.stdout, 8, 6));
}

#[test]
fn devices_are_written_into_not_replaced() {
    let null = PathBuf::from("/dev/null");
    let o = points_to(&null, None);
    assert!(o.status.success(), "{}", err(&o));
    assert!(fs::metadata(&null).unwrap().file_type().is_char_device());
}

#[test]
fn the_format_follows_the_name() {
    let dir = temp_dir("formats");
    let bmp = dir.join("p.BMP");
    let o = points_to(&bmp, None);
    assert!(o.status.success(), "{}", err(&o));
    let bytes = fs::read(&bmp).unwrap();
    assert!(bytes.starts_with(b"BM"), "a BMP");
    let (w, h, _) = rasterlab::app::image_io::read_rgb(&bmp).unwrap();
    assert_eq!((w, h), (8, 6));
    for name in ["p.jpg", "p"] {
        let o = points_to(&dir.join(name), None);
        assert_eq!(o.status.code(), Some(2), "{}", err(&o));
        assert_eq!(err(&o).lines().count(), 1, "{}", err(&o));
        assert!(err(&o).contains(".png or .bmp"), "{}", err(&o));
        assert!(!dir.join(name).exists());
    }
}

#[test]
fn an_existing_file_keeps_its_permissions() {
    let dir = temp_dir("permissions");
    let out = dir.join("p.png");
    fs::write(&out, b"old").unwrap();
    fs::set_permissions(&out, fs::Permissions::from_mode(0o640)).unwrap();
    let o = points_to(&out, None);
    assert!(o.status.success(), "{}", err(&o));
    assert_eq!(
        fs::metadata(&out).unwrap().permissions().mode() & 0o777,
        0o640
    );
    assert!(is_png_of(&fs::read(&out).unwrap(), 8, 6));
}

#[test]
fn a_closed_pipe_stops_quietly_and_fails() {
    // The reader goes away before anything is written: no panic, no backtrace,
    // no claim that anything was written, and a failing exit status.
    for args in [
        &["pixel-light", "-o", "-"][..],
        &["rows", "10,5", "5,10", "15,15"][..],
    ] {
        // A pipe whose reading end is closed before the command starts: its
        // first write fails, however soon it comes.
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let o = Command::new(bin())
            .args(args)
            .stdout(writer)
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", err(&o));
        assert_eq!(err(&o), "", "{args:?}");
    }
}
