//! Writing images and text without ever leaving a half-written file behind, or
//! writing through a file that someone else planted.
//!
//! - A regular file (or a new one) is written to a temporary file beside it, which
//!   is then renamed into place. The temporary file is created exclusively, with
//!   an unpredictable short name (`tempfile`), so a link planted under the name it
//!   will have cannot redirect the write and a long output name still fits.
//! - A symbolic link is followed: its target is replaced that way, the link stays.
//!   Only a link of the user running the command, or of root, is followed: one
//!   that another user made may have been planted for it, to point at a file
//!   that user may not write (root writing `/shared/out.png`, a link to
//!   `/etc/passwd`). Such a path is refused instead, as is one whose folders
//!   include such a link.
//! - Anything else that exists (a device such as /dev/null, a FIFO) is written
//!   directly, since renaming over it would replace it.
//! - `-` is standard output. A reader that closes it early (`| head`) stops the
//!   output quietly, but the command fails: nothing claims it was written.
//!
//! The image format follows the name: `.png` or `.bmp`.

use crate::pipeline::Frame;
use std::fmt;
use std::fs;
use std::io::{self, BufWriter, Write};
use std::os::unix::fs::{MetadataExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Why an image could not be written; the message names the path.
#[derive(Debug)]
pub struct WriteError {
    pub path: PathBuf,
    pub reason: String,
    /// The reader of standard output went away: say nothing more, but fail.
    pub closed_early: bool,
}

impl WriteError {
    pub fn new(path: &Path, reason: impl Into<String>) -> Self {
        WriteError {
            path: path.to_path_buf(),
            reason: reason.into(),
            closed_early: false,
        }
    }
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot write {}: {}", describe(&self.path), self.reason)
    }
}

impl std::error::Error for WriteError {}

/// The image formats a name can ask for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    Png,
    Bmp,
}

impl ImageFormat {
    /// The format `path`'s extension names; `-` (standard output) is PNG.
    pub fn of(path: &Path) -> Option<ImageFormat> {
        if path.as_os_str() == "-" {
            return Some(ImageFormat::Png);
        }
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(ImageFormat::Png),
            "bmp" => Some(ImageFormat::Bmp),
            _ => None,
        }
    }
}

/// How a written path is named in messages: "standard output" for `-`.
pub fn describe(path: &Path) -> String {
    if path.as_os_str() == "-" {
        "standard output".into()
    } else {
        super::streams::printable(&path.display().to_string())
    }
}

/// Writes `frame` to `path` as 8-bit RGB in the format its name asks for.
pub fn write_image(frame: &Frame, path: &Path) -> Result<(), WriteError> {
    let rgb = frame
        .try_to_rgb8()
        .map_err(|why| WriteError::new(path, why))?;
    write_rgb(&rgb, frame.width, frame.height, path)
}

/// Writes 8-bit RGB rows to `path` in the format its name asks for (PNG when the
/// name says nothing). A file is encoded straight into its temporary file, so a
/// large image needs no second copy in memory; standard output and devices get
/// the image encoded whole first, so nothing is written on failure.
pub fn write_rgb(rgb: &[u8], width: u32, height: u32, path: &Path) -> Result<(), WriteError> {
    let format = ImageFormat::of(path).unwrap_or(ImageFormat::Png);
    write_with(path, |out| encode(out, format, rgb, width, height))
}

/// 8-bit RGB rows encoded as `format` into `out`.
fn encode(
    mut out: &mut dyn Write,
    format: ImageFormat,
    rgb: &[u8],
    width: u32,
    height: u32,
) -> io::Result<()> {
    let encoded = match format {
        ImageFormat::Png => image::ImageEncoder::write_image(
            image::codecs::png::PngEncoder::new(&mut *out),
            rgb,
            width,
            height,
            image::ExtendedColorType::Rgb8,
        ),
        ImageFormat::Bmp => image::ImageEncoder::write_image(
            image::codecs::bmp::BmpEncoder::new(&mut out),
            rgb,
            width,
            height,
            image::ExtendedColorType::Rgb8,
        ),
    };
    encoded.map_err(|e| match e {
        image::ImageError::IoError(e) => e,
        e => io::Error::other(e.to_string()),
    })
}

