//! Section `[roughness]`: the initial irregularity of a growth study
//! (`kind` = none, harmonics, random, levels or measured).
//!
//! A measured record (`kind = "measured"`) is read from `file` (relative to
//! the config file; [`super::record`]), processed as asked (spikes,
//! curvature, detrending) and resampled onto the stretch
//! ([`crate::growth::record`]). The resolved config names the record by its
//! absolute path and the SHA-256 of its samples (`sha256`); the run file
//! stores the samples themselves (group `record`), so that a resumed run
//! rebuilds the same profile without the file, and a config that names a
//! changed file is refused.

use super::ConfigError;
use super::reader::{Range, Section};
use super::record::{HEIGHT_UNITS, POSITION_UNITS, ReadOptions, RecordSamples, read_record};
use crate::growth::record::{Processing, measured_roughness};
use crate::params::{LevelBand, ProfileHarmonic, Roughness};
use std::path::{Path, PathBuf};
use toml::{Table, Value};

/// Shortest wavelength kept from a measured record by default (m): the
/// 5 mm one-third-octave band's centre; a 2 mm trolley record resolves it.
pub const DEFAULT_MEASURED_WAVELENGTH_MIN: f64 = 0.005;
/// Default spike-removal threshold (robust standard deviations).
pub const DEFAULT_SPIKE_THRESHOLD: f64 = 5.0;

/// Where a measured record comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum RecordSource {
    /// Read `roughness.file` relative to this folder (the config's).
    Dir(PathBuf),
    /// The samples stored in a run file (a resumed run).
    Stored(RecordSamples),
}

/// What the roughness reader needs from the rest of the config.
pub struct Context<'a> {
    /// Where a measured record comes from.
    pub source: &'a RecordSource,
    /// The periodic stretch (x_min, x_max) (m), where valid.
    pub stretch: Option<(f64, f64)>,
    /// geometry.wheel_radius (m), where valid.
    pub wheel_radius: Option<f64>,
}

/// Reads `[roughness]`; None when a key is invalid (the errors recorded).
pub fn read(root: &mut Table, resolved: &mut Table, ctx: &Context, errors: &mut Vec<ConfigError>) -> Option<Roughness> {
    let mut s = Section::new(root, "", "roughness", errors);
    let kind = s.choice("kind", Some("none"), &["none", "harmonics", "random", "levels", "measured"]);
    let is = |k: &str| kind.as_deref() == Some(k);
    // The keys of the other kinds may stay (validated, unused), so that
    // --set roughness.kind=... can switch kinds.
    let harmonics = (is("harmonics") || s.has("harmonics")).then(|| s.array_of_tables("harmonics", read_harmonic));
    let seed = (is("random") || is("levels") || s.has("seed")).then(|| s.usize("seed", None, 0, usize::MAX >> 1));
    let measured = is("measured") || s.has("file");
    // The wavelength band: random roughness's, or what is kept of a record.
    let band = is("random") || measured || s.has("rms") || s.has("wavelength_min") || s.has("wavelength_max");
    let (lo, hi) = if band {
        let lo_default = is("measured").then_some(DEFAULT_MEASURED_WAVELENGTH_MIN);
        let hi_default = if is("measured") { ctx.stretch.map(|(a, b)| b - a) } else { None };
        let lo = s.f64("wavelength_min", lo_default, Range::Positive);
        let hi = s.f64("wavelength_max", hi_default, Range::Positive);
        match (lo, hi) {
            (Some(lo), Some(hi)) if lo > hi => {
                s.error("wavelength_max", format!("= {hi} must be >= roughness.wavelength_min = {lo}"));
                (None, None)
            }
            other => other,
        }
    } else {
        (None, None)
    };
    let random = (is("random") || s.has("rms")).then(|| {
        let rms = s.f64("rms", None, Range::NonNegative);
        match (seed.flatten(), rms, lo, hi) {
            (Some(seed), Some(rms), Some(lo), Some(hi)) => {
                Some(Roughness::Random { seed: seed as u64, rms, wavelength_min: lo, wavelength_max: hi })
            }
            _ => None,
        }
    });
    let levels = (is("levels") || s.has("bands")).then(|| {
        let bands = s.array_of_tables("bands", read_band);
        match (seed.flatten(), bands) {
            (Some(seed), Some(bands)) if !bands.is_empty() => Some(Roughness::Levels { seed: seed as u64, bands }),
            (Some(_), Some(_)) => {
                s.error("bands", "must list at least one band".into());
                None
            }
            _ => None,
        }
    });
    let record = measured.then(|| read_measured(&mut s, ctx, lo, hi)).flatten();
    let roughness = match kind.as_deref() {
        Some("harmonics") => harmonics.flatten().map(Roughness::Harmonics),
        Some("random") => random.flatten(),
        Some("levels") => levels.flatten(),
        Some("measured") => record,
        Some(_) => Some(Roughness::None),
        None => None,
    };
    resolved.insert("roughness".into(), Value::Table(s.finish()));
    roughness
}

