//! The words and the JSON of `rasterlab check IMAGE`: plain words first, then
//! the stage, the light, the variants, the errors before and after the fit, and
//! where the differences left are.

use super::image::{ImageCheck, Shading, LAB3_SHARE, LAB3_TOLERANCE, THRESHOLD};
use crate::pipeline::Light;
use std::fmt::Write as _;

/// A number for the report: three significant digits, no trailing zeros.
pub fn three_digits(v: f32) -> String {
    let v = v + 0.0; // -0 is 0
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = (2 - v.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// What a figure of the handout shows, in a few words.
pub fn figure_words(figure: u8) -> &'static str {
    match figure {
        2 => "the vertices as points",
        3 => "the edges as lines",
        4 => "filled triangles, no depth test",
        5 => "filled triangles behind a depth buffer",
        6 => "light per vertex",
        7 => "light per pixel",
        8 => "light per pixel, interpolated affinely: section 6.2's mistake",
        _ => "not a figure of the handout",
    }
}

/// A variant's meaning, in words.
pub fn variant_words(name: &str) -> &'static str {
    match name {
        "projection-sum-truncated" => {
            "the projection truncates the whole sum, int(f X/Z + W/2), not int(f X/Z) + W/2"
        }
        "rounding" => "Interpolate rounds positions instead of truncating them",
        "dy-sampling" => "edges are sampled at |dy| + 1 points instead of max(|dx|, |dy|) + 1",
        "step-over-n" => "Interpolate steps by (b - a) / N instead of (b - a) / (N - 1)",
        "no-depth-test" => "there is no depth test: the triangle drawn last wins",
        "z-interpolated" => "the depth test interpolates z instead of 1/z",
        "perspective-vertex-light" => "the light per vertex is interpolated perspective-correctly",
        "truncated-colours" => "colours are truncated to 8 bits instead of rounded",
        "pi-3.14" => "pi is written as 3.14",
        "pi-3" => "pi is written as 3",
        "rho-squared" => "the reflectance is multiplied in twice: rho rho (D + N)",
        _ => "an unknown variant",
    }
}

/// The interior RMSE (0 to 255) a JPEG's compression alone leaves: the handout's
/// figures saved at quality 75 to 95 are 0.8 to 1.8 from their PNGs, a light
/// moved a little is tens.
const JPEG_NOISE_RMSE: f64 = 3.0;