/// Writes text to `path` (see the module's rules).
pub fn write_text(path: &Path, text: &str) -> Result<(), WriteError> {
    write_bytes(path, text.as_bytes())
}

/// Writes `bytes` to `path` by the module's rules.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    write_with(path, |out| out.write_all(bytes))
}

/// Where a path's bytes go.
enum Destination {
    Stdout,
    /// A device or a FIFO: written into directly.
    Special(PathBuf),
    /// A regular file, or a new one: replaced by a renamed temporary file.
    File(PathBuf),
}

/// Whether `path` names standard output: `-`, or one of the system's names
/// for it, which may stand for a file the shell opened (`-o /dev/stdout >
/// x.png`): written through the stream, not by renaming over that file.
pub fn names_stdout(path: &Path) -> bool {
    let names = ["-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"];
    names.iter().any(|n| path.as_os_str() == *n)
}

fn destination(path: &Path) -> Result<Destination, WriteError> {
    if names_stdout(path) {
        return Ok(Destination::Stdout);
    }
    let target = follow_links(path).map_err(|why| WriteError::new(path, why))?;
    let special = |m: &fs::Metadata| !m.is_file() && !m.is_dir();
    match fs::metadata(&target) {
        Ok(m) if m.is_dir() => Err(WriteError::new(path, "it is a folder")),
        Ok(m) if special(&m) => Ok(Destination::Special(target)),
        // A link of /proc (/dev/stdout to /proc/self/fd/1 to "pipe:[...]")
        // names no path; only the kernel can open what it stands for.
        Err(_) if fs::metadata(path).is_ok_and(|m| special(&m)) => {
            Ok(Destination::Special(path.to_path_buf()))
        }
        _ => Ok(Destination::File(target)),
    }
}

/// Runs `write` into `path`'s destination by the module's rules.
pub fn write_with(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<(), WriteError> {
    match destination(path)? {
        Destination::File(target) => {
            let staged = stage(path, &target, write)?;
            commit(path, staged)
        }
        Destination::Stdout => {
            let mut bytes = Vec::new();
            write(&mut bytes).map_err(|e| WriteError::new(path, e.to_string()))?;
            let mut out = io::stdout().lock();
            out.write_all(&bytes)
                .and_then(|()| out.flush())
                .map_err(|e| WriteError {
                    closed_early: e.kind() == io::ErrorKind::BrokenPipe,
                    ..WriteError::new(path, e.to_string())
                })
        }
        Destination::Special(target) => {
            let mut bytes = Vec::new();
            write(&mut bytes).map_err(|e| WriteError::new(path, e.to_string()))?;
            // O_NONBLOCK: a FIFO with no reader is an error, not a wait.
            let mut f = fs::OpenOptions::new()
                .write(true)
                .custom_flags(libc::O_NONBLOCK)
                .open(&target)
                .map_err(|e| match e.raw_os_error() {
                    Some(libc::ENXIO) => WriteError::new(path, "a FIFO that nothing reads"),
                    _ => WriteError::new(path, e.to_string()),
                })?;
            // Opened: now a reader slower than the writer is waited for, not
            // left with the image's first 64 KB.
            let fd = std::os::fd::AsRawFd::as_raw_fd(&f);
            // SAFETY: F_GETFL and F_SETFL change only the flags of `f`'s descriptor.
            unsafe {
                let flags = libc::fcntl(fd, libc::F_GETFL);
                if flags != -1 {
                    libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK);
                }
            }
            f.write_all(&bytes)
                .map_err(|e| WriteError::new(path, e.to_string()))
        }
    }
}

/// Files written as one, each staged in full as it comes (so only one image is
/// held encoded at a time) and all renamed into place by [`AllOrNone::commit`]:
/// a file that cannot be written leaves every other as it was, the figures of
/// `all` and the files of `report` as much as an OBJ and its MTL. Dropped
/// without a commit, it removes what it staged.
#[derive(Default)]
pub struct AllOrNone {
    staged: Vec<(PathBuf, Staged)>,
}

