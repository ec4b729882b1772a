//! Reading a run file back as the [`RunState`] a resumed run continues from.
//!
//! Everything is read at the stored precision (f64), so a resumed run
//! starts from exactly the numbers the interrupted one had in memory.

use super::netcdf::{NcError, read_f64, read_i8, read_i64};
use super::run_file::{FIELD_VARS, STEP_VARS, field_columns_mut, step_columns_mut};
use crate::growth::state::{PassRow, RailSnapshot, RunState};
use crate::passage::{PatchFields, PatchHistory};
use ndarray::{Array2, ArrayD, Axis, Ix1, Ix2, Ix3};
use std::path::Path;

/// What the reader must know from the run's config to read its state.
#[derive(Debug, Clone)]
pub struct StateLayout<'a> {
    /// Rail grid nodes (ny, nx).
    pub grid_shape: (usize, usize),
    /// Number of spectrum wavelengths.
    pub wavelengths: usize,
    /// Number of roughness-level bands.
    pub bands: usize,
    /// Patch elements.
    pub elements: usize,
    /// Whether stored histories carry the patch fields.
    pub fields: bool,
    /// Passages whose history the run stores.
    pub history_passes: &'a [usize],
    /// Traffic classes of the study.
    pub classes: usize,
    /// Wheels on the rail of each traffic class's vehicle (the stored
    /// passages of a class of several wheels hold the others' histories).
    pub class_wheels: Vec<usize>,
    /// Whether the run has the wheelset's second rail (group
    /// `second_rail`).
    pub second_rail: bool,
}

/// Reads the state of the run file at `path`, checking every shape against
/// `layout`: the first rail's from the root groups, the wheelset's second
/// rail's from group `second_rail` where `layout` has one.
pub fn read_run_state(path: &Path, layout: &StateLayout) -> Result<RunState, NcError> {
    let mut state = read_rail_state(path, layout, "")?;
    if layout.second_rail {
        let second = read_rail_state(path, layout, "second_rail/")?;
        if second.rows.len() != state.rows.len() {
            return Err(NcError::Invalid {
                path: path.to_owned(),
                what: "second_rail/passes/pass".into(),
                msg: format!("has {} passages, the first rail {}", second.rows.len(), state.rows.len()),
            });
        }
        state.second_rail = Some(Box::new(second));
    }
    Ok(state)
}

