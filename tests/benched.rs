//! The benchmark pages quote one sitting: every time, ratio and instruction count
//! that docs/performance.md, docs/check.md, docs/viewer.md and
//! steps/3-wireframe.md give is a generated block (`<!-- bench: NAME -->` to
//! `<!-- end bench -->`) made from the sitting committed in docs/bench/
//! (`bash benches/sitting.sh`). A new sitting that changes a number fails here
//! until `RASTERLAB_UPDATE_DOCS=1 cargo test --release --test suite benched::`
//! rewrites the blocks. A time written by hand elsewhere on those pages must name
//! the commit it was measured at (a record of a change, not a claim about now).

use crate::quoted::{read, rewrite_blocks};
use std::collections::HashMap;

/// One file of docs/bench/: its header line and its rows by case.
struct Sheet {
    /// "commit 1234abc, 2026-12-03, default build, ...".
    about: String,
    rows: Vec<(String, Vec<f64>)>,
}

impl Sheet {
    fn read(name: &str) -> Sheet {
        let path = format!("docs/bench/{name}.tsv");
        let text = read(&path);
        let mut lines = text.lines();
        let about = lines
            .next()
            .and_then(|l| l.strip_prefix("# "))
            .unwrap_or_else(|| panic!("{path}: no '# commit ...' line"))
            .to_string();
        let header = lines.next().unwrap_or_else(|| panic!("{path}: no header"));
        let columns = header.split('\t').count();
        let rows = lines
            .map(|l| {
                let cells: Vec<&str> = l.split('\t').collect();
                assert_eq!(cells.len(), columns, "{path}: {l}");
                let values = cells[1..]
                    .iter()
                    .map(|c| {
                        c.parse()
                            .unwrap_or_else(|_| panic!("{path}: {c:?} is not a number"))
                    })
                    .collect();
                (cells[0].to_string(), values)
            })
            .collect();
        Sheet { about, rows }
    }

    fn get(&self, case: &str) -> &[f64] {
        self.rows
            .iter()
            .find(|(c, _)| c == case)
            .map(|(_, v)| v.as_slice())
            .unwrap_or_else(|| panic!("the sitting has no case {case:?} ({})", self.about))
    }

    fn ms(&self, case: &str) -> f64 {
        self.get(case)[0]
    }

