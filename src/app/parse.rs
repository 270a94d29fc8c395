//! Parsing the command line's values: sizes, vectors and 2D points. Each parser
//! returns a one-line message naming what is wrong.

use crate::pipeline::StageName;
use glam::Vec3;

/// The largest width or height accepted: a 16384 x 16384 frame with its depth
/// buffer and PNG rows takes about 3 GiB.
pub const MAX_SIDE: u32 = 16384;

/// `WxH`, both at least 1 and at most [`MAX_SIDE`].
pub fn size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT such as 500x500, got '{s}'"))?;
    let side = |t: &str| -> Result<u32, String> {
        let t = t.trim();
        let all_digits = |t: &str| !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit());
        // A whole number too large for u32 is still a side too long, and a
        // negative one a side too short, not a non-number.
        let v: u64 = match t.parse() {
            Ok(v) => v,
            Err(_) if all_digits(t) => u64::MAX,
            Err(_) if t.strip_prefix('-').is_some_and(all_digits) => 0,
            Err(_) => return Err(format!("'{t}' is not a whole number of pixels in '{s}'")),
        };
        if v == 0 || v > MAX_SIDE as u64 {
            return Err(format!(
                "each side must be from 1 to {MAX_SIDE} pixels, got '{s}'"
            ));
        }
        Ok(v as u32)
    };
    Ok((side(w)?, side(h)?))
}

fn numbers(s: &str, n: usize, what: &str) -> Result<Vec<f32>, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != n {
        return Err(format!("expected {what}, got '{s}'"));
    }
    parts
        .iter()
        .map(|t| match t.trim().parse::<f32>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) if crate::scene::input::past_f32(t.trim()) => Err(format!(
                "'{t}' is past the largest number this holds (about 3.4e38) in '{s}'"
            )),
            Ok(_) => Err(format!("'{t}' is not a finite number in '{s}'")),
            Err(_) => Err(format!("'{t}' is not a number in '{s}'")),
        })
        .collect()
}

/// `X,Y,Z`: three finite numbers, e.g. `-0.5,0,-2`.
pub fn vec3(s: &str) -> Result<Vec3, String> {
    let v = numbers(s, 3, "three numbers X,Y,Z such as 0,-0.5,-0.7")?;
    Ok(Vec3::new(v[0], v[1], v[2]))
}

/// `FOCUS,APERTURE`: the depth in focus (> 0) and the lens radius (>= 0), in
/// world units, for `--dof`.
pub fn dof(s: &str) -> Result<crate::extensions::depth_of_field::DepthOfField, String> {
    let v = numbers(s, 2, "FOCUS,APERTURE such as 3,0.05")?;
    if v[0] <= 0.0 || v[1] < 0.0 {
        return Err(format!(
            "the focus depth must be greater than 0 and the aperture at least 0, got '{s}'"
        ));
    }
    Ok(crate::extensions::depth_of_field::DepthOfField {
        focus: v[0],
        aperture: v[1],
    })
}

/// A finite number.
pub fn finite(s: &str) -> Result<f32, String> {
    Ok(numbers(s, 1, "a number")?[0])
}

/// A finite number greater than zero.
pub fn positive(s: &str) -> Result<f32, String> {
    let v = finite(s)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(format!("must be greater than 0, got '{s}'"))
    }
}

/// A finite number at least zero: a light's power, the indirect light.
pub fn non_negative(s: &str) -> Result<f32, String> {
    let v = finite(s)?;
    if v >= 0.0 {
        Ok(v)
    } else {
        Err(format!(
            "must be at least 0 (light cannot be negative), got '{s}'"
        ))
    }
}

/// The longest focal length accepted, in pixels.
pub const MAX_FOCAL: f32 = 1e9;

/// A focal length: greater than 0 and at most [`MAX_FOCAL`].
pub fn focal(s: &str) -> Result<f32, String> {
    let v = positive(s)?;
    if v > MAX_FOCAL {
        return Err(format!(
            "at most {MAX_FOCAL:e} pixels, got '{s}': a point beside the view projects f x/z pixels away, and past about 1e11 f32's 24 bits cannot place the clipped edges (Figure 5 at 2e11 draws 60 % of the wall black)"
        ));
    }
    Ok(v)
}

/// A stage's name: `points`, `wireframe`, `filled`, `depth`, `vertex-light`, `pixel-light`.
pub fn stage(s: &str) -> Result<StageName, String> {
    StageName::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = StageName::ALL.iter().map(|s| s.name()).collect();
        format!("unknown stage '{s}': expected one of {}", names.join(", "))
    })
}

/// A whole number from `min` to `max`, for counts such as `--time N`.
pub fn whole(s: &str, min: u64, max: u64) -> Result<u64, String> {
    match s.trim().parse::<u64>() {
        Ok(v) if (min..=max).contains(&v) => Ok(v),
        _ => Err(format!(
            "expected a whole number from {min} to {max}, got '{s}'"
        )),
    }
}

/// Where an image goes: `-` (or /dev/stdout) for standard output, a file whose
/// name ends in `.png` or `.bmp` (the format follows the name), or an existing
/// device or FIFO such as /dev/null (PNG).
pub fn image_path(s: &str) -> Result<std::path::PathBuf, String> {
    let path = std::path::PathBuf::from(s);
    let special = std::fs::metadata(&path).is_ok_and(|m| !m.is_file() && !m.is_dir());
    let stdout = crate::app::image_io::names_stdout(&path);
    if stdout || special || crate::app::image_io::ImageFormat::of(&path).is_some() {
        Ok(path)
    } else {
        let why = match path.extension() {
            Some(ext) => format!(
                "images are written as PNG or BMP, not .{}",
                ext.to_string_lossy()
            ),
            None => "its name has no ending to choose the image format by".to_string(),
        };
        Err(format!(
            "'{s}': {why}; name the file .png or .bmp, or give - for standard output"
        ))
    }
}

