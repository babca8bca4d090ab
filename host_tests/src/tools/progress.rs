//! Progress of the long passes of `report` and `bench` on stderr, one line at a time:
//! `report: errors: scene 3 of 14, 12.4 s`.
//!
//! Nothing is printed while a pass is shorter than [`QUIET_FOR`]; after that a line at
//! most every [`EVERY`], and a last line when the pass ends if any line was printed
//! (so a long pass is seen to finish). Steps may come from several threads (the
//! callgrind jobs).

use std::sync::Mutex;
use std::time::{Duration, Instant};

/// How long a pass runs before its progress is shown.
pub const QUIET_FOR: Duration = Duration::from_secs(3);

/// The least time between two progress lines.
pub const EVERY: Duration = Duration::from_secs(1);

/// Should the line for `done` of `total` be printed at `elapsed`, the last line having
/// been printed at `last` (`None`: none yet)?
pub fn due(elapsed: Duration, last: Option<Duration>, done: usize, total: usize) -> bool {
    if elapsed < QUIET_FOR {
        return false;
    }
    match last {
        None => true,
        Some(t) => done >= total || elapsed.saturating_sub(t) >= EVERY,
    }
}

/// The progress line: `PREFIX: UNIT DONE of TOTAL, SECONDS s`.
pub fn line(prefix: &str, unit: &str, done: usize, total: usize, elapsed: Duration) -> String {
    format!(
        "{prefix}: {unit} {done} of {total}, {:.1} s",
        elapsed.as_secs_f64()
    )
}

/// What has been done and when the last line was printed.
struct State {
    done: usize,
    last: Option<Duration>,
}

/// The progress of one pass of `total` steps (scenes, jobs).
pub struct Progress {
    prefix: String,
    unit: &'static str,
    total: usize,
    start: Instant,
    state: Mutex<State>,
}

impl Progress {
    /// A pass of `total` steps called `unit` (`scene`, `job`), its lines starting with
    /// `prefix` (`report: errors`); the clock starts now.
    pub fn new(prefix: impl Into<String>, unit: &'static str, total: usize) -> Self {
        Self {
            prefix: prefix.into(),
            unit,
            total,
            start: Instant::now(),
            state: Mutex::new(State {
                done: 0,
                last: None,
            }),
        }
    }

    /// One more step done: prints the progress line on stderr when it is [`due`].
    pub fn step(&self) {
        let elapsed = self.start.elapsed();
        // A panic elsewhere cannot leave the counter half-written: keep counting.
        let mut s = self.state.lock().unwrap_or_else(|e| e.into_inner());
        s.done += 1;
        if due(elapsed, s.last, s.done, self.total) {
            s.last = Some(elapsed);
            eprintln!(
                "{}",
                line(&self.prefix, self.unit, s.done, self.total, elapsed)
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[allow(non_snake_case)]
    fn S(ms: u64) -> Duration {
        Duration::from_millis(ms)
    }

    #[test]
    fn quiet_for_the_first_seconds() {
        assert!(!due(S(0), None, 1, 10));
        assert!(!due(S(2_999), None, 10, 10), "not even the last step");
        assert!(due(S(3_000), None, 1, 10));
    }

    #[test]
    fn at_most_once_a_second_then_the_last_step() {
        assert!(!due(S(3_500), Some(S(3_000)), 2, 10));
        assert!(due(S(4_000), Some(S(3_000)), 2, 10));
        // The last step is shown even within the second, once something was shown.
        assert!(due(S(3_100), Some(S(3_000)), 10, 10));
    }

    #[test]
    fn the_line() {
        assert_eq!(
            line("report: errors", "scene", 3, 14, S(12_440)),
            "report: errors: scene 3 of 14, 12.4 s"
        );
    }

    #[test]
    fn steps_count_from_threads() {
        let p = Progress::new("test", "job", 8);
        std::thread::scope(|s| {
            for _ in 0..4 {
                s.spawn(|| {
                    p.step();
                    p.step();
                });
            }
        });
        assert_eq!(p.state.lock().unwrap().done, 8);
        // Within the quiet seconds nothing was printed.
        assert!(p.state.lock().unwrap().last.is_none());
    }
}
