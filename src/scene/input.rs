//! Reading files that come from strangers: a model, its materials, a texture, a
//! screenshot or a printout. What is read is bounded before it is read:
//!
//! - Only regular files are read. A FIFO, a device or a socket is refused with
//!   its kind named; it is opened without blocking (`O_NONBLOCK`), so a FIFO with
//!   no writer is refused at once instead of waited on.
//! - Text is read up to a limit in bytes, and refused past it.
//! - An image's size is read from its header first, and refused before decoding
//!   when it is larger than the caller allows; decoding then runs under the
//!   `image` crate's limits, so a lying header cannot allocate more.

use std::fs::{File, OpenOptions};
use std::io::{BufReader, Read};
use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
use std::path::Path;

/// Whether `word` is a number past the largest an f32 holds (1e39): read
/// as infinite, it is neither NaN nor infinite, and is named so.
pub fn past_f32(word: &str) -> bool {
    word.parse::<f32>().is_ok_and(f32::is_infinite) && word.parse::<f64>().is_ok_and(f64::is_finite)
}

/// A name from a file as a message shows it: a long one (a path of thousands
/// of parts, say) cut in the middle.
pub fn shortened(name: &str) -> String {
    const SHOWN: usize = 60;
    let chars = name.chars().count();
    if chars <= 2 * SHOWN {
        return name.to_string();
    }
    let head: String = name.chars().take(SHOWN).collect();
    let tail: String = name.chars().skip(chars - SHOWN).collect();
    format!("{head}...{tail}")
}

/// Opens `path` for reading if it is a regular file; the error says why not (no
/// path in it: the caller names the file).
pub fn open_regular(path: &Path) -> Result<File, String> {
    let file = OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
        .map_err(|e| format!("cannot open: {e}"))?;
    let kind = file
        .metadata()
        .map_err(|e| format!("cannot open: {e}"))?
        .file_type();
    let what = if kind.is_file() {
        return Ok(file);
    } else if kind.is_dir() {
        "a folder"
    } else if kind.is_fifo() {
        "a FIFO"
    } else if kind.is_char_device() || kind.is_block_device() {
        "a device"
    } else if kind.is_socket() {
        "a socket"
    } else {
        "not a file"
    };
    Err(format!("{what}, not a regular file: refused"))
}

/// The whole of `reader` as text, refused past `max_bytes`: UTF-8, or UTF-16
/// after its byte-order mark (what Windows PowerShell 5 writes for `> file`).
pub fn read_text_bounded(reader: impl Read, max_bytes: u64) -> Result<String, String> {
    let mut bytes = Vec::new();
    reader
        .take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read: {e}"))?;
    if bytes.len() as u64 > max_bytes {
        return Err(format!("longer than {max_bytes} bytes: refused"));
    }
    let utf16 = |pair: fn([u8; 2]) -> u16| {
        let pairs = bytes[2..].chunks_exact(2);
        let whole = pairs.remainder().is_empty();
        let units: Vec<u16> = pairs.map(|c| pair([c[0], c[1]])).collect();
        whole.then(|| String::from_utf16(&units).ok()).flatten()
    };
    match bytes.get(..2) {
        Some([0xff, 0xfe]) => utf16(u16::from_le_bytes),
        Some([0xfe, 0xff]) => utf16(u16::from_be_bytes),
        _ => String::from_utf8(bytes).ok(),
    }
    .ok_or_else(|| "not UTF-8 or UTF-16 text".into())
}

/// The text file at `path`, refused past `max_bytes`.
pub fn read_text_file(path: &Path, max_bytes: u64) -> Result<String, String> {
    read_text_bounded(open_regular(path)?, max_bytes)
}

/// How large an image [`read_image`] may decode.
#[derive(Clone, Copy, Debug)]
pub struct ImageLimit {
    /// The longest side, in pixels.
    pub max_side: u32,
    /// What to say the image is, in the refusal ("a texture", "a screenshot").
    pub what: &'static str,
}

