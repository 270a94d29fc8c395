//! The pages quote one run: every draw time, speed-up and error that README.md,
//! steps/ and docs/ give for the stages comes from the committed `rasterlab report`
//! run in docs/report/ (report.csv and report.md, written together). A new run
//! that changes a number fails here until the pages say what it says;
//! `RASTERLAB_UPDATE_DOCS=1 cargo test --release --test suite quoted::` rewrites
//! the generated blocks (`<!-- report: NAME -->` to `<!-- end report -->`), and the
//! costs at the end of each step page are checked as they are written.

use std::collections::HashMap;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

pub(crate) fn read(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// One row of report.csv, its fields by column name.
struct Row(HashMap<String, String>);

impl Row {
    fn get(&self, column: &str) -> &str {
        self.0
            .get(column)
            .map(String::as_str)
            .unwrap_or_else(|| panic!("report.csv has no column {column}"))
    }
    fn num(&self, column: &str) -> f64 {
        let v = self.get(column);
        v.parse()
            .unwrap_or_else(|_| panic!("report.csv: {column} = {v:?} is not a number"))
    }
    fn ms(&self) -> String {
        format!("{:.2}", self.num("median_ms"))
    }
}

struct Run {
    rows: Vec<Row>,
    /// report.md, written in the same run.
    markdown: String,
}

impl Run {
    fn committed() -> Run {
        let csv = read("docs/report/report.csv");
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let rows = lines
            .map(|l| {
                let cells: Vec<&str> = l.split(',').collect();
                assert_eq!(cells.len(), header.len(), "report.csv: {l}");
                Row(header
                    .iter()
                    .zip(cells)
                    .map(|(h, c)| (h.to_string(), c.to_string()))
                    .collect())
            })
            .collect();
        Run {
            rows,
            markdown: read("docs/report/report.md"),
        }
    }

    fn row(&self, stage: &str, size: u32) -> &Row {
        self.row_k(stage, size, 1)
    }

    fn row_k(&self, stage: &str, size: u32, k: u32) -> &Row {
        let (size, k) = (size.to_string(), k.to_string());
        self.rows
            .iter()
            .find(|r| r.get("stage") == stage && r.get("size") == size && r.get("k") == k)
            .unwrap_or_else(|| panic!("report.csv has no row {stage} at {size}, k = {k}"))
    }

    /// The values of `column` in the rows of `stage` where `by` varies (the
    /// subdivisions k at 500 x 500, or the sizes at k = 1), in the run's order.
    fn series(&self, stage: &str, by: &str) -> Vec<(u32, f64, &Row)> {
        self.rows
            .iter()
            .filter(|r| r.get("stage") == stage)
            .filter(|r| match by {
                "k" => r.get("size") == "500",
                _ => r.get("k") == "1",
            })
            .map(|r| (r.get(by).parse().unwrap(), r.num("rmse_interior"), r))
            .collect()
    }

    /// docs/error-vs-time.md's readings of the curves.
    fn curves(&self) -> String {
        let vertex = self.series("vertex-light", "k");
        let pixel = self.series("pixel-light", "k");
        let affine = self.series("pixel-light --affine", "k");
        let (p1, p1_ms) = (pixel[0].1, pixel[0].2.num("median_ms"));
        let list = |s: &[(u32, f64, &Row)]| {
            let errors: Vec<String> = s.iter().map(|(_, e, _)| format!("{e:.2}")).collect();
            let ks: Vec<String> = s.iter().map(|(k, _, _)| k.to_string()).collect();
            (errors.join(", "), ks.join(", "))
        };
        let (errors, ks) = list(&vertex);
        let reach = match vertex.iter().find(|(_, e, _)| *e <= p1 * 1.05) {
            Some((k, _, r)) => format!(
                ", within 5% of per-pixel light's {p1:.2} from k = {k}, in {:.1} times \
                 per-pixel light's time ({} triangles against {})",
                r.num("median_ms") / p1_ms,
                r.get("triangles"),
                pixel[0].2.get("triangles")
            ),
            None => format!(", never within 5% of per-pixel light's {p1:.2} in this run"),
        };
        let last = |s: &[(u32, f64, &Row)]| s[s.len() - 1].1;
        let (lo, hi) = pixel
            .iter()
            .fold((f64::MAX, f64::MIN), |(lo, hi), (_, e, _)| {
                (lo.min(*e), hi.max(*e))
            });
        let k_last = pixel[pixel.len() - 1].0;
        let grow = pixel[pixel.len() - 1].2.num("median_ms") / p1_ms;
        let placed = |stage: &str| {
            let r = self.row(stage, 500);
            (r.num("within_one_px"), r.num("placed"))
        };
        let (near, all) = placed("points");
        let (edge_near, edge_all) = placed("wireframe");
        let sizes = |stage: &str| self.series(stage, "size");
        let pixel_sizes = sizes("pixel-light");
        let flat = |stage: &str| {
            let s = sizes(stage);
            let (lo, hi) = s.iter().fold((f64::MAX, f64::MIN), |(lo, hi), (_, e, _)| {
                (lo.min(*e), hi.max(*e))
            });
            format!("{lo:.2} to {hi:.2}")
        };
        let (first, end) = (pixel_sizes[0], pixel_sizes[pixel_sizes.len() - 1]);
        format!(
            "- **Buying accuracy with triangles** (the curves). Splitting every triangle k x k \
             lets per-vertex light follow the light: its interior RMSE is {errors} at k = \
             {ks}{reach}. Affine per-pixel light's falls from {:.2} to {:.2}; perspective-correct \
             per-pixel light's stays between {lo:.2} and {hi:.2} while its time grows {grow:.1} \
             times by k = {k_last}. Many small triangles hide interpolation error, the trade \
             hardware made before it interpolated perspective-correctly.\n\
             - **Where vertices land.** {near} of {all} vertex placements ({:.0}%) are within \
             one pixel of the exact projection. The handout's `int(f X/Z) + W/2` truncates \
             toward zero, so for points left of or above the centre it rounds the wrong way \
             and can be up to 1.5 pixels off; the edge pixels ({:.0}% within one pixel) show \
             the same.\n\
             - **Resolution.** Per-pixel light's interior error shrinks as pixels shrink ({:.2} \
             at {} to {:.2} at {}, {:.1} times less): it is sampling, not shading. Per-vertex \
             ({}) and affine per-pixel ({}) errors barely move across the sizes: they are the \
             method's own.\n",
            affine[0].1,
            last(&affine),
            100.0 * near / all,
            100.0 * edge_near / edge_all,
            first.1,
            first.0,
            end.1,
            end.0,
            first.1 / end.1,
            flat("vertex-light"),
            flat("pixel-light --affine"),
        )
    }

    /// The stages measured at every size, in the report's order.
    fn stages(&self) -> Vec<String> {
        let mut stages: Vec<String> = Vec::new();
        for r in &self.rows {
            let s = r.get("stage").to_string();
            let everywhere = self
                .rows
                .iter()
                .any(|o| o.get("stage") == s && o.get("size") == "2000");
            if everywhere && !stages.contains(&s) {
                stages.push(s);
            }
        }
        stages
    }

    /// `report.md`'s own answers, the bullets under "What this run answers".
    fn answers(&self) -> String {
        let start = self
            .markdown
            .find("## What this run answers")
            .expect("report.md answers");
        let section = &self.markdown[start..];
        let bullets: Vec<&str> = section
            .lines()
            .skip(1)
            .take_while(|l| !l.starts_with("## "))
            .filter(|l| l.starts_with("- "))
            .collect();
        bullets.join("\n") + "\n"
    }

    /// The spread of the draws, as report.md words it.
    fn noise(&self) -> (String, String) {
        let line = self
            .markdown
            .lines()
            .find(|l| l.starts_with("Noise: "))
            .expect("report.md's noise line");
        let percent = |after: &str| -> String {
            let at = line.find(after).unwrap_or_else(|| panic!("{line}")) + after.len();
            line[at..]
                .chars()
                .take_while(|c| c.is_ascii_digit())
                .collect()
        };
        (percent("median, was "), percent("median row and "))
    }

    /// README.md's table of draw times at both sizes.
    fn times(&self) -> String {
        let (median, worst) = self.noise();
        let mut out = format!(
            "Median draw times from that run, one thread pinned to one core of a shared\n\
             2-core machine. Noise: a row's 5 draws spread by {median}% for the median row,\n\
             {worst}% at worst; a fresh run differs by tens of percent here, but the ratios\n\
             between stages hold. At 2000x2000 the focal length is 2000, so the view is the\n\
             same.\n\n| stage | 500x500 | 2000x2000 |\n|---|---|---|\n"
        );
        for s in self.stages() {
            let (a, b) = (self.row(&s, 500).ms(), self.row(&s, 2000).ms());
            out.push_str(&format!("| {s} | {a} ms | {b} ms |\n"));
        }
        out
    }

    /// docs/error-vs-time.md's table at 500 x 500.
    fn table(&self) -> String {
        let mut out = String::from(
            "| stage | figure | median ms | x faster than the ray tracer | error |\n|---|---|---|---|---|\n",
        );
        for s in self.stages() {
            let r = self.row(&s, 500);
            let figure = match s.as_str() {
                "points" => "2",
                "wireframe" => "3",
                "filled" => "4",
                "depth" => "5",
                "vertex-light" => "6",
                "pixel-light" => "7",
                "pixel-light --affine" => "8",
                _ => "",
            };
            let speedup = match r.num("speedup_vs_raytrace") {
                x if s == "raytrace" => format!("{x:.0}"),
                x if x < 10.0 => format!("{x:.2}"),
                x => format!("{x:.0}"),
            };
            let percent = |c: &str| format!("{:.2}%", r.num(c) * 100.0);
            let error = match s.as_str() {
                "raytrace" => "0: the reference".to_string(),
                "points" => format!(
                    "{} of {} vertices within 1 px",
                    r.get("within_one_px"),
                    r.get("placed")
                ),
                "wireframe" => format!(
                    "{} of {} edge pixels within 1 px",
                    r.get("within_one_px"),
                    r.get("placed")
                ),
                _ if !r.get("differing_interior").is_empty() => format!(
                    "{} of interior pixels wrong ({} of all)",
                    percent("differing_interior"),
                    percent("differing_all")
                ),
                _ => format!(
                    "interior RMSE {:.2}, max {}{}",
                    r.num("rmse_interior"),
                    r.get("max_interior"),
                    if s == "raytrace --shadows" {
                        ": what shadows change"
                    } else {
                        ""
                    }
                ),
            };
            out.push_str(&format!(
                "| {s} | {figure} | {} | {speedup} | {error} |\n",
                r.ms()
            ));
        }
        out
    }

    fn block(&self, name: &str) -> String {
        match name {
            "answers" => self.answers(),
            "times" => self.times(),
            "table" => self.table(),
            "curves" => self.curves(),
            _ => panic!("no generated block {name}"),
        }
    }
}

/// The pages that quote the run.
fn pages() -> Vec<String> {
    let mut pages = vec!["README.md".to_string()];
    for dir in ["docs", "steps"] {
        let mut names: Vec<String> = std::fs::read_dir(root().join(dir))
            .unwrap()
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".md"))
            .map(|n| format!("{dir}/{n}"))
            .collect();
        names.sort();
        pages.extend(names);
    }
    pages
}

