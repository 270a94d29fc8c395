//! `rasterlab check rows`: a student's printed `ComputePolygonRows` output (the
//! handout's section 4 test program) against ours, and which known way of
//! walking the edges reproduces it.

use super::report::json_string;
use super::walk::Walk;
use crate::pipeline::interpolate::Pixel;
use crate::pipeline::raster::rows::{compute_polygon_rows_by, Rows};
use crate::pipeline::raster::Bounds;
use crate::scene::input::shortened;
use std::fmt::Write as _;

/// One printed row: the start (x, y) and the end (x, y).
pub type Row = [i32; 4];

/// A way of computing the rows: a walk of the edges, and whether the printed end
/// is one past the last pixel (a half-open row) instead of the last pixel itself.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RowsVariant {
    pub walk: Walk,
    pub exclusive_end: bool,
}

impl RowsVariant {
    /// What differs from the handout, by name; empty for the handout's.
    pub fn names(self) -> Vec<&'static str> {
        let mut names = self.walk.names();
        if self.exclusive_end {
            names.push("exclusive-end");
        }
        names
    }

    /// Every variant, those with fewer changes first.
    pub fn all() -> Vec<RowsVariant> {
        let mut all: Vec<RowsVariant> = [false, true]
            .into_iter()
            .flat_map(|exclusive_end| {
                Walk::all().into_iter().map(move |walk| RowsVariant {
                    walk,
                    exclusive_end,
                })
            })
            .collect();
        all.sort_by_key(|v| v.names().len());
        all
    }

    /// The rows of the polygon `vertices` as this variant computes and prints them.
    pub fn rows(self, vertices: &[(i32, i32)]) -> Vec<Row> {
        let pixels: Vec<_> = vertices.iter().map(|&(x, y)| Pixel::at(x, y)).collect();
        let mut rows = Rows::new();
        compute_polygon_rows_by(&self.walk, &pixels, &Bounds::unbounded(), &mut rows);
        let end = self.exclusive_end as i32;
        rows.left
            .iter()
            .zip(&rows.right)
            .map(|(l, r)| [l.x, l.y, r.x.saturating_add(end), r.y])
            .collect()
    }
}

/// A row as the handout's program prints it.
pub fn row_text(r: &Row) -> String {
    format!("Start: ({},{}). End: ({},{}). ", r[0], r[1], r[2], r[3])
}

/// The rows in a student's printout. Each row is four whole numbers, the start's
/// x and y and the end's x and y, in any wrapping: one row per line as our
/// `rasterlab rows` prints it, all on one line as the handout shows it, with or
/// without the words and punctuation. A line whose count of numbers is not a
/// multiple of four cannot be read as rows and is an error naming it.
///
/// Pasted console output is read too: when some line holds `Start`, the lines
/// that hold neither `Start` nor `End` (`Render time: 3 ms.`, a prompt) are
/// other output and left out.
pub fn parse_rows(text: &str) -> Result<Vec<Row>, String> {
    parse_rows_skipping(text).map(|(rows, _)| rows)
}

/// [`parse_rows`], with how many lines were left out as not rows.
pub fn parse_rows_skipping(text: &str) -> Result<(Vec<Row>, usize), String> {
    let mut numbers = Vec::new();
    let mut lines = 0;
    let mut skipped = 0;
    let worded = text.lines().any(|l| l.contains("Start"));
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        if worded && !line.contains("Start") && !line.contains("End") {
            skipped += 1;
            continue;
        }
        lines += 1;
        let found = integers(line).map_err(|e| format!("line {}: {e}", i + 1))?;
        if found.is_empty() || found.len() % 4 != 0 {
            return Err(format!(
                "line {}: expected rows as 'Start: (x,y). End: (x,y).', found {} number{} in '{}'",
                i + 1,
                found.len(),
                if found.len() == 1 { "" } else { "s" },
                shortened(line.trim())
            ));
        }
        numbers.extend(found);
    }
    if lines == 0 {
        return Err("the rows text is empty".into());
    }
    let rows = numbers
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect();
    Ok((rows, skipped))
}