/// Whether `path`'s name ends in `.ext`, in any case.
fn has_extension(path: &std::path::Path, ext: &str) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// Where a model goes: a file ending in `.obj`.
pub fn obj_path(s: &str) -> Result<std::path::PathBuf, String> {
    let path = std::path::PathBuf::from(s);
    if has_extension(&path, "obj") {
        Ok(path)
    } else {
        Err(format!(
            "a model is written as OBJ: name the file .obj, got '{s}'"
        ))
    }
}

/// Where an animation goes: a `.gif` file, or - for standard output.
pub fn gif_path(s: &str) -> Result<std::path::PathBuf, String> {
    let path = std::path::PathBuf::from(s);
    if s == "-" || has_extension(&path, "gif") {
        Ok(path)
    } else {
        Err(format!(
            "an animation is a GIF: name the file .gif, got '{s}'"
        ))
    }
}

/// `X,Y` in pixels, fractions allowed: a point for `explain edge`.
pub fn point_f32(s: &str) -> Result<(f32, f32), String> {
    let v = numbers(s, 2, "a point X,Y such as 1.5,0.5")?;
    if v.iter().any(|c| c.abs() > MAX_ROWS_COORDINATE as f32) {
        return Err(format!(
            "coordinates must be within -{MAX_ROWS_COORDINATE}..{MAX_ROWS_COORDINATE}, got '{s}'"
        ));
    }
    Ok((v[0], v[1]))
}

/// The largest coordinate `rasterlab rows` takes, so a polygon's rows always fit.
pub const MAX_ROWS_COORDINATE: i32 = 10_000;

/// `X,Y`: a pixel position with whole coordinates within ±[`MAX_ROWS_COORDINATE`].
pub fn point(s: &str) -> Result<(i32, i32), String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 2 {
        return Err(format!("expected a pixel X,Y such as 10,5, got '{s}'"));
    }
    let c = |t: &str| -> Result<i32, String> {
        let v: i32 = t
            .trim()
            .parse()
            .map_err(|_| format!("'{t}' is not a whole number in '{s}'"))?;
        // `unsigned_abs`: `i32::MIN.abs()` wraps to itself, below the limit.
        if v.unsigned_abs() > MAX_ROWS_COORDINATE as u32 {
            return Err(format!(
                "coordinates must be within -{MAX_ROWS_COORDINATE}..{MAX_ROWS_COORDINATE}, got '{s}'"
            ));
        }
        Ok(v)
    };
    Ok((c(parts[0])?, c(parts[1])?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes() {
        assert_eq!(size("500x400"), Ok((500, 400)));
        assert_eq!(
            size("0x0").unwrap_err(),
            "each side must be from 1 to 16384 pixels, got '0x0'"
        );
        assert!(size("500").is_err());
        assert!(size("20000x1").is_err());
        assert_eq!(
            size("-5x5").unwrap_err(),
            "each side must be from 1 to 16384 pixels, got '-5x5'"
        );
        assert_eq!(
            size("5x-x").unwrap_err(),
            "'-x' is not a whole number of pixels in '5x-x'"
        );
    }

    #[test]
    fn vectors() {
        assert_eq!(vec3("-0.5,0,-2"), Ok(Vec3::new(-0.5, 0.0, -2.0)));
        assert_eq!(
            vec3("1,2").unwrap_err(),
            "expected three numbers X,Y,Z such as 0,-0.5,-0.7, got '1,2'"
        );
        assert_eq!(
            vec3("1,nan,2").unwrap_err(),
            "'nan' is not a finite number in '1,nan,2'"
        );
        assert_eq!(
            vec3("1,1e39,2").unwrap_err(),
            "'1e39' is past the largest number this holds (about 3.4e38) in '1,1e39,2'"
        );
        assert_eq!(vec3("1,a,2").unwrap_err(), "'a' is not a number in '1,a,2'");
        assert!(positive("0").is_err());
        assert_eq!(positive("2.5"), Ok(2.5));
    }

    #[test]
    fn counts_and_image_names() {
        assert_eq!(whole("5", 1, 10), Ok(5));
        assert_eq!(
            whole("-1", 1, 10).unwrap_err(),
            "expected a whole number from 1 to 10, got '-1'"
        );
        assert!(whole("0", 1, 10).is_err());
        assert!(image_path("a.png").is_ok() && image_path("b.BMP").is_ok());
        assert!(image_path("-").is_ok());
        assert!(image_path("x.jpg").unwrap_err().contains("'x.jpg'"));
        assert!(image_path("noext").is_err());
    }

    #[test]
    fn points() {
        assert_eq!(point("10,5"), Ok((10, 5)));
        assert_eq!(point("-3,4"), Ok((-3, 4)));
        assert!(point("1.5,2").is_err());
        assert!(point("20000,0").is_err());
        // The one value whose `abs` wraps round to a negative number.
        let least = point("0,-2147483648").unwrap_err();
        assert_eq!(
            least,
            "coordinates must be within -10000..10000, got '0,-2147483648'"
        );
        assert!(point("-2147483648,0").is_err());
        assert_eq!(point("-10000,10000"), Ok((-10000, 10000)));
    }
}