/// The keys of `kind = "measured"`.
fn read_measured(s: &mut Section, ctx: &Context, lo: Option<f64>, hi: Option<f64>) -> Option<Roughness> {
    let file = match s.raw("file") {
        Some(Value::String(f)) if !f.trim().is_empty() => Some(f),
        Some(other) => {
            s.error("file", format!("expected a path (a string), found `{other}`"));
            None
        }
        None => {
            s.error("file", "missing; expected the record's path, relative to the config file".into());
            None
        }
    };
    let unit = |s: &mut Section, key: &str, allowed: &[(&str, f64)]| -> Result<Option<String>, ()> {
        if !s.has(key) {
            s.raw(key);
            return Ok(None);
        }
        let names: Vec<&str> = allowed.iter().map(|(n, _)| *n).collect();
        s.choice(key, None, &names).map(Some).ok_or(())
    };
    let position_unit = unit(s, "position_unit", &POSITION_UNITS);
    let height_unit = unit(s, "height_unit", &HEIGHT_UNITS);
    let position_column = s.usize("position_column", Some(1), 1, 64);
    let height_column = s.usize("height_column", Some(2), 1, 64);
    let spikes = s.bool("remove_spikes", false);
    let threshold = s.f64("spike_threshold", Some(DEFAULT_SPIKE_THRESHOLD), Range::Closed(2.0, 100.0));
    let curvature = s.bool("curvature_processing", false);
    let radius = s.f64("curvature_radius", ctx.wheel_radius, Range::Positive);
    let detrend = s.bool("detrend", false);
    let window_start =
        if s.has("window_start") { s.f64("window_start", None, Range::Finite).map(Some) } else { Some(None) };
    let sha = match s.raw("sha256") {
        None => Some(None),
        Some(Value::String(h)) if h.len() == 64 && h.chars().all(|c| c.is_ascii_hexdigit()) => Some(Some(h)),
        Some(other) => {
            s.error("sha256", format!("expected 64 hexadecimal digits (the record's fingerprint), found `{other}`"));
            None
        }
    };
    let (
        Some(file),
        Ok(position_unit),
        Ok(height_unit),
        Some(position_column),
        Some(height_column),
        Some(spikes),
        Some(threshold),
        Some(curvature),
        Some(radius),
        Some(detrend),
        Some(window_start),
        Some(sha),
        Some(lo),
        Some(hi),
        Some((x_min, x_max)),
    ) = (
        file,
        position_unit,
        height_unit,
        position_column,
        height_column,
        spikes,
        threshold,
        curvature,
        radius,
        detrend,
        window_start,
        sha,
        lo,
        hi,
        ctx.stretch,
    )
    else {
        return None;
    };
    if position_column == height_column {
        s.error("height_column", format!("= {height_column} is also roughness.position_column"));
        return None;
    }
    let samples = match ctx.source {
        RecordSource::Stored(samples) => samples.clone(),
        RecordSource::Dir(dir) => {
            let path = dir.join(&file);
            let options = ReadOptions { position_unit, height_unit, position_column, height_column };
            match read_record(&path, &options) {
                Ok(mut r) => {
                    r.file = absolute(&path);
                    r
                }
                Err(e) => {
                    s.error("file", e);
                    return None;
                }
            }
        }
    };
    // The resolved config names the record unambiguously.
    s.resolved.insert("file".into(), Value::String(samples.file.display().to_string()));
    s.resolved.insert("position_unit".into(), Value::String(samples.position_unit.clone()));
    s.resolved.insert("height_unit".into(), Value::String(samples.height_unit.clone()));
    let fingerprint = samples.sha256();
    if let Some(given) = sha
        && !given.eq_ignore_ascii_case(&fingerprint)
    {
        s.error(
            "sha256",
            format!(
                "= \"{given}\", but the record {} has the fingerprint \"{fingerprint}\": the record changed since \
                 this config was written (remove roughness.sha256 to accept the new record)",
                samples.file.display()
            ),
        );
        return None;
    }
    s.resolved.insert("sha256".into(), Value::String(fingerprint));
    let processing = Processing {
        spike_threshold: spikes.then_some(threshold),
        curvature_radius: curvature.then_some(radius),
        detrend,
        window_start,
        wavelength_min: lo,
        wavelength_max: hi,
    };
    match measured_roughness(samples, processing, x_min, x_max - x_min) {
        Ok(m) => Some(Roughness::Measured(Box::new(m))),
        Err((key, message)) => {
            s.error(key.trim_start_matches("roughness."), message);
            None
        }
    }
}

/// `path` made absolute (canonical where it exists).
fn absolute(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| std::env::current_dir().map(|d| d.join(path)).unwrap_or(path.into()))
}

fn read_band(s: &mut Section) -> Option<LevelBand> {
    let wavelength = s.f64("wavelength", None, Range::Positive);
    let level = s.f64("level", None, Range::Closed(-100.0, 60.0));
    Some(LevelBand { wavelength: wavelength?, level: level? })
}

fn read_harmonic(s: &mut Section) -> Option<ProfileHarmonic> {
    let amplitude = s.f64("amplitude", None, Range::NonNegative);
    let wavelength = s.f64("wavelength", None, Range::Positive);
    let phase = s.f64("phase", Some(0.0), Range::Finite);
    Some(ProfileHarmonic { amplitude: amplitude?, wavelength: wavelength?, phase: phase? })
}
