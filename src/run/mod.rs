//! A scene run end to end: the validated scene -> contact model -> passages
//! -> run file. The terminal and the file system stay out of the kernels:
//! progress is a callback, output goes through [`crate::output`].

mod study;

pub use study::{Event, ResumeError, RunError, RunState, RunSummary, resume, run_scene, stored_config, stored_state};
