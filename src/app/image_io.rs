//! Writing images and text without ever leaving a half-written file behind.
//!
//! - A regular file (or a new one) is written to a temporary file beside it, which
//!   is then renamed into place.
//! - A symbolic link is followed: its target is replaced that way, the link stays.
//! - Anything else that exists (a device such as /dev/null, a FIFO) is written
//!   directly, since renaming over it would replace it.
//! - `-` is standard output.
//!
//! The image format follows the name: `.png` or `.bmp`.

use crate::pipeline::Frame;
use std::fmt;
use std::fs;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Why an image could not be written; the message names the path.
#[derive(Debug)]
pub struct WriteError {
    pub path: PathBuf,
    pub reason: String,
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot write {}: {}", self.path.display(), self.reason)
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
        path.display().to_string()
    }
}

/// Writes `frame` to `path` as 8-bit RGB in the format its name asks for.
pub fn write_png(frame: &Frame, path: &Path) -> Result<(), WriteError> {
    write_rgb_png(&frame.to_rgb8(), frame.width, frame.height, path)
}

/// Writes 8-bit RGB rows to `path` in the format its name asks for (PNG when the
/// name says nothing), encoded in memory first so nothing is written on failure.
pub fn write_rgb_png(rgb: &[u8], width: u32, height: u32, path: &Path) -> Result<(), WriteError> {
    let fail = |reason: String| WriteError {
        path: path.to_path_buf(),
        reason,
    };
    let mut bytes = Vec::new();
    let encoded = match ImageFormat::of(path).unwrap_or(ImageFormat::Png) {
        ImageFormat::Png => image::ImageEncoder::write_image(
            image::codecs::png::PngEncoder::new(&mut bytes),
            rgb,
            width,
            height,
            image::ExtendedColorType::Rgb8,
        ),
        ImageFormat::Bmp => image::ImageEncoder::write_image(
            image::codecs::bmp::BmpEncoder::new(&mut bytes),
            rgb,
            width,
            height,
            image::ExtendedColorType::Rgb8,
        ),
    };
    encoded.map_err(|e| fail(e.to_string()))?;
    write_bytes(path, &bytes)
}

/// Writes text to `path` (see the module's rules).
pub fn write_text(path: &Path, text: &str) -> Result<(), WriteError> {
    write_bytes(path, text.as_bytes())
}

/// Writes `bytes` to `path` by the module's rules. A reader that closes standard
/// output early (`| head`) is not an error.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let fail = |reason: String| WriteError {
        path: path.to_path_buf(),
        reason,
    };
    if path.as_os_str() == "-" {
        let mut out = std::io::stdout().lock();
        return match out.write_all(bytes).and_then(|()| out.flush()) {
            Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(fail(e.to_string())),
            _ => Ok(()),
        };
    }
    let target = follow_links(path).map_err(fail)?;
    match fs::metadata(&target) {
        Ok(m) if !m.is_file() && !m.is_dir() => {
            // A device or a FIFO: write into it; a rename would replace it.
            let mut f = fs::OpenOptions::new()
                .write(true)
                .open(&target)
                .map_err(|e| fail(e.to_string()))?;
            f.write_all(bytes).map_err(|e| fail(e.to_string()))
        }
        Ok(m) if m.is_dir() => Err(fail("it is a folder".into())),
        _ => write_atomically(&target, bytes).map_err(fail),
    }
}

/// The file a path finally names: symbolic links followed (relative targets from
/// the link's folder), up to 40 of them.
fn follow_links(path: &Path) -> Result<PathBuf, String> {
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        match fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
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

/// Writes `bytes` to a temporary file beside `path`, then renames it into place;
/// on any failure the temporary file is removed and `path` is left as it was. An
/// existing file keeps its permissions.
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let name = path.file_name().ok_or("not a file name")?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".{}.tmp", std::process::id()));
    let tmp = path.with_file_name(tmp_name);
    let result = (|| {
        let file = fs::File::create(&tmp).map_err(|e| e.to_string())?;
        let mut out = BufWriter::new(file);
        out.write_all(bytes).map_err(|e| e.to_string())?;
        out.flush().map_err(|e| e.to_string())?;
        drop(out);
        if let Ok(m) = fs::metadata(path) {
            let _ = fs::set_permissions(&tmp, m.permissions());
        }
        fs::rename(&tmp, path).map_err(|e| e.to_string())
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// Reads a PNG or BMP back as (width, height, RGB rows), for tests and comparisons.
pub fn read_rgb_png(path: &Path) -> Result<(u32, u32, Vec<u8>), String> {
    let img = image::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let rgb = img.to_rgb8();
    Ok((rgb.width(), rgb.height(), rgb.into_raw()))
}
