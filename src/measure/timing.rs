//! `--time N`: render N times and report the median, as the binary's own benchmark.

use std::time::{Duration, Instant};

/// Median, fastest and slowest of a set of timed runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    pub median: Duration,
    pub min: Duration,
    pub max: Duration,
    pub runs: usize,
}

/// Runs `f` `runs` times (at least once) and times each run.
pub fn time_runs(runs: usize, mut f: impl FnMut()) -> Timing {
    summarize(
        (0..runs.max(1))
            .map(|_| {
                let start = Instant::now();
                f();
                start.elapsed()
            })
            .collect(),
    )
}

/// Median (the mean of the middle two for an even count), min and max of
/// `samples`, which must not be empty.
pub fn summarize(mut t: Vec<Duration>) -> Timing {
    t.sort();
    let n = t.len();
    let median = if n % 2 == 1 {
        t[n / 2]
    } else {
        (t[n / 2 - 1] + t[n / 2]) / 2
    };
    Timing {
        median,
        min: t[0],
        max: t[n - 1],
        runs: n,
    }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

impl std::fmt::Display for Timing {
    /// `median 0.84 ms (min 0.80 ms, max 0.95 ms, 20 runs)`
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "median {:.2} ms (min {:.2} ms, max {:.2} ms, {} runs)",
            ms(self.median),
            ms(self.min),
            ms(self.max),
            self.runs
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_even_and_odd_counts() {
        let ms = |v: &[u64]| v.iter().map(|&m| Duration::from_millis(m)).collect();
        let odd = summarize(ms(&[5, 1, 3]));
        assert_eq!(
            (odd.median, odd.min, odd.max, odd.runs),
            (
                Duration::from_millis(3),
                Duration::from_millis(1),
                Duration::from_millis(5),
                3
            )
        );
        let even = summarize(ms(&[4, 1, 3, 10]));
        assert_eq!(even.median, Duration::from_micros(3500));
        let mut calls = 0;
        assert_eq!(time_runs(0, || calls += 1).runs, 1);
        assert_eq!(calls, 1);
    }

    #[test]
    fn the_line_format() {
        let s = Timing {
            median: Duration::from_micros(840),
            min: Duration::from_micros(800),
            max: Duration::from_micros(950),
            runs: 20,
        }
        .to_string();
        assert_eq!(s, "median 0.84 ms (min 0.80 ms, max 0.95 ms, 20 runs)");
    }
}