/// Checks (or, with `RASTERLAB_UPDATE_DOCS`, rewrites) every block
/// `<!-- KIND: NAME -->` ... `<!-- end KIND -->` of `pages` against
/// `generate(NAME)`; returns "PAGE NAME" for each block found.
pub(crate) fn rewrite_blocks(
    kind: &str,
    pages: &[&str],
    generate: impl Fn(&str) -> String,
) -> Vec<String> {
    let update = std::env::var_os("RASTERLAB_UPDATE_DOCS").is_some();
    let (open, close) = (format!("<!-- {kind}: "), format!("<!-- end {kind} -->"));
    let mut found = Vec::new();
    for &page in pages {
        let path = root().join(page);
        let mut text = read(page);
        let mut at = 0;
        while let Some(start) = text[at..].find(&open).map(|i| i + at) {
            let name_end = text[start..].find(" -->").unwrap() + start;
            let name = text[start + open.len()..name_end].to_string();
            let body = name_end + 5;
            let end = text[body..]
                .find(&close)
                .unwrap_or_else(|| panic!("{page}: block {name} never ends"))
                + body;
            let want = generate(&name);
            if update {
                text.replace_range(body..end, &want);
            } else {
                assert_eq!(
                    text[body..end],
                    want,
                    "{page}: the block {name} is not what its run says; run \
                     RASTERLAB_UPDATE_DOCS=1 cargo test --release --test suite"
                );
            }
            found.push(format!("{page} {name}"));
            at = body;
        }
        if update {
            std::fs::write(&path, &text).unwrap();
        }
    }
    found
}