/// The whole numbers in a line, with their signs; anything else separates them.
fn integers(line: &str) -> Result<Vec<i32>, String> {
    let mut out = Vec::new();
    let mut current = String::new();
    let mut flush = |current: &mut String| -> Result<(), String> {
        if current.chars().any(|c| c.is_ascii_digit()) {
            let v = current
                .parse::<i32>()
                .map_err(|_| format!("'{}' is not a whole number of pixels", shortened(current)))?;
            out.push(v);
        }
        current.clear();
        Ok(())
    };
    let chars: Vec<char> = line.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        i += 1;
        let next_is_digit = |k: usize| chars.get(k).is_some_and(|c| c.is_ascii_digit());
        // A fraction or an exponent right after digits (`2.5`, `1e30`) is a
        // number that is not whole, not two numbers.
        let not_whole = current.chars().any(|c| c.is_ascii_digit())
            && ((c == '.' && next_is_digit(i))
                || ((c == 'e' || c == 'E')
                    && (next_is_digit(i)
                        || (matches!(chars.get(i), Some('+' | '-')) && next_is_digit(i + 1)))));
        if not_whole {
            let mut token: String = current.clone();
            token.push(c);
            while let Some(&d) = chars.get(i) {
                if d.is_ascii_alphanumeric() || matches!(d, '.' | '+' | '-') {
                    token.push(d);
                    i += 1;
                } else {
                    break;
                }
            }
            return Err(format!(
                "'{}' is not a whole number of pixels",
                shortened(&token)
            ));
        }
        if c.is_ascii_digit() || (c == '-' && current.is_empty()) {
            current.push(c);
        } else {
            flush(&mut current)?;
            if c == '-' {
                current.push(c);
            }
        }
    }
    flush(&mut current)?;
    Ok(out)
}

/// What `check rows` found.
#[derive(Clone, Debug, PartialEq)]
pub struct RowsCheck {
    pub handout: Vec<Row>,
    pub student: Vec<Row>,
    /// The first row (0-based) where the student's differs from the handout's,
    /// counting a missing or extra row; `None` when they are equal.
    pub first_difference: Option<usize>,
    /// The rows that differ, counting missing and extra ones.
    pub differing: usize,
    /// The variants that reproduce the student's rows exactly, fewest changes first.
    pub exact: Vec<RowsVariant>,
    /// When none does: the variant with the fewest differing rows, and that count.
    pub closest: Option<(RowsVariant, usize)>,
    /// Lines of the printout that were not rows (console output around them).
    pub skipped: usize,
}

/// Rows that differ between two listings, a missing or extra row counting as one.
fn differences(a: &[Row], b: &[Row]) -> (Option<usize>, usize) {
    let n = a.len().max(b.len());
    let differ: Vec<usize> = (0..n).filter(|&i| a.get(i) != b.get(i)).collect();
    (differ.first().copied(), differ.len())
}