/// One rail's state from the groups `{prefix}passes`, `{prefix}rail` and
/// `{prefix}contact`.
fn read_rail_state(path: &Path, layout: &StateLayout, prefix: &str) -> Result<RunState, NcError> {
    let passes_group = format!("{prefix}passes");
    let rail_group = format!("{prefix}rail");
    let invalid = |what: &str, msg: String| NcError::Invalid { path: path.to_owned(), what: what.into(), msg };
    let dim = |a: ArrayD<f64>, what: &str| -> Result<ndarray::Array1<f64>, NcError> {
        a.into_dimensionality::<Ix1>().map_err(|e| invalid(what, e.to_string()))
    };
    // Group `passes`.
    let index = read_i64(path, &passes_group, "pass")?
        .into_dimensionality::<Ix1>()
        .map_err(|e| invalid("passes/pass", e.to_string()))?;
    let done = index.len();
    if index.iter().enumerate().any(|(k, i)| *i != k as i64) {
        return Err(invalid("passes/pass", "passage indices are not 0, 1, 2, ...".into()));
    }
    let column = |name: &str| -> Result<ndarray::Array1<f64>, NcError> {
        let c = dim(read_f64(path, &passes_group, name)?, &format!("passes/{name}"))?;
        if c.len() != done {
            return Err(invalid(&format!("passes/{name}"), format!("has {} rows, not {done}", c.len())));
        }
        Ok(c)
    };
    let table = |name: &str| -> Result<Array2<f64>, NcError> {
        let t = read_f64(path, &passes_group, name)?
            .into_dimensionality::<Ix2>()
            .map_err(|e| invalid(name, e.to_string()))?;
        if t.dim() != (done, layout.wavelengths) {
            return Err(invalid(name, format!("has shape {:?}, not ({done}, {})", t.dim(), layout.wavelengths)));
        }
        Ok(t)
    };
    let [traffic, scale, rms, volume, cpu, ratio] =
        ["traffic", "traffic_scale", "rms_corrugation", "removed_volume", "cpu_seconds", "update_ratio"].map(column);
    let (traffic, scale, rms, volume, cpu, ratio) = (traffic?, scale?, rms?, volume?, cpu?, ratio?);
    let (spectrum, filtered, rate) = (table("spectrum")?, table("filtered_spectrum")?, table("growth_rate")?);
    // Files written before the column existed had no contact loss recorded.
    let optional = |name: &str| match read_f64(path, &passes_group, name) {
        Ok(_) => column(name),
        Err(_) => Ok(ndarray::Array1::zeros(done)),
    };
    let (loss, profile) = (optional("contact_loss_steps")?, optional("profile_contact")?);
    // The band levels (files written before them have none: the study
    // derives them from the spectra, crate::growth::study).
    let band_table = |name: &str| -> Result<Option<Array2<f64>>, NcError> {
        let Ok(t) = read_f64(path, &passes_group, name) else { return Ok(None) };
        let t = t.into_dimensionality::<Ix2>().map_err(|e| invalid(name, e.to_string()))?;
        if t.dim() != (done, layout.bands) {
            return Err(invalid(name, format!("has shape {:?}, not ({done}, {})", t.dim(), layout.bands)));
        }
        Ok(Some(t))
    };
    let (levels, rates) = (band_table("roughness_level")?, band_table("level_rate")?);
    let forced_bands = band_table("forced_band_wear")?;
    // The forced wear (files written before it have none: empty rows).
    let forced = match read_f64(path, &passes_group, "forced_wear") {
        Ok(_) => Some(table("forced_wear")?),
        Err(_) => None,
    };
    // The wear regimes' shares (files written before the wear laws have
    // none: empty rows).
    let shares = match read_f64(path, &passes_group, "wear_regime_share") {
        Ok(t) => {
            let t = t.into_dimensionality::<Ix2>().map_err(|e| invalid("wear_regime_share", e.to_string()))?;
            if t.nrows() != done {
                return Err(invalid("wear_regime_share", format!("has {} rows, not {done}", t.nrows())));
            }
            Some(t)
        }
        Err(_) => None,
    };
    let initial_level = match (&levels, read_f64(path, &passes_group, "initial_level")) {
        (Some(_), Ok(v)) => {
            let v = dim(v, "passes/initial_level")?;
            if v.len() != layout.bands {
                return Err(invalid("passes/initial_level", format!("has {} bands, not {}", v.len(), layout.bands)));
            }
            v.to_vec()
        }
        _ => Vec::new(),
    };
    let band_row = |t: &Option<Array2<f64>>, k: usize| t.as_ref().map_or_else(Vec::new, |t| t.row(k).to_vec());
    let clipped = optional("clipped_steps")?;
    // Files of a study without classes, or written before the column existed.
    let class = match read_i64(path, &passes_group, "traffic_class") {
        Ok(c) => {
            let c = c.into_dimensionality::<Ix1>().map_err(|e| invalid("passes/traffic_class", e.to_string()))?;
            if c.len() != done || c.iter().any(|k| *k < 0 || *k as usize >= layout.classes.max(1)) {
                return Err(invalid(
                    "passes/traffic_class",
                    format!("must hold {done} class indices in 0 .. {}", layout.classes.max(1)),
                ));
            }
            c.mapv(|k| k as usize)
        }
        // Without the column every passage was of the one class; a mix
        // cannot be resumed without it (its tallies decide the next class).
        Err(_) if layout.classes <= 1 => ndarray::Array1::zeros(done),
        Err(e) => return Err(e),
    };
    let rows: Vec<PassRow> = (0..done)
        .map(|k| PassRow {
            index: k as i64,
            traffic: traffic[k],
            traffic_scale: scale[k],
            rms_corrugation: rms[k],
            removed_volume: volume[k],
            cpu_seconds: cpu[k],
            update_ratio: ratio[k],
            contact_loss_steps: loss[k],
            profile_contact: profile[k],
            clipped_steps: clipped[k],
            traffic_class: class[k],
            wear_regime_share: shares.as_ref().map_or_else(Vec::new, |t| t.row(k).to_vec()),
            spectrum: spectrum.row(k).to_vec(),
            filtered_spectrum: filtered.row(k).to_vec(),
            growth_rate: rate.row(k).to_vec(),
            forced_wear: forced.as_ref().map_or_else(Vec::new, |t| t.row(k).to_vec()),
            roughness_level: if initial_level.is_empty() { Vec::new() } else { band_row(&levels, k) },
            level_rate: if initial_level.is_empty() { Vec::new() } else { band_row(&rates, k) },
            forced_band_wear: match &forced_bands {
                // All zeros is the file's way of writing none.
                Some(t) if t.row(k).iter().any(|v| *v != 0.0) => t.row(k).to_vec(),
                _ => Vec::new(),
            },
        })
        .collect();

    // Group `rail`.
    let (ny, nx) = layout.grid_shape;
    let profile = read_f64(path, &rail_group, "state")?
        .into_dimensionality::<Ix2>()
        .map_err(|e| invalid("state", e.to_string()))?;
    if profile.dim() != (ny, nx) {
        return Err(invalid(
            "rail/state",
            format!("has shape {:?}, not the config's grid ({ny}, {nx})", profile.dim()),
        ));
    }
    let stored = read_i64(path, &rail_group, "pass")?
        .into_dimensionality::<Ix1>()
        .map_err(|e| invalid("pass", e.to_string()))?;
    let rail_traffic = dim(read_f64(path, &rail_group, "traffic")?, "rail/traffic")?;
    if rail_traffic.len() != stored.len() {
        return Err(invalid("rail/traffic", format!("has {} entries, not {}", rail_traffic.len(), stored.len())));
    }
    if stored.iter().zip(stored.iter().skip(1)).any(|(a, b)| a >= b)
        || stored.iter().any(|i| *i < 0 || *i as usize >= done)
    {
        return Err(invalid("rail/pass", format!("stored passages must increase within 0 .. {done}")));
    }
    let stack = |name: &str| -> Result<ndarray::Array3<f64>, NcError> {
        let a = read_f64(path, &rail_group, name)?
            .into_dimensionality::<Ix3>()
            .map_err(|e| invalid(name, e.to_string()))?;
        if a.dim() != (stored.len(), ny, nx) {
            return Err(invalid(name, format!("has shape {:?}, not ({}, {ny}, {nx})", a.dim(), stored.len())));
        }
        Ok(a)
    };
    let (profiles, wear) = (stack("profile")?, stack("wear")?);
    let rail = (0..stored.len())
        .map(|k| RailSnapshot {
            index: stored[k],
            traffic: rail_traffic[k],
            profile: profiles.index_axis(Axis(0), k).to_owned(),
            wear: wear.index_axis(Axis(0), k).to_owned(),
        })
        .collect();

    // Group `contact`, and the other wheels' subgroups.
    let (mut histories, mut wheel_histories) = (Vec::new(), Vec::new());
    for k in (0..done).filter(|k| layout.history_passes.contains(k)) {
        let group = format!("{prefix}contact/pass_{k:05}");
        histories.push((k as i64, read_history(path, &group, layout)?));
        let wheels = layout.class_wheels.get(rows[k].traffic_class).copied().unwrap_or(1);
        if wheels > 1 {
            let others = (2..=wheels)
                .map(|w| read_history(path, &format!("{group}/wheel_{w}"), layout))
                .collect::<Result<Vec<_>, _>>()?;
            wheel_histories.push((k as i64, others));
        }
    }
    Ok(RunState { profile, rows, rail, histories, wheel_histories, initial_level, second_rail: None })
}