/// Each stage's median time at 500 x 500 (k = 1) in the committed report run.
pub(crate) fn report_medians() -> Vec<(String, f64)> {
    Run::committed()
        .rows
        .iter()
        .filter(|r| r.get("size") == "500" && r.get("k") == "1")
        .map(|r| (r.get("stage").to_string(), r.num("median_ms")))
        .collect()
}

#[test]
fn the_generated_blocks_are_the_committed_runs() {
    let run = Run::committed();
    let pages = pages();
    let pages: Vec<&str> = pages.iter().map(String::as_str).collect();
    let found = rewrite_blocks("report", &pages, |name| run.block(name));
    for want in [
        "README.md times",
        "README.md answers",
        "docs/error-vs-time.md table",
        "docs/error-vs-time.md answers",
        "docs/error-vs-time.md curves",
    ] {
        assert!(found.iter().any(|f| f == want), "{want} missing: {found:?}");
    }
}

/// "Cost: 1.11 ms." at the end of a step page, and "(1.45 ms with `--flag`)":
/// the page's stage at 500 x 500 in the committed run.
#[test]
fn each_step_pages_cost_is_the_runs() {
    let run = Run::committed();
    let stages = [
        ("2-points", "points"),
        ("3-wireframe", "wireframe"),
        ("4-filled", "filled"),
        ("5-depth", "depth"),
        ("6-vertex-light", "vertex-light"),
        ("7-pixel-light", "pixel-light"),
    ];
    for (page, stage) in stages {
        let file = format!("steps/{page}.md");
        let text = read(&file);
        let line = text
            .lines()
            .find(|l| l.starts_with("Cost: "))
            .unwrap_or_else(|| panic!("{file} has no Cost line"));
        let want = format!("Cost: {} ms", run.row(stage, 500).ms());
        assert!(
            line.starts_with(&want),
            "{file}: '{line}' should start '{want}'"
        );
        // The variant in brackets, when the page gives one.
        if let Some(open) = line.find(" ms with `") {
            let number_start = line[..open].rfind('(').unwrap() + 1;
            let flag_end = line[open + 10..].find('`').unwrap() + open + 10;
            let variant = format!("{stage} {}", &line[open + 10..flag_end]);
            let want = run.row(&variant, 500).ms();
            assert_eq!(&line[number_start..open], want, "{file}: {variant}");
        }
    }
}

