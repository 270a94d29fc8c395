//! The criterion benches' harness: runs them, reads the medians criterion wrote
//! and hands them to `common::record` (benches/stages.rs, threads.rs and
//! check.rs include this file).

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion};
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

/// Runs `benches`, which name each benchmark they add (its full id) in the
/// vector they are given, and with `RASTERLAB_RECORD` writes their medians as
/// the sitting's `NAME-BUILD.tsv`.
pub fn run_and_record(name: &str, benches: impl FnOnce(&mut Criterion, &mut Vec<String>)) {
    let since = SystemTime::now();
    let mut c = Criterion::default().configure_from_args();
    let mut ids = Vec::new();
    benches(&mut c, &mut ids);
    c.final_summary();
    if super::common::recording() {
        let (medians, whole) = criterion_medians(since, &ids);
        if whole {
            super::common::record(name, &["median_ms"], &medians);
        } else if medians.is_empty() {
            // Nothing measured (`--list`, or a filter that matched nothing).
        } else if std::env::var_os("RASTERLAB_RECORD_ADD").is_some() {
            add(name, &["median_ms"], &medians);
        } else {
            // A sitting is never a mix of runs unless it asks to be.
            eprintln!("not recorded: this run measured only some of the benchmarks (a filter?); RASTERLAB_RECORD_ADD=1 adds them to the sitting");
        }
    }
}

/// Adds `rows` to `docs/bench/NAME-BUILD.tsv` (replacing the cases it has),
/// when that file names the same commit and build; otherwise starts it. For a
/// sitting that runs a bench one case at a time (benches/sitting.sh draws the
/// stages of now and then in turns, case by case).
fn add(name: &str, columns: &[&str], rows: &[(String, Vec<f64>)]) {
    let header = super::common::header(columns);
    // "# commit C, DATE, BUILD build, ...": the same code and build, any date.
    fn code_and_build(title: &str) -> (Option<&str>, Option<&str>) {
        let mut fields = title.split(", ");
        (fields.next(), fields.nth(1))
    }
    let ours = header.lines().next().map(code_and_build);
    let kept = std::fs::read_to_string(super::common::path(name)).unwrap_or_default();
    let mut lines = kept.lines();
    let mut all = Vec::new();
    if lines.next().map(code_and_build) == ours && lines.next() == header.lines().nth(1) {
        for line in lines {
            let (case, values) = line.split_once('\t').unwrap_or((line, ""));
            if rows.iter().all(|(c, _)| c != case) {
                // NaN, not a dropped column, for a value that does not read.
                let values = values.split('\t').map(|v| v.parse().unwrap_or(f64::NAN));
                all.push((case.to_string(), values.collect()));
            }
        }
    }
    all.extend(rows.iter().cloned());
    super::common::write(name, &header, &all);
}

/// `samples` samples in about 3 s after 1 s of warming up (criterion takes
/// longer where they need it): the whole sitting in minutes, not half an hour.
pub fn short(g: &mut BenchmarkGroup<WallTime>, samples: usize) {
    g.sample_size(samples)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
}

/// Where criterion keeps its results.
fn criterion_home() -> PathBuf {
    if let Some(home) = std::env::var_os("CRITERION_HOME") {
        return home.into();
    }
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("target"));
    target.join("criterion")
}

fn text_field<'a>(json: &'a str, field: &str) -> Option<&'a str> {
    let start = json.find(&format!("\"{field}\":\""))? + field.len() + 4;
    let end = json[start..].find('"')? + start;
    Some(&json[start..end])
}

/// The median, in ms, of each benchmark `order` names (the full ids as the bench
/// named them) as this process measured it (criterion's `new/estimates.json`
/// written since `since`), in that order, and whether it measured all of them
/// (not, with a filter).
fn criterion_medians(since: SystemTime, order: &[String]) -> (Vec<(String, Vec<f64>)>, bool) {
    let mut found = Vec::new();
    let mut stack = vec![criterion_home()];
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            if !path.ends_with("new/benchmark.json") {
                continue;
            }
            let estimates = path.with_file_name("estimates.json");
            let fresh = std::fs::metadata(&estimates)
                .and_then(|m| m.modified())
                .is_ok_and(|t| t >= since);
            let (Ok(about), Ok(numbers)) = (
                std::fs::read_to_string(&path),
                std::fs::read_to_string(&estimates),
            ) else {
                continue;
            };
            let Some(id) = text_field(&about, "full_id") else {
                continue;
            };
            // "median":{"confidence_interval":{...},"point_estimate":N,...}
            let median = numbers.find("\"median\":").and_then(|at| {
                let rest = &numbers[at..];
                let from = rest.find("\"point_estimate\":")? + 17;
                let to = rest[from..].find([',', '}'])? + from;
                rest[from..to].parse::<f64>().ok()
            });
            if let (true, Some(ns)) = (fresh, median) {
                found.push((id.to_string(), ns / 1e6));
            }
        }
    }
    let medians: Vec<_> = order
        .iter()
        .filter_map(|id| {
            let ms = found.iter().find(|(f, _)| f == id)?.1;
            Some((id.clone(), vec![ms]))
        })
        .collect();
    let whole = medians.len() == order.len();
    (medians, whole)
}
