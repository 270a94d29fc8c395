//! How far along a long command is (`report`, `stress`, `check` on many files): one
//! line on standard error per finished step, with an estimate of the time left.
//! Shown only when standard error is a terminal, so that a log file or a pipe gets
//! what the command produces and nothing else.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

/// Counts finished steps of a phase of known length and tells the terminal.
pub struct Progress {
    shown: bool,
    phase: Phase,
}

struct Phase {
    total: usize,
    done: usize,
    start: Instant,
}

impl Progress {
    /// Shown when standard error is a terminal.
    pub fn on_stderr() -> Self {
        Self::new(std::io::stderr().is_terminal())
    }

    fn new(shown: bool) -> Self {
        Progress {
            shown,
            phase: Phase {
                total: 0,
                done: 0,
                start: Instant::now(),
            },
        }
    }

    /// Starts a phase of `total` steps; its estimate counts from now.
    pub fn begin(&mut self, total: usize) {
        self.phase = Phase {
            total,
            done: 0,
            start: Instant::now(),
        };
    }

    /// What is being done, when it has no steps to count.
    pub fn note(&self, what: &str) {
        if self.shown {
            crate::say!("{what}");
        }
    }

    /// One step of the phase is done; `what` says which and how it went.
    pub fn step(&mut self, what: &str) {
        self.phase.done += 1;
        if self.shown {
            let p = &self.phase;
            crate::say!("{}", line(p.done, p.total, what, p.start.elapsed()));
        }
    }
}

/// `[ 3/40] what, about 12 s left`: the time left assumes the steps still to come
/// take as long as the average one so far.
fn line(done: usize, total: usize, what: &str, elapsed: Duration) -> String {
    let width = total.to_string().len();
    let left = match done {
        0 => None,
        _ => Some(elapsed.as_secs_f64() / done as f64 * total.saturating_sub(done) as f64),
    };
    let estimate = match left {
        Some(s) if done < total && s >= 0.5 => format!(", about {} left", seconds(s)),
        _ => String::new(),
    };
    format!("[{done:>width$}/{total}] {what}{estimate}")
}

fn seconds(s: f64) -> String {
    match s {
        s if s < 90.0 => format!("{:.0} s", s.max(1.0)),
        s => format!("{:.0} min", s / 60.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_says_how_far_along_and_what_is_left() {
        let second = Duration::from_secs(1);
        assert_eq!(
            line(3, 40, "a/shot.png: matches", 6 * second),
            "[ 3/40] a/shot.png: matches, about 74 s left"
        );
        assert_eq!(
            line(1, 52, "raytrace", 3 * second),
            "[ 1/52] raytrace, about 3 min left"
        );
        assert_eq!(line(40, 40, "last", 80 * second), "[40/40] last");
        assert_eq!(line(1, 9, "fast", Duration::from_millis(10)), "[1/9] fast");
    }
}