impl ImageCheck {
    /// The report, plain words first.
    pub fn text(&self, name: &str) -> String {
        let mut out = String::new();
        for note in &self.notes {
            let _ = writeln!(out, "Note: {note}");
        }
        let Some(f) = &self.fitted else {
            let c = &self.closest;
            let (all, drawn) = (c.errors.near * 100.0, c.errors.near_drawn * 100.0);
            // Say which of the two shares fell short: a black image matches most
            // of the pixels (the background) and none of those a stage draws.
            let joint = if c.errors.near >= LAB3_SHARE {
                "but only"
            } else {
                "and"
            };
            let _ = writeln!(
                out,
                "{name} is not a lab 3 image: the closest stage, {} (Figure {}), matches {}{all:.0} % of the image's pixels within {}/255 {joint} {drawn:.0} % of the pixels it draws; a lab 3 screenshot matches over 90 % of both.",
                c.hypothesis.stage.name(),
                c.hypothesis.figure(),
                if c.errors.near >= LAB3_SHARE { "" } else { "only " },
                LAB3_TOLERANCE,
            );
            let _ = writeln!(
                out,
                "If it is one, check its size ({}x{}), the focal length (--focal; the image's height unless given) and the camera; for a light elsewhere give --light or --fit-light.",
                self.width, self.height
            );
            return out;
        };
        let h = f.hypothesis;
        let lit = h.lit();
        let variants = f.variants();
        let mut first = format!(
            "Your image is the handout's Figure {} ({})",
            h.figure(),
            figure_words(h.figure())
        );
        if let Some(a) = &self.alike {
            let figure = a.hypothesis.figure();
            let _ = write!(
                first,
                " or Figure {figure} ({}), which draws the same from this camera (no surface hides another in it){}",
                figure_words(figure),
                match a.pixels {
                    0 => String::new(),
                    n => format!(" but for {n} pixels on edges, which a fitted camera or a resized image does not place exactly"),
                }
            );
        }
        if lit {
            let default = Shading::handout();
            let differs = |a: f32, b: f32| three_digits(a) != three_digits(b);
            if differs(f.shading.power, default.power) {
                let _ = write!(first, " at light power {}", three_digits(f.shading.power));
            }
            if differs(f.shading.indirect, default.indirect) {
                let _ = write!(
                    first,
                    "{} indirect light {}",
                    if differs(f.shading.power, default.power) {
                        " and"
                    } else {
                        " at"
                    },
                    three_digits(f.shading.indirect)
                );
            }
            if f.light != Light::handout().position {
                let _ = write!(
                    first,
                    " with the light at ({}, {}, {})",
                    three_digits(f.light.x),
                    three_digits(f.light.y),
                    three_digits(f.light.z)
                );
            }
        }
        if !variants.is_empty() {
            let words: Vec<&str> = variants.iter().map(|v| variant_words(v)).collect();
            let _ = write!(first, "; {}", words.join("; "));
        }
        let r = &self.remaining;
        let within = if f.errors.max <= 1 { 1 } else { THRESHOLD };
        if self.lossy {
            let _ = write!(
                first,
                ", as far as a JPEG shows: its compression moves colours by a few levels, so pixels are not compared to {}/255; inside the surfaces it is {:.2}/255 RMS from it, and {} pixels ({:.2} %) are more than {}/255 off: {}.",
                THRESHOLD,
                f.errors.interior_rmse,
                r.total,
                f.errors.off * 100.0,
                THRESHOLD,
                self.where_words()
            );
        } else if r.total == 0 {
            let _ = write!(first, ". Every pixel matches within {within}/255.");
        } else {
            let _ = write!(
                first,
                ". Every pixel matches within {}/255 except {} ({:.2} %): {}.",
                THRESHOLD,
                r.total,
                f.errors.off * 100.0,
                self.where_words()
            );
        }
        let _ = writeln!(out, "{first}");
        let _ = writeln!(out);
        let _ = write!(
            out,
            "stage:      {} (Figure {})",
            h.stage.name(),
            h.figure()
        );
        if let Some(a) = &self.alike {
            let other = a.hypothesis;
            let _ = write!(
                out,
                " or {} (Figure {})",
                other.stage.name(),
                other.figure()
            );
        }
        let _ = writeln!(out);
        if lit {
            let _ = writeln!(
                out,
                "light:      power P = {}, indirect N = {}, at ({}, {}, {}){}",
                three_digits(f.shading.power),
                three_digits(f.shading.indirect),
                three_digits(f.light.x),
                three_digits(f.light.y),
                three_digits(f.light.z),
                if self.light_searched {
                    " (fitted)"
                } else if f.light == Light::handout().position {
                    " (the handout's)"
                } else {
                    " (given)"
                }
            );
        }
        let _ = writeln!(
            out,
            "variants:   {}",
            if variants.is_empty() {
                "none".to_string()
            } else {
                variants.join(", ")
            }
        );
        let _ = writeln!(
            out,
            "before fit: interior RMSE {:.2}/255, {:.2} % of pixels off by more than {}/255 (the handout's Figure {})",
            self.before.interior_rmse,
            self.before.off * 100.0,
            THRESHOLD,
            h.figure()
        );
        let _ = writeln!(
            out,
            "after fit:  interior RMSE {:.2}/255, {:.2} % of pixels off by more than {}/255",
            f.errors.interior_rmse,
            f.errors.off * 100.0,
            THRESHOLD
        );
        let _ = writeln!(out, "remaining:  {}", r.summary());
        if self.light_searched_in_vain && self.shade_differs() {
            let _ = writeln!(
                out,
                "The shade still differs inside the surfaces, and no position of the light explains it better (it was searched for, as --fit-light does): the heat map (--out) shows where."
            );
        } else if !self.light_searched && self.shade_differs() {
            let _ = writeln!(
                out,
                "The shade still differs inside the surfaces: if your light is elsewhere, --fit-light searches for it."
            );
        }
        out
    }

    /// Whether the best explanation lights the surfaces and their shade still
    /// differs inside them, not only along edges: what a light elsewhere leaves.
    pub fn shade_differs(&self) -> bool {
        let f = self.fitted.as_ref().unwrap_or(&self.closest);
        f.hypothesis.lit()
            && match self.lossy {
                true => f.errors.interior_rmse > JPEG_NOISE_RMSE,
                false => self.remaining.total > self.remaining.edges * 2,
            }
    }

