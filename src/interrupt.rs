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
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// The file was written in full (no checkpoint left to continue).
const WRITTEN: usize = usize::MAX;

/// Longest wait for a file being written before the signal is answered.
const WRITE_WAIT: Duration = Duration::from_secs(30);

/// The passages the run file holds as a checkpoint (0: none yet), kept up
/// to date by the run's events, and whether the file is being rewritten
/// (then what it holds is only known once the write is over).
#[derive(Clone, Default)]
pub struct Checkpoint(Arc<AtomicUsize>, Arc<AtomicBool>);

impl Checkpoint {
    /// The run file is being rewritten.
    pub fn writing(&self) {
        self.1.store(true, Ordering::SeqCst);
    }

    /// A checkpoint of `done` passages was written.
    pub fn written(&self, done: usize) {
        self.0.store(done, Ordering::SeqCst);
        self.1.store(false, Ordering::SeqCst);
    }

    /// No write is under way any more (one failed: the file is as it was).
    pub fn settled(&self) {
        self.1.store(false, Ordering::SeqCst);
    }

    /// The run file was written in full.
    pub fn finished(&self) {
        self.0.store(WRITTEN, Ordering::SeqCst);
        self.1.store(false, Ordering::SeqCst);
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
    let (kept, writing) = (checkpoint.0.clone(), checkpoint.1.clone());
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            // A write under way is let finish (it is atomic: the file is
            // then either the old checkpoint or the new one, and the
            // message says which).
            let clock = Instant::now();
            while writing.load(Ordering::SeqCst) && clock.elapsed() < WRITE_WAIT {
                std::thread::sleep(Duration::from_millis(2));
            }
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