impl AllOrNone {
    /// Stages `frame` as the image `path` names (8-bit RGB).
    pub fn image(&mut self, frame: &Frame, path: &Path) -> Result<(), WriteError> {
        let rgb = frame
            .try_to_rgb8()
            .map_err(|why| WriteError::new(path, why))?;
        let format = ImageFormat::of(path).unwrap_or(ImageFormat::Png);
        self.file(path, |out| {
            encode(out, format, &rgb, frame.width, frame.height)
        })
    }

    /// Stages `bytes` as the file `path`.
    pub fn bytes(&mut self, path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
        self.file(path, |out| out.write_all(bytes))
    }

    fn file(
        &mut self,
        path: &Path,
        write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
    ) -> Result<(), WriteError> {
        match destination(path)? {
            Destination::File(target) => {
                let staged = stage(path, &target, write)?;
                self.staged.push((path.to_path_buf(), staged));
                Ok(())
            }
            _ => Err(WriteError::new(
                path,
                "not a regular file: files that belong together are written as files",
            )),
        }
    }

    /// Renames every staged file into place, in the order staged.
    pub fn commit(self) -> Result<(), WriteError> {
        for (path, staged) in self.staged {
            commit(&path, staged)?;
        }
        Ok(())
    }
}

/// A temporary file written in full, and the name it will take.
struct Staged {
    file: tempfile::NamedTempFile,
    target: PathBuf,
    _live: Live,
}

/// The temporary files being written, removed if a signal ends the process.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// A temporary file's place in [`LIVE`], from its making until it is renamed
/// or removed.
struct Live(PathBuf);

impl Live {
    /// The temporary file `make` makes, listed while the list is held: a
    /// signal that comes as it is made has its removal wait until it is listed.
    fn make(
        make: impl FnOnce() -> io::Result<tempfile::NamedTempFile>,
    ) -> io::Result<(tempfile::NamedTempFile, Live)> {
        let mut files = live();
        let file = make()?;
        files.push(file.path().to_path_buf());
        let listed = Live(file.path().to_path_buf());
        Ok((file, listed))
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        let mut files = live();
        if let Some(i) = files.iter().position(|p| *p == self.0) {
            files.swap_remove(i);
        }
    }
}

/// Nothing is written while the list is held, so no panic can poison it.
fn live() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Ctrl-C, `kill` and a terminal closed (SIGINT, SIGTERM, SIGHUP) end the
/// process as they would, but first remove the temporary files being
/// written, which their default action left behind. The signals are blocked
/// in every thread and waited for by one of their own, so nothing runs in a
/// signal handler; one the process was started ignoring (`nohup`, a job in
/// the background) stays ignored. Called first in `main`, before any thread
/// starts.
pub fn remove_temporaries_on_signals() {
    // SAFETY: the sigset is initialised by sigemptyset before use; the calls
    // change only this process's signal mask and dispositions.
    unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for signal in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            let mut old: libc::sigaction = std::mem::zeroed();
            let ignored = libc::sigaction(signal, std::ptr::null(), &mut old) == 0
                && old.sa_sigaction == libc::SIG_IGN;
            if !ignored {
                libc::sigaddset(&mut set, signal);
            }
        }
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return;
        }
        let waiting = std::thread::Builder::new()
            .name("signals".into())
            .spawn(move || {
                let mut signal = 0;
                if libc::sigwait(&set, &mut signal) != 0 {
                    return;
                }
                for path in live().iter() {
                    let _ = fs::remove_file(path);
                }
                // Ended by the signal, as without this thread: its default
                // action, raised where it is not blocked.
                libc::signal(signal, libc::SIG_DFL);
                libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
                libc::raise(signal);
            });
        if waiting.is_err() {
            // No thread to wait for them: taken as they came.
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
        }
    }
}