    fn where_words(&self) -> String {
        let r = &self.remaining;
        let mut parts = Vec::new();
        if r.edges > 0 {
            parts.push(format!("{} on edges", r.edges));
        }
        for (name, k) in r.surfaces.iter().take(3) {
            parts.push(format!("{k} inside {name}"));
        }
        if r.surfaces.len() > 3 {
            let rest: usize = r.surfaces[3..].iter().map(|(_, k)| k).sum();
            parts.push(format!("{rest} inside other surfaces"));
        }
        parts.join(", ")
    }

    /// The report as one JSON object, for a teacher's script.
    pub fn json(&self, name: &str) -> String {
        let mut out = self.json_fields(name);
        // The camera, the crop and the notes last, as more fields.
        out.pop();
        if let Some(c) = self.camera {
            let _ = write!(
                out,
                ",\"camera\":[{},{},{}],\"yaw\":{},\"pitch\":{},\"focal\":{}",
                three_digits(c.position.x),
                three_digits(c.position.y),
                three_digits(c.position.z),
                three_digits(c.yaw.to_degrees()),
                three_digits(c.pitch.to_degrees()),
                c.focal
            );
        }
        if self.lossy {
            out += ",\"jpeg\":true";
        }
        if let Some([x, y, w, h]) = self.crop {
            let _ = write!(out, ",\"crop\":[{x},{y},{w},{h}]");
        }
        let notes: Vec<String> = self.notes.iter().map(|n| json_string(n)).collect();
        let _ = write!(out, ",\"notes\":[{}]}}", notes.join(","));
        out
    }

    fn json_fields(&self, name: &str) -> String {
        let mut out = String::from("{");
        let _ = write!(out, "\"image\":{}", json_string(name));
        let _ = write!(out, ",\"width\":{},\"height\":{}", self.width, self.height);
        let Some(f) = &self.fitted else {
            let _ = write!(
                out,
                ",\"lab3\":false,\"figure\":null,\"stage\":null,\"light_power\":null,\"indirect\":null,\"light\":null,\"variants\":[],\"interior_rmse\":null}}"
            );
            return out;
        };
        let h = f.hypothesis;
        let _ = write!(
            out,
            ",\"lab3\":true,\"figure\":{},\"stage\":{}",
            h.figure(),
            json_string(h.stage.name())
        );
        if let Some(a) = &self.alike {
            let _ = write!(out, ",\"or_figure\":{}", a.hypothesis.figure());
        }
        if h.lit() {
            let _ = write!(
                out,
                ",\"light_power\":{},\"indirect\":{},\"light\":[{},{},{}]",
                three_digits(f.shading.power),
                three_digits(f.shading.indirect),
                three_digits(f.light.x),
                three_digits(f.light.y),
                three_digits(f.light.z)
            );
        } else {
            let _ = write!(
                out,
                ",\"light_power\":null,\"indirect\":null,\"light\":null"
            );
        }
        let names: Vec<String> = f.variants().iter().map(|v| json_string(v)).collect();
        let _ = write!(out, ",\"variants\":[{}]", names.join(","));
        let _ = write!(
            out,
            ",\"interior_rmse\":{:.3},\"interior_rmse_before\":{:.3},\"off\":{:.5},\"off_before\":{:.5},\"threshold\":{}",
            f.errors.interior_rmse,
            self.before.interior_rmse,
            f.errors.off,
            self.before.off,
            THRESHOLD
        );
        let r = &self.remaining;
        let _ = write!(
            out,
            ",\"remaining\":{},\"differing\":{},\"on_edges\":{}}}",
            json_string(r.summary()),
            r.total,
            r.edges
        );
        out
    }
}

/// A JSON string literal.
pub fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_three_significant_digits() {
        assert_eq!(three_digits(1.1), "1.1");
        assert_eq!(three_digits(14.1), "14.1");
        assert_eq!(three_digits(1.100_56), "1.1");
        assert_eq!(three_digits(0.5), "0.5");
        assert_eq!(three_digits(-0.7), "-0.7");
        assert_eq!(three_digits(-0.0), "0");
        assert_eq!(three_digits(123.4), "123");
        assert_eq!(json_string("a\"b\\c\n"), "\"a\\\"b\\\\c\\u000a\"");
    }
}