impl ImageLimit {
    /// The width and height of the image at `path`, from its header, refused
    /// when a side is longer than allowed or 0 (a GIF's screen may be 0 wide).
    pub fn allowed_size(&self, path: &Path) -> Result<(u32, u32), String> {
        let (w, h) = image_size(path)?;
        if w == 0 || h == 0 {
            return Err(format!("the image is empty ({w}x{h})"));
        }
        if w > self.max_side || h > self.max_side {
            return Err(format!(
                "{w}x{h} is too large for {} (at most {} pixels a side)",
                self.what, self.max_side
            ));
        }
        Ok((w, h))
    }
}

/// The image at `path` (PNG, JPEG, BMP or GIF by its content, TGA by its
/// name), refused from its header when a side is longer than `limit` allows.
pub fn read_image(path: &Path, limit: ImageLimit) -> Result<image::DynamicImage, String> {
    read_image_with_format(path, limit).map(|(image, _)| image)
}

/// [`read_image`], with the format its content showed.
pub fn read_image_with_format(
    path: &Path,
    limit: ImageLimit,
) -> Result<(image::DynamicImage, Option<image::ImageFormat>), String> {
    let (w, h) = limit.allowed_size(path)?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(limit.max_side);
    limits.max_image_height = Some(limit.max_side);
    // Room for the decoded image at 16 bits a channel with alpha, and no more.
    limits.max_alloc = Some(w as u64 * h as u64 * 8 + (1 << 20));
    let mut reader = image_reader(path)?;
    reader.limits(limits);
    let format = reader.format();
    let image = reader.decode().map_err(|e| damaged(format, e))?;
    // The JPEG decoder fills a cut-short image with grey and says nothing.
    if format == Some(image::ImageFormat::Jpeg) && !jpeg_ends(path)? {
        return Err("a damaged or cut-short JPEG image (its end marker is missing)".into());
    }
    Ok((image, format))
}

/// Whether the JPEG at `path` reaches its end marker (`FF D9`), read segment by
/// segment (so that a thumbnail inside a segment, a whole JPEG of its own, is
/// passed over) and through each scan, where a byte `FF` is followed by `00` or
/// a restart marker. Bytes after the end marker (some cameras add data) are
/// allowed.
fn jpeg_ends(path: &Path) -> Result<bool, String> {
    let mut bytes = BufReader::new(open_regular(path)?).bytes();
    let mut next = || -> Result<Option<u8>, String> {
        bytes
            .next()
            .transpose()
            .map_err(|e| format!("cannot read: {e}"))
    };
    // The marker read last, if the scan before it ended on one.
    let mut pending = None;
    loop {
        let marker = match pending.take() {
            Some(m) => m,
            None => {
                // Up to the next FF, then past any fill bytes FF.
                loop {
                    match next()? {
                        None => return Ok(false),
                        Some(0xFF) => break,
                        Some(_) => {}
                    }
                }
                let mut m = 0xFF;
                while m == 0xFF {
                    let Some(b) = next()? else { return Ok(false) };
                    m = b;
                }
                m
            }
        };
        match marker {
            0xD9 => return Ok(true),
            0xD8 | 0xD0..=0xD7 | 0x01 | 0x00 => continue,
            _ => {}
        }
        let (Some(high), Some(low)) = (next()?, next()?) else {
            return Ok(false);
        };
        let length = u16::from_be_bytes([high, low]);
        for _ in 2..length {
            if next()?.is_none() {
                return Ok(false);
            }
        }
        if marker != 0xDA {
            continue;
        }
        // The scan's data, up to the marker after it.
        pending = loop {
            match next()? {
                None => return Ok(false),
                Some(0xFF) => {
                    let mut m = 0xFF;
                    while m == 0xFF {
                        let Some(b) = next()? else { return Ok(false) };
                        m = b;
                    }
                    if !(m == 0x00 || (0xD0..=0xD7).contains(&m)) {
                        break Some(m);
                    }
                }
                Some(_) => {}
            }
        };
    }
}

/// A reader of the image at `path`, its format known from its first bytes,
/// or for a TGA, which has no mark of its own, from its name (models' textures
/// often are).
fn image_reader(path: &Path) -> Result<image::ImageReader<BufReader<std::fs::File>>, String> {
    let mut reader = image::ImageReader::new(BufReader::new(open_regular(path)?))
        .with_guessed_format()
        .map_err(|e| format!("cannot read: {e}"))?;
    let tga = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("tga"));
    if reader.format().is_none() && tga {
        reader.set_format(image::ImageFormat::Tga);
    }
    Ok(reader)
}

