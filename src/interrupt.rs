//! What the command line says when a run is stopped by SIGINT (Ctrl-C) or
//! SIGTERM: the line under the progress bar cleared, which checkpoint the
//! run file keeps and the command that continues it; then the process ends
//! with the shell's code for the signal (128 + its number: 130, 143).

use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::iterator::Signals;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The passages the run file holds as a checkpoint (0: none yet), kept up
/// to date by the run's events.
#[derive(Clone, Default)]
pub struct Checkpoint(Arc<AtomicUsize>);

impl Checkpoint {
    /// A checkpoint of `done` passages was written.
    pub fn written(&self, done: usize) {
        self.0.store(done, Ordering::SeqCst);
    }
}

/// Watches for SIGINT and SIGTERM while a run writes `out`; `checkpoint`
/// starts at the passages the file already holds (a resumed study) or 0.
pub fn watch(out: PathBuf, checkpoint: &Checkpoint) {
    let Ok(mut signals) = Signals::new([SIGINT, SIGTERM]) else {
        // Without the handler the default action (end the process) stays.
        return;
    };
    let kept = checkpoint.0.clone();
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            let name = if signal == SIGINT { "SIGINT" } else { "SIGTERM" };
            let clear = if std::io::stderr().is_terminal() { "\r\x1b[2K" } else { "" };
            let what = match kept.load(Ordering::SeqCst) {
                0 => format!("{} was not written", out.display()),
                n => format!(
                    "{} keeps its checkpoint after passage {n}: `corrugation resume {}` continues it",
                    out.display(),
                    out.display()
                ),
            };
            say_raw!("{clear}");
            say!("stopped by {name}: {what}");
            std::process::exit(128 + signal);
        }
    });
}