fn read_history(path: &Path, group: &str, layout: &StateLayout) -> Result<PatchHistory, NcError> {
    let invalid = |what: &str, msg: String| NcError::Invalid { path: path.to_owned(), what: what.into(), msg };
    let mut h = PatchHistory::default();
    for ((name, _, _), column) in STEP_VARS.iter().zip(step_columns_mut(&mut h)) {
        *column = read_f64(path, group, name)?.into_raw_vec_and_offset().0;
    }
    let steps = h.time.len();
    if let Some(((name, _, _), c)) = STEP_VARS.iter().zip(step_columns_mut(&mut h)).find(|(_, c)| c.len() != steps) {
        return Err(invalid(name, format!("has {} steps, not {steps}", c.len())));
    }
    if !layout.fields {
        return Ok(h);
    }
    let mut f = PatchFields::new(steps, layout.elements);
    for ((name, _, _), column) in FIELD_VARS.iter().zip(field_columns_mut(&mut f)) {
        let a = read_f64(path, group, name)?.into_dimensionality::<Ix2>().map_err(|e| invalid(name, e.to_string()))?;
        if a.dim() != column.dim() {
            return Err(invalid(name, format!("has shape {:?}, not {:?}", a.dim(), column.dim())));
        }
        *column = a;
    }
    let stick =
        read_i8(path, group, "stick")?.into_dimensionality::<Ix2>().map_err(|e| invalid("stick", e.to_string()))?;
    if stick.dim() != f.stick.dim() {
        return Err(invalid("stick", format!("has shape {:?}, not {:?}", stick.dim(), f.stick.dim())));
    }
    f.stick = stick;
    // Files written before the wear laws have no regimes: zeros.
    if let Ok(r) = read_i8(path, group, "wear_regime")
        .and_then(|r| r.into_dimensionality::<Ix2>().map_err(|e| invalid("wear_regime", e.to_string())))
        && r.dim() == f.wear_regime.dim()
    {
        f.wear_regime = r;
    }
    h.fields = Some(f);
    Ok(h)
}
