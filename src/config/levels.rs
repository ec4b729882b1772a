//! Section `[levels]`: the bands the rail's roughness levels are reported
//! in and the limit they are held against ([`crate::levels`]).
//!
//! ```toml
//! [levels]
//! bands = "third-octave"      # or "en13231-3" (10-30, 30-100, 100-300, 300-1000 mm)
//! limit = "iso3095"           # ISO 3095's rail roughness limit (one-third octaves, the
//!                             # default); "grinding" (EN 13231-3 bands, the default
//!                             # there), "file" (limit_file), "table" (limit_table) or "none"
//! limit_file = "limit.csv"    # limit = "file": CSV `wavelength, level`, relative to the config
//! limit_name = "my limit"     # what the terminal calls the curve (default: ISO 3095 / the file name)
//! [[levels.limit_table]]      # limit = "table": one entry per band
//! wavelength = 0.0315         # m, inside the band (the nominal centre)
//! level = 15.0                # dB re 1 um
//! ```
//!
//! A curve read from a file is resolved into `limit = "table"`: the run
//! file holds the values, and a resumed run needs no file. Without the
//! section the levels are one-third octaves against ISO 3095, and the
//! resolved config has no `[levels]` (configs without it resolve as
//! before).

use super::ConfigError;
use super::reader::{Range, Section};
use crate::levels::BandSet;
use crate::levels::limit::{LimitCurve, band_of, read_curve_file, set_name};
use crate::params::LevelParams;
use std::path::Path;
use toml::{Table, Value};

/// Reads `[levels]`; the defaults without it. `dir`: the config's folder
/// (a relative `limit_file` is read from there). None when a key is
/// invalid (recorded).
pub fn read(root: &mut Table, resolved: &mut Table, dir: &Path, errors: &mut Vec<ConfigError>) -> Option<LevelParams> {
    if !root.contains_key("levels") {
        return Some(LevelParams::default());
    }
    let mut s = Section::new(root, "", "levels", errors);
    let bands = match s.choice("bands", Some("third-octave"), &["third-octave", "en13231-3"]).as_deref() {
        Some("en13231-3") => Some(BandSet::En13231),
        Some(_) => Some(BandSet::ThirdOctave),
        None => None,
    };
    let default_limit = if bands == Some(BandSet::En13231) { "grinding" } else { "iso3095" };
    let kind = s.choice("limit", Some(default_limit), &["iso3095", "grinding", "file", "table", "none"]);
    let name = if s.has("limit_name") { s.string("limit_name", "") } else { None };
    let curve = match (kind.as_deref(), bands) {
        (Some("iso3095"), Some(BandSet::En13231)) => {
            s.error(
                "limit",
                "= \"iso3095\" is a one-third-octave curve; with levels.bands = \"en13231-3\" use \"grinding\" \
                 (the default), \"file\" or \"table\" (a network's values for its class of work), or \"none\""
                    .into(),
            );
            None
        }
        (Some("iso3095"), Some(_)) => Some(LimitCurve::iso3095()),
        (Some("grinding"), Some(BandSet::ThirdOctave)) => {
            s.error(
                "limit",
                "= \"grinding\" is a limit in EN 13231-3's bands: set levels.bands = \"en13231-3\" with it".into(),
            );
            None
        }
        (Some("grinding"), Some(_)) => Some(LimitCurve::grinding()),
        (Some("none"), Some(_)) => Some(LimitCurve::none()),
        (Some("file"), Some(set)) => read_file(&mut s, dir, set),
        (Some("table"), Some(set)) => read_table(&mut s, set),
        _ => None,
    };
    for (key, needs) in [("limit_file", "file"), ("limit_table", "table")] {
        if s.has(key) && kind.as_deref().is_some_and(|k| k != needs) {
            s.error(
                key,
                format!(
                    "is only read with levels.limit = \"{needs}\" (levels.limit = \"{}\")",
                    kind.as_deref().unwrap_or("")
                ),
            );
        }
    }
    let curve = curve.map(|c| LimitCurve { name: name.clone().unwrap_or(c.name), ..c });
    // A file's curve is kept as a table: the resolved config stands alone.
    if kind.as_deref() == Some("file")
        && let Some(c) = &curve
    {
        s.resolved.insert("limit".into(), Value::String("table".into()));
        s.resolved.insert("limit_name".into(), Value::String(c.name.clone()));
        let entries = c.points.iter().map(|(w, l)| {
            let mut t = Table::new();
            t.insert("wavelength".into(), Value::Float(*w));
            t.insert("level".into(), Value::Float(*l));
            Value::Table(t)
        });
        s.resolved.insert("limit_table".into(), Value::Array(entries.collect()));
    }
    resolved.insert("levels".into(), Value::Table(s.finish()));
    Some(LevelParams { bands: bands?, limit: curve? })
}

/// `limit = "file"`: the CSV `limit_file`, relative to `dir`.
fn read_file(s: &mut Section, dir: &Path, set: BandSet) -> Option<LimitCurve> {
    if !s.has("limit_file") {
        s.error("limit_file", "missing: levels.limit = \"file\" needs the CSV of `wavelength, level`".into());
        return None;
    }
    let file = s.string("limit_file", "")?;
    s.resolved.remove("limit_file");
    let path = dir.join(&file);
    match read_curve_file(&path, set) {
        Ok(points) => Some(LimitCurve { name: file, points }),
        Err(e) => {
            s.error("limit_file", format!("= \"{file}\": {e}"));
            None
        }
    }
}

/// `limit = "table"`: the entries of `limit_table`.
fn read_table(s: &mut Section, set: BandSet) -> Option<LimitCurve> {
    if !s.has("limit_table") {
        s.error("limit_table", "missing: levels.limit = \"table\" needs [[levels.limit_table]] entries".into());
        return None;
    }
    let entries = s.array_of_tables("limit_table", |t| {
        let w = t.f64("wavelength", None, Range::Positive);
        let l = t.f64("level", None, Range::Closed(-100.0, 100.0));
        Some((w?, l?))
    })?;
    let mut points: Vec<(f64, f64)> = Vec::new();
    for (i, (w, l)) in entries.into_iter().enumerate() {
        let Some(band) = band_of(set, w) else {
            s.error(
                &format!("limit_table[{i}].wavelength"),
                format!("= {w} m is in none of the bands ({})", set_name(set)),
            );
            return None;
        };
        if let Some(j) = points.iter().position(|(p, _)| band.contains(*p)) {
            s.error(
                &format!("limit_table[{i}].wavelength"),
                format!("= {w} m: the {} band again (entry {j})", band.label()),
            );
            return None;
        }
        points.push((w, l));
    }
    if points.is_empty() {
        s.error("limit_table", "must list at least one band".into());
        return None;
    }
    Some(LimitCurve { name: "user".into(), points })
}
