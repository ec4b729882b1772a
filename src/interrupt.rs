//! What the command line says when a run is stopped by SIGINT (Ctrl-C) or
//! SIGTERM: the line under the progress bar cleared, which checkpoint the
//! run file keeps and the command that continues it; then the process ends
//! with the shell's code for the signal (128 + its number: 130, 143).

use corrugation::output::netcdf::TEMPORARY_SUFFIX;
use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::iterator::Signals;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The file was written in full (no checkpoint left to continue).
const WRITTEN: usize = usize::MAX;

/// The passages the run file holds as a checkpoint (0: none yet), kept up
/// to date by the run's events.
#[derive(Clone, Default)]
pub struct Checkpoint(Arc<AtomicUsize>);

impl Checkpoint {
    /// A checkpoint of `done` passages was written.
    pub fn written(&self, done: usize) {
        self.0.store(done, Ordering::SeqCst);
    }

    /// The run file was written in full.
    pub fn finished(&self) {
        self.0.store(WRITTEN, Ordering::SeqCst);
    }
}

/// Watches for SIGINT and SIGTERM while a run writes `out`; `checkpoint`
/// starts at the passages the file already holds (a resumed study) or 0;
/// `target` is the passages a `resume --passes` was asked to reach (its
/// continuation then needs `--passes` too).
pub fn watch(out: PathBuf, checkpoint: &Checkpoint, target: Option<usize>) {
    let Ok(mut signals) = Signals::new([SIGINT, SIGTERM]) else {
        // Without the handler the default action (end the process) stays.
        return;
    };
    let kept = checkpoint.0.clone();
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            let name = if signal == SIGINT { "SIGINT" } else { "SIGTERM" };
            let clear = if std::io::stderr().is_terminal() { "\r\x1b[2K" } else { "" };
            // A half-written file of this process is of no use.
            let mut tmp = out.clone().into_os_string();
            tmp.push(format!("{TEMPORARY_SUFFIX}{}", std::process::id()));
            let _ = std::fs::remove_file(tmp);
            let file = out.display();
            let what = match kept.load(Ordering::SeqCst) {
                0 => format!("{file} was not written"),
                WRITTEN => format!("{file} was written in full"),
                n => {
                    let more = target.filter(|t| *t > n).map(|t| format!(" --passes {}", t - n)).unwrap_or_default();
                    format!(
                        "{file} keeps its checkpoint after passage {n}: `corrugation resume {file}{more}` continues it"
                    )
                }
            };
            say_raw!("{clear}");
            say!("stopped by {name}: {what}");
            std::process::exit(128 + signal);
        }
    });
}