    /// "commit 1234abc, 2026-12-03" for a page to say where a table comes from.
    fn commit_and_date(&self) -> String {
        self.about
            .split(", ")
            .take(2)
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// A time in ms as the tables print it: three significant figures, at most
/// two decimals.
fn ms(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

/// A time in ms to three significant figures, for the short cases too.
fn fine_ms(v: f64) -> String {
    match v {
        v if v >= 1.0 => ms(v),
        v if v >= 0.1 => format!("{v:.3}"),
        v => format!("{v:.4}"),
    }
}

/// How much slower than at the issue's filing a stage may measure and still
/// count as no slower: within this, the shared host's noise decides
/// (performance.md, "Every stage, before and after issue #20").
const SAME_WITHIN: f64 = 1.05;

/// One case drawn in turns, in one build: two threads' speed over one's, two
/// threads' median frame, and what two frames at once allow.
struct Turns {
    ratio: f64,
    two_ms: f64,
    allowed: f64,
}

/// Every file of the sitting.
struct Sitting {
    sheets: HashMap<&'static str, Sheet>,
}

const FIGURES: [&str; 7] = [
    "points",
    "wireframe",
    "filled",
    "depth",
    "vertex-light",
    "pixel-light",
    "pixel-light --affine",
];

impl Sitting {
    fn committed() -> Sitting {
        let names = [
            "stages-default",
            "stages-native",
            "stages-before-default",
            "stages-before-native",
            "threads-default",
            "threads-native",
            "threads_alternating-default",
            "threads_alternating-native",
            "versus_euc-default",
            "versus_euc-native",
            "check-default",
            "viewer-default",
            "instructions-default",
        ];
        Sitting {
            sheets: names.iter().map(|&n| (n, Sheet::read(n))).collect(),
        }
    }

    fn sheet(&self, name: &str) -> &Sheet {
        &self.sheets[name]
    }

    /// `body` and, under it, where it comes from.
    fn sourced(&self, body: String, sheets: &[&str], command: &str) -> String {
        body + "\n" + &self.source(sheets, command)
    }

    /// The provenance line under a table.
    fn source(&self, sheets: &[&str], command: &str) -> String {
        let mut seen: Vec<String> = Vec::new();
        for s in sheets {
            let about = self.sheet(s).commit_and_date();
            if !seen.contains(&about) {
                seen.push(about);
            }
        }
        format!(
            "*From `{command}`, the sitting of {} in `docs/bench/`.*\n",
            seen.join(" and ")
        )
    }

    /// rasterlab against euc, one build.
    fn versus_euc(&self, build: &str) -> String {
        let name = format!("versus_euc-{build}");
        let sheet = self.sheet(&name);
        let mut out = String::from(
            "| case | rows (ms) | edge (ms) | euc (ms) | rows / euc | edge / euc | edge vs euc, pixels differing |\n\
             |---|---|---|---|---|---|---|\n",
        );
        for (case, v) in &sheet.rows {
            out.push_str(&format!(
                "| {case} | {} | {} | {} | {:.2} | {:.2} | {:.3} % |\n",
                ms(v[0]),
                ms(v[1]),
                ms(v[2]),
                v[0] / v[2],
                v[1] / v[2],
                v[3]
            ));
        }
        self.sourced(out, &[name.as_str()], "bash benches/sitting.sh")
    }

    /// The range of rasterlab / euc over the cases `which` picks, both builds.
    fn ratio_range(&self, column: usize, which: impl Fn(&str) -> bool) -> (f64, f64) {
        let mut range = (f64::MAX, f64::MIN);
        for build in ["default", "native"] {
            for (case, v) in &self.sheet(&format!("versus_euc-{build}")).rows {
                if which(case) {
                    let r = v[column] / v[2];
                    range = (range.0.min(r), range.1.max(r));
                }
            }
        }
        range
    }

    fn versus_euc_summary(&self) -> String {
        let boxed = |c: &str| c.starts_with("box");
        let million = |c: &str| c.starts_with("cornell:183");
        let (rows_box, edge_box) = (self.ratio_range(0, boxed), self.ratio_range(1, boxed));
        let (rows_m, edge_m) = (self.ratio_range(0, million), self.ratio_range(1, million));
        let fast = rows_box.0.min(edge_box.0);
        let slow = rows_box.1.max(edge_box.1);
        format!(
            "Where pixels dominate (the box), a rasterlab frame takes {:.2} to {:.2} of \
             euc's time in both builds ({:.1} to {:.1} times as fast). With a million \
             triangles of a few pixels each, the exact rasterizer takes {:.2} to {:.2} of \
             euc's time and the handout's rows {:.2} to {:.2}.\n",
            fast,
            slow,
            1.0 / slow,
            1.0 / fast,
            edge_m.0,
            edge_m.1,
            rows_m.0,
            rows_m.1
        )
    }

    /// Every stage, both rasterizers, both builds.
    fn stages(&self) -> String {
        let (d, n) = (self.sheet("stages-default"), self.sheet("stages-native"));
        let mut out = String::from(
            "| case | rows, default | edge, default | rows, native | edge, native |\n\
             |---|---|---|---|---|\n",
        );
        let groups: [(&str, &[&str]); 4] = [
            ("box 500x500", &FIGURES),
            ("box 2000x2000", &FIGURES),
            ("cornell:16 1920x1080", &["depth", "pixel-light"]),
            ("cornell:183 1920x1080", &["depth", "pixel-light"]),
        ];
        for (group, figures) in groups {
            for figure in figures {
                let cell = |s: &Sheet, raster: &str| ms(s.ms(&format!("{group}/{figure}{raster}")));
                out.push_str(&format!(
                    "| {group}, {figure} | {} | {} | {} | {} |\n",
                    cell(d, ""),
                    cell(d, " --raster edge"),
                    cell(n, ""),
                    cell(n, " --raster edge")
                ));
            }
        }
        self.sourced(
            out,
            &["stages-default", "stages-native"],
            "cargo bench --features bench --bench stages",
        )
    }

    /// Each case of the stages bench in `build`, with its median at the commit
    /// issue #20 was filed at (run in the same sitting) and now.
    fn then_and_now<'s>(&'s self, build: &str) -> impl Iterator<Item = (&'s str, f64, f64)> {
        let then = self.sheet(&format!("stages-before-{build}"));
        let now = self.sheet(&format!("stages-{build}"));
        now.rows
            .iter()
            .map(move |(case, v)| (case.as_str(), then.ms(case), v[0]))
    }

    /// Every case's medians then and now, and now over then, both builds.
    fn before(&self) -> String {
        let mut out = String::from(
            "| case | then, default | now, default | now / then | then, native | now, native | now / then |\n\
             |---|---|---|---|---|---|---|\n",
        );
        for ((case, d0, d1), (_, n0, n1)) in self
            .then_and_now("default")
            .zip(self.then_and_now("native"))
        {
            out.push_str(&format!(
                "| {case} | {} | {} | {:.2} | {} | {} | {:.2} |\n",
                fine_ms(d0),
                fine_ms(d1),
                d1 / d0,
                fine_ms(n0),
                fine_ms(n1),
                n1 / n0
            ));
        }
        self.sourced(
            out,
            &[
                "stages-before-default",
                "stages-default",
                "stages-before-native",
                "stages-native",
            ],
            "bash benches/sitting.sh",
        )
    }

    /// The case and build where now over then is highest, and how many of the
    /// cells, of how many, are below 1.
    fn slowest_against_before(&self) -> (f64, String, usize, usize) {
        let ratios: Vec<(f64, String)> = ["default", "native"]
            .iter()
            .flat_map(|b| {
                self.then_and_now(b)
                    .map(move |(case, then, now)| (now / then, format!("{case}, {b}")))
            })
            .collect();
        let faster = ratios.iter().filter(|(r, _)| *r < 1.0).count();
        let (worst, case) = ratios
            .iter()
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .cloned()
            .unwrap_or_default();
        (worst, case, faster, ratios.len())
    }

    fn lines(&self) -> String {
        let (d, n) = (self.sheet("stages-default"), self.sheet("stages-native"));
        let mut out = String::from(
            "| case | `Interpolate`, default | Bresenham, default | `Interpolate`, native | Bresenham, native |\n\
             |---|---|---|---|---|\n",
        );
        let cases = [
            (
                "walk every line to \\|dx\\|, \\|dy\\| <= 64",
                "walk every line, {}",
            ),
            ("box 500x500, wireframe", "box 500x500, wireframe{}"),
            ("box 500x500, filled", "box 500x500, filled{}"),
        ];
        for (title, pattern) in cases {
            let id = |walk: &str| {
                let suffix = match (pattern.starts_with("walk"), walk) {
                    (true, w) => w.to_string(),
                    (false, "Interpolate") => String::new(),
                    (false, _) => " --lines bresenham".to_string(),
                };
                format!("lines/{}", pattern.replace("{}", &suffix))
            };
            out.push_str(&format!(
                "| {title} | {} | {} | {} | {} |\n",
                ms(d.ms(&id("Interpolate"))),
                ms(d.ms(&id("Bresenham"))),
                ms(n.ms(&id("Interpolate"))),
                ms(n.ms(&id("Bresenham")))
            ));
        }
        self.sourced(
            out,
            &["stages-default", "stages-native"],
            "cargo bench --features bench --bench stages",
        )
    }

    fn threads_of(&self, build: &str, case: &str) -> (f64, f64) {
        let s = self.sheet(&format!("threads-{build}"));
        (
            s.ms(&format!("threads/{case}, 1 thread")),
            s.ms(&format!("threads/{case}, 2 threads")),
        )
    }

    /// One thread's median frame, two threads', two frames' at once (a thread
    /// each), and two threads' bands one after the other on one thread, drawn
    /// in turns.
    fn in_turns_of(&self, build: &str, case: &str) -> (f64, f64, f64, f64) {
        let v = self
            .sheet(&format!("threads_alternating-{build}"))
            .get(case);
        (v[0], v[1], v[2], v[3])
    }

    fn threads(&self) -> String {
        let mut out = String::from(
            "| case | 1 thread, default | 2 threads, default | ratio | 1 thread, native | 2 threads, native | ratio |\n\
             |---|---|---|---|---|---|---|\n",
        );
        let mut cases: Vec<String> = FIGURES
            .iter()
            .map(|f| format!("box 2000x2000, {f}"))
            .collect();
        cases.push("box 500x500, pixel-light".into());
        cases.push("cornell:183 1920x1080, depth --raster edge".into());
        cases.push("cornell:183 1920x1080, pixel-light --raster edge".into());
        cases.push("2000x2000, the clear alone".into());
        for case in cases {
            let (d1, d2) = self.threads_of("default", &case);
            let (n1, n2) = self.threads_of("native", &case);
            out.push_str(&format!(
                "| {case} | {} | {} | {:.2} | {} | {} | {:.2} |\n",
                ms(d1),
                ms(d2),
                d1 / d2,
                ms(n1),
                ms(n2),
                n1 / n2
            ));
        }
        self.sourced(
            out,
            &["threads-default", "threads-native"],
            "cargo bench --features bench --bench threads",
        )
    }

    /// Every case of the threads bench drawn in turns: one thread, two, two
    /// frames at once on a thread each, and the two threads' bands one after
    /// the other on one thread (what the split's work costs, against one
    /// thread's frame).
    fn in_turns(&self) -> String {
        let mut out = String::from(
            "| case | build | 1 thread | 2 threads | ratio | two frames at once, each | two cores allow | two bands in turn | the split's work |\n\
             |---|---|---|---|---|---|---|---|---|\n",
        );
        for (case, _) in &self.sheet("threads_alternating-default").rows {
            for build in ["default", "native"] {
                let (one, two, side, in_turn) = self.in_turns_of(build, case);
                out.push_str(&format!(
                    "| {case} | {build} | {} | {} | {:.2} | {} | {:.2} | {} | {:.3} times |\n",
                    fine_ms(one),
                    fine_ms(two),
                    one / two,
                    fine_ms(side),
                    2.0 * one / side,
                    fine_ms(in_turn),
                    in_turn / one
                ));
            }
        }
        self.sourced(
            out,
            &["threads_alternating-default", "threads_alternating-native"],
            "cargo bench --features bench --bench threads",
        )
    }

    /// Issue #20's targets against the sitting.
    fn targets(&self) -> String {
        let mut out = String::from("| target | measured | |\n|---|---|---|\n");
        let mut row = |target: String, measured: String, met: bool| {
            let verdict = if met { "met" } else { "missed" };
            out.push_str(&format!("| {target} | {measured} | {verdict} |\n"));
        };
        for (stage, case) in [
            ("depth", "cornell:183, depth, 1920x1080"),
            ("pixel-light", "cornell:183, pixel-light, 1920x1080"),
        ] {
            let speedup = |b: &str| {
                let v = self.sheet(&format!("versus_euc-{b}")).get(case);
                v[2] / v[1]
            };
            let (d, n) = (speedup("default"), speedup("native"));
            row(
                format!("a million triangles, {stage}, exact rasterizer, one thread: at least 1.5 times as fast as euc, both builds"),
                format!("{d:.2} times (default), {n:.2} times (native)"),
                d >= 1.5 && n >= 1.5,
            );
        }
        // Two threads against one: judged on the frames drawn in turns (one
        // thread's and two's alternating, so the host's drift is shared),
        // criterion's medians (measured seconds apart) shown beside.
        let turns = |case: &str| {
            ["default", "native"].map(|b| {
                let (one, two, side, _) = self.in_turns_of(b, case);
                Turns {
                    ratio: one / two,
                    two_ms: two,
                    allowed: 2.0 * one / side,
                }
            })
        };
        let criterion = |case: &str| {
            ["default", "native"].map(|b| {
                let (one, two) = self.threads_of(b, case);
                one / two
            })
        };
        for stage in ["depth", "pixel-light"] {
            let case = format!("cornell:183 1920x1080, {stage} --raster edge");
            let [d, n] = turns(&case);
            let [cd, cn] = criterion(&case);
            row(
                format!("the same, {stage}, two threads: at least 1.8 times one, at most 33 ms"),
                format!(
                    "in turns {:.2} times, {} ms (default); {:.2} times, {} ms (native), where two cores allow {:.2} / {:.2}; criterion apart {cd:.2} / {cn:.2} times",
                    d.ratio,
                    ms(d.two_ms),
                    n.ratio,
                    ms(n.two_ms),
                    d.allowed,
                    n.allowed
                ),
                d.ratio >= 1.8 && n.ratio >= 1.8 && d.two_ms <= 33.0 && n.two_ms <= 33.0,
            );
        }
        let lit = ["default", "native"].map(|b| {
            self.sheet(&format!("stages-{b}"))
                .ms("box 500x500/pixel-light")
        });
        row(
            "pixel-light, box, 500x500, one thread: at most 1.0 ms".into(),
            format!("{} ms (default), {} ms (native)", ms(lit[0]), ms(lit[1])),
            lit[0] <= 1.0 && lit[1] <= 1.0,
        );
        let times = ["default", "native"].map(|b| {
            let v = self
                .sheet(&format!("versus_euc-{b}"))
                .get("box, pixel-light, 500x500");
            v[2] / v[0]
        });
        row(
            "the same: at least 5 times as fast as euc".into(),
            format!(
                "{:.2} times (default), {:.2} times (native)",
                times[0], times[1]
            ),
            times[0] >= 5.0 && times[1] >= 5.0,
        );
        // The box stage with the lowest ratio, in each build, by `ratios`.
        let lowest = |ratios: &dyn Fn(&str) -> [f64; 2]| {
            [0, 1].map(|b| {
                FIGURES
                    .iter()
                    .map(|f| (ratios(&format!("box 2000x2000, {f}"))[b], *f))
                    .fold((f64::MAX, ""), |a, b| if b.0 < a.0 { b } else { a })
            })
        };
        let worst = lowest(&|case| turns(case).map(|t| t.ratio));
        let apart = lowest(&|case| criterion(case));
        let clear = turns("2000x2000, the clear alone");
        row(
            "every stage of the box at 2000x2000: two threads at least 1.8 times one".into(),
            format!(
                "in turns lowest {:.2} times, {} (default); {:.2} times, {} (native); the clear alone {:.2} / {:.2} times; criterion apart lowest {:.2} / {:.2}",
                worst[0].0, worst[0].1, worst[1].0, worst[1].1, clear[0].ratio, clear[1].ratio, apart[0].0, apart[1].0
            ),
            worst[0].0 >= 1.8 && worst[1].0 >= 1.8,
        );
        let (worst, case, faster, cells) = self.slowest_against_before();
        let then = self.sheet("stages-before-default").commit_and_date();
        let then = then.split(", ").next().unwrap_or_default();
        row(
            format!("no stage slower than at the issue's filing ({then}), one thread, both builds, in one sitting (slower: more than {SAME_WITHIN} times then)"),
            format!("{faster} of {cells} cases faster; the highest now / then {worst:.2}, {case}"),
            worst <= SAME_WITHIN,
        );
        self.sourced(
            out,
            &[
                "stages-default",
                "stages-native",
                "stages-before-default",
                "stages-before-native",
                "threads-default",
                "threads-native",
                "threads_alternating-default",
                "threads_alternating-native",
                "versus_euc-default",
                "versus_euc-native",
            ],
            "bash benches/sitting.sh",
        )
    }

    /// Instructions per frame with each option beyond the handout, and its time in
    /// the committed report run.
    fn options(&self) -> String {
        let counts = self.sheet("instructions-default");
        let report = crate::quoted::report_medians();
        let base = counts.get("pixel-light")[0];
        let mut out = String::from(
            "| option | instructions per frame | x pixel-light's | ms in the report run |\n\
             |---|---|---|---|\n",
        );
        for (case, v) in &counts.rows {
            let Some(option) = case.strip_prefix("pixel-light") else {
                continue;
            };
            let option = option.trim();
            let time = report
                .iter()
                .find(|(stage, _)| {
                    stage == case
                        || (option.starts_with("--dof") && stage.starts_with("pixel-light --dof"))
                })
                .map_or(String::new(), |(_, t)| format!("{t:.2}"));
            let name = if option.is_empty() {
                "none (pixel-light)".to_string()
            } else {
                format!("`{option}`")
            };
            out.push_str(&format!(
                "| {name} | {:.1} M | {:.1} | {time} |\n",
                v[0] / 1e6,
                v[0] / base
            ));
        }
        self.sourced(
            out,
            &["instructions-default"],
            "bash benches/sitting.sh instructions",
        )
    }

    /// Instructions per frame of the cases issue #19 compares before and after.
    fn instructions(&self) -> String {
        let counts = self.sheet("instructions-default");
        let mut out =
            String::from("| case (500x500 unless said) | instructions per frame |\n|---|---|\n");
        for case in ["depth", "pixel-light", "depth --scene cornell:64"] {
            out.push_str(&format!(
                "| `{case}` | {:.2} M |\n",
                counts.get(case)[0] / 1e6
            ));
        }
        self.sourced(
            out,
            &["instructions-default"],
            "bash benches/sitting.sh instructions",
        )
    }

    fn check(&self) -> String {
        let sheet = self.sheet("check-default");
        let names = [
            ("figure 7", "the handout's Figure 7"),
            ("figure 7, --fit-light", "Figure 7, `--fit-light`"),
            ("walked camera", "a walked-around camera"),
            ("moved light, --fit-light", "a moved light, `--fit-light`"),
            (
                "walked camera and moved light, --fit-light",
                "camera and light both moved, `--fit-light`",
            ),
        ];
        let mut out = String::from("| 500 x 500 screenshot | time |\n|---|---|\n");
        let mut slowest: f64 = 0.0;
        for (id, title) in names {
            let t = sheet.ms(&format!("check 500x500/{id}")) / 1000.0;
            slowest = slowest.max(t);
            out.push_str(&format!("| {title} | {t:.2} s |\n"));
        }
        out.push_str(&format!(
            "\nThe slowest, a full fit, takes {slowest:.2} s on one core.\n\n"
        ));
        out + &self.source(&["check-default"], "bash benches/sitting.sh")
    }

    fn viewer(&self) -> String {
        let sheet = self.sheet("viewer-default");
        let free: Vec<&(String, Vec<f64>)> = sheet
            .rows
            .iter()
            .filter(|(c, _)| c.starts_with("--fps 0"))
            .collect();
        let frames: Vec<String> = free.iter().map(|(_, v)| format!("{:.2}", v[0])).collect();
        let draw = |f: fn(f64, f64) -> f64, start| free.iter().map(|(_, v)| v[1]).fold(start, f);
        let (least, most) = (draw(f64::min, f64::MAX), draw(f64::max, 0.0));
        let drawing = if format!("{least:.2}") == format!("{most:.2}") {
            format!("{least:.2}")
        } else {
            format!("{least:.2} to {most:.2}")
        };
        let fastest = free.iter().map(|(_, v)| v[0]).fold(f64::MAX, f64::min);
        let slowest = free.iter().map(|(_, v)| v[0]).fold(0.0, f64::max);
        let sixty = sheet.get("--fps 60");
        let million = sheet.get("cornell:183 1920x1080 --raster edge, --fps 0");
        format!(
            "Under Xvfb on this 2-core machine, pixel-light at 500x500 with `--fps 0`, {} runs \
             of 600 frames: median frame time {} ms ({:.0} to {:.0} frames per second), of \
             which drawing {} ms; the rest is handing the frame to X. With the \
             default `--fps 60` the frame time is {:.2} ms (draw {:.2} ms). A million \
             triangles (`--scene cornell:183 --size 1920x1080 --raster edge`, pixel-light, \
             `--fps 0`, 300 frames): median frame time {:.1} ms ({:.0} frames per second), \
             of which drawing {:.1} ms.\n\n{}",
            free.len(),
            join_and(&frames),
            1000.0 / slowest,
            1000.0 / fastest,
            drawing,
            sixty[0],
            sixty[1],
            million[0],
            1000.0 / million[0],
            million[1],
            self.source(&["viewer-default"], "bash benches/sitting.sh viewer")
        )
    }

    fn block(&self, name: &str) -> String {
        match name {
            "versus-euc default" => self.versus_euc("default"),
            "versus-euc native" => self.versus_euc("native"),
            "versus-euc summary" => self.versus_euc_summary(),
            "stages" => self.stages(),
            "lines" => self.lines(),
            "threads" => self.threads(),
            "threads in turns" => self.in_turns(),
            "targets" => self.targets(),
            "before" => self.before(),
            "options" => self.options(),
            "instructions" => self.instructions(),
            "check" => self.check(),
            "viewer" => self.viewer(),
            _ => panic!("no bench block {name}"),
        }
    }
}

fn join_and(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

const BENCH_PAGES: [&str; 4] = [
    "docs/performance.md",
    "docs/check.md",
    "docs/viewer.md",
    "steps/3-wireframe.md",
];

#[test]
fn the_bench_blocks_are_the_committed_sitting() {
    let sitting = Sitting::committed();
    let found = rewrite_blocks("bench", &BENCH_PAGES, |name| sitting.block(name));
    for want in [
        "docs/performance.md versus-euc default",
        "docs/performance.md versus-euc native",
        "docs/performance.md versus-euc summary",
        "docs/performance.md stages",
        "docs/performance.md lines",
        "docs/performance.md threads",
        "docs/performance.md threads in turns",
        "docs/performance.md targets",
        "docs/performance.md before",
        "docs/performance.md options",
        "docs/performance.md instructions",
        "docs/check.md check",
        "docs/viewer.md viewer",
        "steps/3-wireframe.md lines",
    ] {
        assert!(found.iter().any(|f| f == want), "{want} missing: {found:?}");
    }
}

/// A time on a benchmark page outside the generated blocks is a record of a
/// change: its paragraph or table row names the commit it was measured at.
#[test]
fn a_hand_written_time_names_its_commit() {
    let mut checked = 0;
    for page in BENCH_PAGES {
        let text = read(page);
        let mut outside = String::new();
        let mut rest = text.as_str();
        while let Some(start) = rest.find("<!-- bench: ") {
            outside.push_str(&rest[..start]);
            let end = rest[start..]
                .find("<!-- end bench -->")
                .unwrap_or_else(|| panic!("{page}: a block never ends"))
                + start;
            rest = &rest[end..];
        }
        outside.push_str(rest);
        // Fenced examples show a command's output, not a measurement.
        let mut in_fence = false;
        let mut prose = String::new();
        for line in outside.lines() {
            if line.starts_with("```") {
                in_fence = !in_fence;
                continue;
            }
            if !in_fence {
                prose.push_str(line);
                prose.push('\n');
            }
        }
        for paragraph in prose.split("\n\n") {
            for part in paragraph.split("\n|") {
                // A step page's cost is the report run's (tests/quoted.rs).
                if part.starts_with("Cost: ") {
                    continue;
                }
                if let Some(time) = first_time(part) {
                    assert!(
                        names_a_commit(part),
                        "{page}: {time} is neither in a generated block nor beside the commit it was measured at: {part}"
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 5, "{checked}");
}

/// The first "1.23 ms", "4 s", "90 us" in `text`.
fn first_time(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    for unit in [" ms", " s", " us", " µs"] {
        for (i, _) in text.match_indices(unit) {
            let after = bytes.get(i + unit.len());
            if after.is_some_and(|c| c.is_ascii_alphanumeric()) {
                continue;
            }
            let digits = text[..i]
                .bytes()
                .rev()
                .take_while(|c| c.is_ascii_digit() || *c == b'.')
                .count();
            // "1/60 s" is a unit, not a measurement.
            let divided = i > digits && bytes[i - digits - 1] == b'/';
            if digits > 0 && bytes[i - digits].is_ascii_digit() && !divided {
                return Some(text[i - digits..i + unit.len()].to_string());
            }
        }
    }
    None
}

/// Whether `text` names a commit: "commit 1234abc" or "(1234abc)".
fn names_a_commit(text: &str) -> bool {
    text.split(|c: char| !c.is_ascii_alphanumeric()).any(|w| {
        w.len() >= 7
            && w.len() <= 12
            && w.bytes().all(|c| c.is_ascii_hexdigit())
            && w.bytes().any(|c| c.is_ascii_digit())
            && w.bytes().any(|c| c.is_ascii_lowercase())
    })
}

#[test]
fn a_time_is_found_and_a_commit_is_recognised() {
    assert_eq!(first_time("took 1.59 ms, then").as_deref(), Some("1.59 ms"));
    assert_eq!(first_time("about 7 s (three)").as_deref(), Some("7 s"));
    assert_eq!(first_time("7 sides, x ms"), None);
    assert_eq!(first_time("by exactly 1/60 s each"), None);
    assert!(names_a_commit("at commit d18bc0c: 72 ms"));
    assert!(!names_a_commit("at 1920x1080, 2000000 pixels"));
}