/// Nothing quotes a stage's time from anywhere but the run: a draw time in ms
/// with two decimals (the report's format) on a page is one of the run's, unless
/// its paragraph names the benchmark sitting it comes from (`cargo bench`), or the
/// page is about benchmarks and says so at its top.
#[test]
fn no_page_quotes_a_stage_time_the_run_does_not_have() {
    let run = Run::committed();
    let known: Vec<String> = run.rows.iter().map(Row::ms).collect();
    let benchmark_pages = [
        "docs/performance.md",
        "docs/check.md",
        "docs/stability.md",
        "docs/viewer.md",
    ];
    let mut checked = 0;
    for page in pages() {
        if benchmark_pages.contains(&page.as_str()) {
            continue;
        }
        let text = read(&page);
        for paragraph in text.split("\n\n") {
            if paragraph.contains("cargo bench") {
                continue;
            }
            for (i, _) in paragraph.match_indices(" ms") {
                let digits = paragraph[..i]
                    .bytes()
                    .rev()
                    .take_while(|c| c.is_ascii_digit() || *c == b'.')
                    .count();
                let number = &paragraph[i - digits..i];
                if number.len() > 3 && number.as_bytes()[number.len() - 3] == b'.' {
                    assert!(
                        known.iter().any(|k| k == number),
                        "{page}: {number} ms is not a time of the committed run: {paragraph}"
                    );
                    checked += 1;
                }
            }
        }
    }
    // README's table alone quotes twenty.
    assert!(checked >= 20, "{checked}");
}
