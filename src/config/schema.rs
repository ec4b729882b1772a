//! The config reader's own list of keys: while [`record`] runs, every key the
//! section readers read or look for is noted with what it allows (the same
//! words the error messages use). The configuration reference of the book
//! (`docs/src/reference/configuration.md`) is checked against it by
//! `tests/config_reference.rs`, so that the page cannot drift from the code.

use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};

/// Keys noted while recording: dotted key with array indices written `[i]`
/// -> the descriptions of what it allows (empty where the reader only
/// looked for the key).
pub type KeyLog = BTreeMap<String, BTreeSet<String>>;

thread_local! {
    static LOG: RefCell<Option<KeyLog>> = const { RefCell::new(None) };
}

/// Runs `f` (which reads configs on this thread) and returns its result with
/// every key the reader read or looked for meanwhile.
pub fn record<T>(f: impl FnOnce() -> T) -> (T, KeyLog) {
    let outer = LOG.with(|l| l.replace(Some(KeyLog::new())));
    let out = f();
    let log = LOG.with(|l| l.replace(outer)).unwrap_or_default();
    (out, log)
}

/// Notes that the reader reads (`allows` = what it accepts) or looks for
/// (`allows` = None) `key`; nothing unless [`record`] is running.
pub(super) fn note(key: &str, allows: Option<&str>) {
    LOG.with(|l| {
        if let Some(log) = l.borrow_mut().as_mut() {
            let entry = log.entry(generic_key(key)).or_default();
            if let Some(a) = allows {
                entry.insert(a.to_string());
            }
        }
    });
}

/// `load.harmonics[2].amplitude` -> `load.harmonics[i].amplitude`.
pub fn generic_key(key: &str) -> String {
    let mut out = String::with_capacity(key.len());
    let mut in_index = false;
    for c in key.chars() {
        match c {
            '[' => {
                in_index = true;
                out.push_str("[i]");
            }
            ']' => in_index = false,
            _ if !in_index => out.push(c),
            _ => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_become_i() {
        assert_eq!(generic_key("load.harmonics[12].amplitude"), "load.harmonics[i].amplitude");
        assert_eq!(generic_key("rolling.speed"), "rolling.speed");
    }

    #[test]
    fn records_only_while_recording() {
        note("a.b", Some("x"));
        let ((), log) = record(|| {
            note("a.b", Some("x"));
            note("a.c[3].d", None);
        });
        assert_eq!(log.len(), 2);
        assert!(log["a.b"].contains("x"));
        assert!(log["a.c[i].d"].is_empty());
        let ((), empty) = record(|| ());
        assert!(empty.is_empty());
    }
}
