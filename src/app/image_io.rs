//! Writing frames as PNG files, never leaving a half-written file behind: the image
//! goes to a temporary file beside the target, which is renamed into place.

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

/// Writes `frame` to `path` as an 8-bit RGB PNG.
pub fn write_png(frame: &Frame, path: &Path) -> Result<(), WriteError> {
    write_rgb_png(&frame.to_rgb8(), frame.width, frame.height, path)
}

/// Writes 8-bit RGB rows to `path` as a PNG, through a temporary file and a rename.
pub fn write_rgb_png(rgb: &[u8], width: u32, height: u32, path: &Path) -> Result<(), WriteError> {
    write_atomically(path, |out| {
        let encoder = image::codecs::png::PngEncoder::new(out);
        image::ImageEncoder::write_image(
            encoder,
            rgb,
            width,
            height,
            image::ExtendedColorType::Rgb8,
        )
        .map_err(|e| e.to_string())
    })
}

/// Writes text to `path`, through a temporary file and a rename.
pub fn write_text(path: &Path, text: &str) -> Result<(), WriteError> {
    write_atomically(path, |out| {
        out.write_all(text.as_bytes()).map_err(|e| e.to_string())
    })
}

/// Runs `write` on a temporary file beside `path`, then renames it into place; on
/// any failure the temporary file is removed and `path` is left as it was.
fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<fs::File>) -> Result<(), String>,
) -> Result<(), WriteError> {
    let fail = |reason: String| WriteError {
        path: path.to_path_buf(),
        reason,
    };
    let name = path
        .file_name()
        .ok_or_else(|| fail("not a file name".into()))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".{}.tmp", std::process::id()));
    let tmp = path.with_file_name(tmp_name);

    let result = (|| {
        let file = fs::File::create(&tmp).map_err(|e| e.to_string())?;
        let mut out = BufWriter::new(file);
        write(&mut out)?;
        out.flush().map_err(|e| e.to_string())?;
        drop(out);
        fs::rename(&tmp, path).map_err(|e| e.to_string())
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result.map_err(fail)
}

/// Reads a PNG back as (width, height, RGB rows), for tests and comparisons.
pub fn read_rgb_png(path: &Path) -> Result<(u32, u32, Vec<u8>), String> {
    let img = image::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let rgb = img.to_rgb8();
    Ok((rgb.width(), rgb.height(), rgb.into_raw()))
}