/// Writes a temporary file beside `target`: created exclusively (a name that
/// exists, a planted link included, is never opened), with a short random name,
/// and the permissions an existing `target` of the running user's has
/// ([`kept_mode`]; a new one gets 0666 less the umask, as any new file). On
/// failure it is removed.
fn stage(
    path: &Path,
    target: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<Staged, WriteError> {
    // tempfile names its random file in errors ("... at path \"dir/.rasterlab-x.tmp\""):
    // the user named `path`, which the message already holds.
    let fail = |e: io::Error| {
        let why = e.to_string();
        let why = why.split(" at path \"").next().unwrap_or_default();
        WriteError::new(path, why)
    };
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let (file, live) = Live::make(|| {
        tempfile::Builder::new()
            .prefix(".rasterlab-")
            .suffix(".tmp")
            .permissions(fs::Permissions::from_mode(0o666))
            .tempfile_in(dir)
    })
    .map_err(fail)?;
    let mut out = BufWriter::new(file);
    write(&mut out).map_err(fail)?;
    let file = out.into_inner().map_err(|e| fail(e.into_error()))?;
    if let Some(mode) = fs::metadata(target).ok().and_then(|m| kept_mode(&m)) {
        file.as_file()
            .set_permissions(fs::Permissions::from_mode(mode))
            .map_err(fail)?;
    }
    Ok(Staged {
        file,
        target: target.to_path_buf(),
        _live: live,
    })
}

fn commit(path: &Path, staged: Staged) -> Result<(), WriteError> {
    staged
        .file
        .persist(&staged.target)
        .map(drop)
        .map_err(|e| WriteError::new(path, e.error.to_string()))
}

/// Refuses `path` if it is, or passes through, a link another user made (as
/// every write here does), before anything is made there.
pub fn refuse_planted_links(path: &Path) -> Result<(), WriteError> {
    follow_links(path)
        .map(drop)
        .map_err(|why| WriteError::new(path, why))
}

/// The file a path finally names: symbolic links followed (relative targets from
/// the link's folder), up to 40 of them, each one, and each folder on the way
/// that is a link, the running user's or root's.
fn follow_links(path: &Path) -> Result<PathBuf, String> {
    let refused = |what: String, uid: u32| {
        format!(
            "{what} made by another user (uid {uid}): not followed, as it may \
             have been planted; remove it or name what it points to"
        )
    };
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        // A planted link to a folder redirects the write as well as one to a file.
        for folder in p.ancestors().skip(1) {
            if let Some(uid) = fs::symlink_metadata(folder)
                .ok()
                .and_then(|m| untrusted(&m))
            {
                let what = format!("it lies in {}, a symbolic link", folder.display());
                return Err(refused(what, uid));
            }
        }
        match fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                if let Some(uid) = untrusted(&m) {
                    let what = match p == path {
                        true => "it is a symbolic link".to_string(),
                        false => format!("it leads through {}, a symbolic link", p.display()),
                    };
                    return Err(refused(what, uid));
                }
                let to = fs::read_link(&p).map_err(|e| e.to_string())?;
                p = match p.parent() {
                    Some(dir) if to.is_relative() => dir.join(to),
                    _ => to,
                };
            }
            _ => return Ok(p),
        }
    }
    Err("too many levels of symbolic links".into())
}

/// The permissions a file written over `existing` keeps: its read, write and
/// run bits when the running user owns it, never set-user-ID, set-group-ID or
/// sticky (as `cp` drops them); none, so that a new file's are taken, when
/// another user owns it: root writing over a stranger's file would otherwise
/// make a root-owned file with whatever mode the stranger chose.
fn kept_mode(existing: &fs::Metadata) -> Option<u32> {
    // SAFETY: geteuid has no preconditions and cannot fail.
    let me = unsafe { libc::geteuid() };
    (existing.uid() == me).then_some(existing.mode() & 0o777)
}

/// The owner of a symbolic link that neither the running user nor root made.
fn untrusted(link: &fs::Metadata) -> Option<u32> {
    // SAFETY: geteuid has no preconditions and cannot fail.
    let me = unsafe { libc::geteuid() };
    let owner = link.uid();
    (link.file_type().is_symlink() && owner != me && owner != 0).then_some(owner)
}

/// The longest side of an image read back by [`read_rgb`].
pub const MAX_READ_SIDE: u32 = 16384;

/// Reads a PNG or BMP back as (width, height, RGB rows), for tests and comparisons.
pub fn read_rgb(path: &Path) -> Result<(u32, u32, Vec<u8>), String> {
    let limit = crate::scene::input::ImageLimit {
        max_side: MAX_READ_SIDE,
        what: "an image",
    };
    let img = crate::scene::input::read_image(path, limit)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let rgb = img.to_rgb8();
    Ok((rgb.width(), rgb.height(), rgb.into_raw()))
}