/// An image's width and height, from its header alone.
pub fn image_size(path: &Path) -> Result<(u32, u32), String> {
    let reader = image_reader(path)?;
    match reader.format() {
        // What a text file or a truncated header gets.
        None => {
            return Err(
                "not a PNG, JPEG, BMP or GIF image (its first bytes are none of those)".into(),
            )
        }
        Some(
            image::ImageFormat::Png
            | image::ImageFormat::Jpeg
            | image::ImageFormat::Bmp
            | image::ImageFormat::Gif
            | image::ImageFormat::Tga,
        ) => {}
        // Other formats are not built in.
        Some(f) => {
            let name = format!("{f:?}").to_uppercase();
            let a = match name.starts_with(['A', 'E', 'I', 'O', 'U']) {
                true => "an",
                false => "a",
            };
            return Err(format!(
                "{a} {name} image, which is not read: save it as PNG (or JPEG, BMP, GIF)"
            ));
        }
    }
    let format = reader.format();
    let mut reader = reader;
    reader.limits(header_limits());
    reader.into_dimensions().map_err(|e| damaged(format, e))
}

/// What reading an image's size may allocate: a PNG's colour profile and text
/// come before its pixels and are inflated on the way (2 MB of a profile
/// inflated to 2 GB, an abort under a memory cap).
fn header_limits() -> image::Limits {
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(HEADER_BYTES);
    limits
}

/// At most how much of an image's metadata is read (colour profiles are
/// kilobytes, a few megabytes at most).
const HEADER_BYTES: u64 = 16 << 20;

/// "a " before a format's name, "an " before "image".
fn article(kind: &str) -> &'static str {
    match kind.is_empty() {
        true => "an ",
        false => "a ",
    }
}

/// Why an image of `format` could not be decoded, on one line (the decoders'
/// messages can run over several).
fn damaged(format: Option<image::ImageFormat>, e: image::ImageError) -> String {
    let kind = format.map_or("".into(), |f| format!("{f:?} ").to_uppercase());
    if let image::ImageError::Limits(_) = e {
        let a = article(&kind);
        return format!(
            "{a}{kind}image whose metadata (a colour profile or text) inflates past \
             {} MB or past the room for its pixels: not read",
            HEADER_BYTES >> 20
        );
    }
    let unsupported = matches!(e, image::ImageError::Unsupported(_));
    let why = e
        .to_string()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    // A valid file in a form the decoders do not read (a 12-bit JPEG, an
    // OS/2 or compressed BMP) is not damaged: said so.
    let form = ["not support", "only parse", "Unknown bitmap header"];
    match unsupported || form.iter().any(|f| why.contains(f)) {
        true => format!(
            "{}{kind}image in a form not read here ({why})",
            article(&kind)
        ),
        false => format!("a damaged or cut-short {kind}image ({why})"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_past_its_bound_is_refused() {
        assert_eq!(read_text_bounded(&b"abcd"[..], 4).unwrap(), "abcd");
        assert_eq!(
            read_text_bounded(&b"abcde"[..], 4).unwrap_err(),
            "longer than 4 bytes: refused"
        );
        assert_eq!(
            read_text_bounded(&[0xff, 0xff][..], 4).unwrap_err(),
            "not UTF-8 or UTF-16 text"
        );
        // UTF-16 after its byte-order mark, either way round; not an odd byte.
        assert_eq!(
            read_text_bounded(&[0xff, 0xfe, b'1', 0][..], 4).unwrap(),
            "1"
        );
        assert_eq!(
            read_text_bounded(&[0xfe, 0xff, 0, b'1'][..], 4).unwrap(),
            "1"
        );
        assert!(read_text_bounded(&[0xff, 0xfe, b'1'][..], 4).is_err());
    }

    #[test]
    fn devices_and_folders_are_refused_by_kind() {
        assert_eq!(
            open_regular(Path::new("/dev/zero")).unwrap_err(),
            "a device, not a regular file: refused"
        );
        assert_eq!(
            open_regular(Path::new("/")).unwrap_err(),
            "a folder, not a regular file: refused"
        );
    }
}
