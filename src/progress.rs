//! Progress report of the command line: an indicatif bar on a terminal, plain
//! log lines otherwise (CI logs, pipes): every 10 % of a single passage, and
//! for a growth study one line per passage at most every 2 s (and the last),
//! with passages done / total, ETA and the current rms corrugation.

use corrugation::run::Event;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::time::{Duration, Instant};

/// Progress of one run.
pub struct Progress {
    bar: Option<ProgressBar>,
    label: String,
    growth: bool,
    next_log: usize,
    start: Instant,
    last_line: Option<Instant>,
    first_pass: Option<usize>,
    /// The run file the checkpoints go to.
    file: String,
}

impl Progress {
    /// A progress report for a run labelled `label`; `growth` for a
    /// multi-passage study.
    pub fn new(label: &str, growth: bool) -> Self {
        // A growth study's bar counts passages, a single passage's its steps;
        // the length is set by the first event (1 until then: 0 %, not the
        // 100 % of an empty bar).
        let bar = std::io::stderr().is_terminal().then(|| {
            let b = ProgressBar::new(1);
            b.set_style(
                ProgressStyle::with_template("{msg} [{bar:20}] {percent}%, {elapsed}, ETA {eta}")
                    .expect("valid template")
                    .progress_chars("=> "),
            );
            b.set_message(label.to_string());
            b
        });
        Progress {
            bar,
            label: label.to_string(),
            growth,
            next_log: 0,
            start: Instant::now(),
            last_line: None,
            first_pass: None,
            file: "the run file".into(),
        }
    }

    /// Names the run file the checkpoints are written to.
    pub fn set_file(&mut self, path: &std::path::Path) {
        self.file = path.display().to_string();
    }

    /// Reports one event of the run.
    pub fn event(&mut self, event: Event) {
        match event {
            Event::Steps { done, total } => match &self.bar {
                Some(_) if self.growth => {}
                Some(b) => {
                    b.set_length(total as u64);
                    b.set_position(done as u64);
                }
                None if !self.growth && (done >= self.next_log || done == total) => {
                    let secs = self.start.elapsed().as_secs_f64();
                    say!("{}: {done}/{total} steps ({secs:.1} s)", self.label);
                    self.next_log = done + (total / 10).max(1);
                }
                None => {}
            },
            Event::Passage { .. } if !self.growth => {}
            Event::Passage { done, total, traffic, scale, rms, second_rail, update_ratio, class } => {
                let first = *self.first_pass.get_or_insert(done - 1);
                let elapsed = self.start.elapsed().as_secs_f64();
                let eta = elapsed / (done - first) as f64 * (total - done) as f64;
                let class = class.map(|c| format!(" [{c}]")).unwrap_or_default();
                let rms_text = match &second_rail {
                    Some((a, b, second)) => format!("{rms:.4e} m ({a}), {second:.4e} m ({b})"),
                    None => format!("{rms:.4e} m"),
                };
                let text = format!(
                    "passage {done}/{total}{class}: traffic {traffic:.4e} (m = {scale:.3e}, update ratio \
                     {update_ratio:.2e}), rms corrugation {rms_text}"
                );
                match &self.bar {
                    Some(b) => {
                        // Compact (the bar's line stays under about 100
                        // characters): the full line is the log's.
                        b.set_length(total as u64);
                        if done - 1 == first {
                            b.set_position((done - 1) as u64);
                            b.reset_eta();
                        }
                        b.set_position(done as u64);
                        b.set_message(format!("passage {done}/{total}{class}: rms {:.3} um, m {scale:.2e}", rms * 1e6));
                    }
                    None => {
                        let due = self.last_line.is_none_or(|t| t.elapsed() >= Duration::from_secs(2));
                        if due || done == total {
                            say!("{text}; {elapsed:.1} s elapsed, ETA {eta:.0} s");
                            self.last_line = Some(Instant::now());
                        }
                    }
                }
            }
            Event::Warning { pass, message } => {
                let text = format!("warning: passage {}: {message}", pass + 1);
                match &self.bar {
                    Some(b) => b.println(text),
                    None => say!("{text}"),
                }
            }
            Event::Note { pass, message } => {
                let text = format!("passage {}: {message}", pass + 1);
                match &self.bar {
                    Some(b) => b.println(text),
                    None => say!("{text}"),
                }
            }
            Event::Stopped { pass, reason } => {
                let text = format!("stopped at passage {}: {reason}", pass + 1);
                match &self.bar {
                    Some(b) => b.println(text),
                    None => say!("{text}"),
                }
            }
            Event::Writing { .. } => {}
            Event::Checkpoint { done } => {
                let text = format!("checkpoint: {} holds passages 1-{done}", self.file);
                match &self.bar {
                    Some(b) => b.println(text),
                    None => say!("{text}"),
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

/// Progress of a local sweep over its members: a bar of members done /
/// total with ETA on a terminal, one plain line per member otherwise.
/// Shared by the worker threads.
pub struct MemberBar {
    bar: Option<ProgressBar>,
    total: usize,
    done: std::sync::Mutex<(usize, usize)>,
}

impl MemberBar {
    /// A bar over `total` members.
    pub fn new(total: usize) -> Self {
        let bar = std::io::stderr().is_terminal().then(|| {
            let b = ProgressBar::new(total as u64);
            b.set_style(
                ProgressStyle::with_template("members {pos}/{len} [{bar:30}] {elapsed} elapsed, ETA {eta} {msg}")
                    .expect("valid template")
                    .progress_chars("=> "),
            );
            b
        });
        MemberBar { bar, total, done: std::sync::Mutex::new((0, 0)) }
    }

    /// Member `index` ended (`ok`: complete), `elapsed` s after the start.
    pub fn done(&self, index: usize, ok: bool, elapsed: f64) {
        let (done, failed) = {
            let mut d = self.done.lock().expect("no panics hold it");
            d.0 += 1;
            d.1 += usize::from(!ok);
            *d
        };
        let failures = if failed > 0 { format!(", {failed} failed") } else { String::new() };
        match &self.bar {
            Some(b) => {
                b.set_position(done as u64);
                b.set_message(failures);
                if !ok {
                    b.suspend(|| say!("member {index} failed"));
                }
            }
            None => {
                let eta = elapsed / done as f64 * (self.total - done) as f64;
                let what = if ok { "complete" } else { "FAILED" };
                say!(
                    "member {index} {what}: {done}/{} members{failures}; {elapsed:.1} s elapsed, ETA {eta:.0} s",
                    self.total
                );
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