/// Compares a student's rows of the polygon `vertices` with ours and with every
/// known variant.
pub fn check_rows(vertices: &[(i32, i32)], student: Vec<Row>) -> RowsCheck {
    let handout = RowsVariant::default().rows(vertices);
    let (first_difference, differing) = differences(&student, &handout);
    let scored: Vec<(RowsVariant, usize)> = RowsVariant::all()
        .into_iter()
        .map(|v| (v, differences(&student, &v.rows(vertices)).1))
        .collect();
    let exact: Vec<RowsVariant> = scored
        .iter()
        .filter(|(_, d)| *d == 0)
        .map(|(v, _)| *v)
        .collect();
    let closest = if exact.is_empty() {
        scored.iter().min_by_key(|(_, d)| *d).copied()
    } else {
        None
    };
    RowsCheck {
        handout,
        student,
        first_difference,
        differing,
        exact,
        closest,
        skipped: 0,
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// A variant in words.
pub fn describe(v: RowsVariant) -> String {
    let mut words = Vec::new();
    if v.walk.rounding {
        words.push("Interpolate rounds to the nearest pixel instead of truncating");
    }
    if v.walk.dy_sampling {
        words.push("each edge is sampled at |dy| + 1 points instead of max(|dx|, |dy|) + 1");
    }
    if v.walk.step_over_n {
        words.push("Interpolate steps by (b - a) / N instead of (b - a) / (N - 1)");
    }
    if v.exclusive_end {
        words.push("each End is printed one past the row's last pixel");
    }
    if words.is_empty() {
        "the handout's ComputePolygonRows".into()
    } else {
        words.join("; ")
    }
}

impl RowsCheck {
    /// The report, plain words first.
    pub fn text(&self) -> String {
        let mut out = String::new();
        if self.skipped > 0 {
            let _ = writeln!(
                out,
                "(skipped {} line{} that {} not rows)",
                self.skipped,
                plural(self.skipped),
                if self.skipped == 1 { "is" } else { "are" }
            );
        }
        let n = self.handout.len();
        match self.first_difference {
            None => {
                let _ = writeln!(
                    out,
                    "Your rows are the handout's ComputePolygonRows exactly ({n} row{}).",
                    plural(n)
                );
                return out;
            }
            Some(i) => {
                let show = |r: Option<&Row>| r.map_or("(no row)".to_string(), row_text);
                let _ = writeln!(
                    out,
                    "Your rows differ from the handout's in {} row{} (the handout has {}, you printed {}); the first is row {}:",
                    self.differing,
                    plural(self.differing),
                    n,
                    self.student.len(),
                    i + 1
                );
                let _ = writeln!(out, "  yours:     {}", show(self.student.get(i)).trim_end());
                let _ = writeln!(out, "  handout's: {}", show(self.handout.get(i)).trim_end());
            }
        }
        if let Some(&best) = self.exact.first() {
            let _ = writeln!(
                out,
                "Reproduced exactly by: {} (variant: {}).",
                describe(best),
                best.names().join(", ")
            );
            for other in &self.exact[1..] {
                let _ = writeln!(
                    out,
                    "Also reproduced exactly by: {} (variant: {}).",
                    describe(*other),
                    other.names().join(", ")
                );
            }
        } else if let Some((v, d)) = self.closest {
            let _ = writeln!(
                out,
                "No known variant reproduces your rows; the closest is {} ({} row{} still differ{}).",
                if v == RowsVariant::default() {
                    "the handout's".to_string()
                } else {
                    format!("{} (variant: {})", describe(v), v.names().join(", "))
                },
                d,
                plural(d),
                if d == 1 { "s" } else { "" }
            );
        }
        out
    }
}

impl RowsCheck {
    /// Whether the printout is the handout's rows: `check rows`' exit status 0.
    pub fn is_handouts(&self) -> bool {
        self.first_difference.is_none()
    }

    /// The result as one JSON object: whether the rows are the handout's, the first
    /// differing row (from 1), and the variants that reproduce them exactly (the
    /// fewest changes first) or, when none does, the closest one.
    pub fn json(&self, name: &str) -> String {
        let names = |v: RowsVariant| {
            let quoted: Vec<String> = v.names().iter().map(|n| json_string(n)).collect();
            format!("[{}]", quoted.join(","))
        };
        let mut out = format!(
            "{{\"file\":{},\"rows\":{},\"printed\":{},\"handout\":{},\"first_difference\":{},\"differing\":{}",
            json_string(name),
            self.handout.len(),
            self.student.len(),
            self.first_difference.is_none(),
            self.first_difference
                .map_or("null".to_string(), |i| (i + 1).to_string()),
            self.differing
        );
        match (self.exact.first(), self.closest) {
            (Some(&v), _) => {
                let _ = write!(out, ",\"reproduced\":true,\"variants\":{}", names(v));
            }
            (None, Some((v, d))) => {
                let _ = write!(
                    out,
                    ",\"reproduced\":false,\"variants\":{},\"still_differing\":{d}",
                    names(v)
                );
            }
            (None, None) => out.push_str(",\"reproduced\":false,\"variants\":[]"),
        }
        if self.skipped > 0 {
            let _ = write!(out, ",\"skipped\":{}", self.skipped);
        }
        out.push('}');
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_handouts_printout_on_one_line_reads_as_its_rows() {
        let text = "Start: (10,5). End: (10,5). Start: (9,6). End: (10,6). Start: (8,7). End: (11,7). Start: (7,8). End: (11,8). Start: (6,9). End: (12,9). Start: (5,10). End: (12,10). Start: (7,11). End: (13,11). Start: (9,12). End: (13,12). Start: (11,13). End: (14,13). Start: (13,14). End: (14,14). Start: (15,15). End: (15,15).";
        let rows = parse_rows(text).unwrap();
        let check = check_rows(&[(10, 5), (5, 10), (15, 15)], rows);
        assert_eq!(check.first_difference, None);
        assert_eq!(check.handout.len(), 11);
        assert_eq!(check.exact[0], RowsVariant::default());
    }

    #[test]
    fn the_json_says_which_variant_prints_the_rows() {
        let vertices = [(3, 2), (40, 9), (17, 31)];
        let rounding = RowsVariant {
            walk: Walk {
                rounding: true,
                ..Walk::default()
            },
            exclusive_end: false,
        };
        let check = check_rows(&vertices, rounding.rows(&vertices));
        assert_eq!(
            check.json("mine.txt"),
            "{\"file\":\"mine.txt\",\"rows\":30,\"printed\":30,\"handout\":false,\"first_difference\":1,\"differing\":23,\"reproduced\":true,\"variants\":[\"rounding\"]}"
        );
        let check = check_rows(&vertices, RowsVariant::default().rows(&vertices));
        assert!(check
            .json("-")
            .contains("\"handout\":true,\"first_difference\":null"));
    }

    #[test]
    fn unreadable_lines_are_named() {
        assert_eq!(parse_rows(" \n\n").unwrap_err(), "the rows text is empty");
        assert_eq!(
            parse_rows("Start: (1,2). End: (3,4).\nStart: (1,2). End: (3).").unwrap_err(),
            "line 2: expected rows as 'Start: (x,y). End: (x,y).', found 3 numbers in 'Start: (1,2). End: (3).'"
        );
        assert_eq!(
            parse_rows("1 -2 3 4").unwrap(),
            vec![[1, -2, 3, 4]],
            "a sign belongs to its number"
        );
        assert!(parse_rows("99999999999 1 2 3")
            .unwrap_err()
            .starts_with("line 1: '99999999999' is not a whole number"));
        // A fraction or an exponent is one number that is not whole.
        for (text, token) in [
            ("Start: (1e30,5). End: (10,5).", "1e30"),
            ("Start: (2.5,5). End: (10,5).", "2.5"),
            ("Start: (1,5). End: (3E-2,5).", "3E-2"),
        ] {
            assert_eq!(
                parse_rows(text).unwrap_err(),
                format!("line 1: '{token}' is not a whole number of pixels"),
            );
        }
        // Console output around the rows is left out.
        assert_eq!(
            parse_rows(
                "$ ./lab3\nRender time: 3 ms.\nStart: (10,5). End: (10,5).\nRender time: 2 ms.\n"
            )
            .unwrap(),
            vec![[10, 5, 10, 5]]
        );
        // A full stop after a number ends a sentence: "(10,5). End".
        assert_eq!(
            parse_rows("Start: (10,5). End: (10,5).").unwrap(),
            vec![[10, 5, 10, 5]]
        );
    }
}
