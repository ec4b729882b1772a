//! Progress report of the command line: an indicatif bar on a terminal, plain
//! log lines every 10 % otherwise (CI logs, pipes).

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::time::Instant;

/// Progress over a known number of units.
pub struct Progress {
    bar: Option<ProgressBar>,
    total: u64,
    label: String,
    next_log: u64,
    start: Instant,
}

impl Progress {
    /// A progress report over `total` units.
    pub fn new(total: u64, label: &str) -> Self {
        let bar = std::io::stderr().is_terminal().then(|| {
            let b = ProgressBar::new(total);
            b.set_style(
                ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} steps, {elapsed} elapsed, ETA {eta}")
                    .expect("valid template")
                    .progress_chars("=> "),
            );
            b.set_message(label.to_string());
            b
        });
        Progress { bar, total, label: label.to_string(), next_log: 0, start: Instant::now() }
    }

    /// Sets the number of units done.
    pub fn set(&mut self, done: u64) {
        match &self.bar {
            Some(b) => b.set_position(done),
            None => {
                if done >= self.next_log || done == self.total {
                    eprintln!(
                        "{}: {done}/{} steps ({:.1} s)",
                        self.label,
                        self.total,
                        self.start.elapsed().as_secs_f64()
                    );
                    self.next_log = done + (self.total / 10).max(1);
                }
            }
        }
    }

    /// Clears the bar.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}
