//! `sweep collect`: the members' results in one netCDF-4 compatible file
//! whose dimensions are the sweep's (named after their keys, with units),
//! e.g. `growth_rate(rolling_speed, track_pad_stiffness, wavelength)`.
//!
//! Per member: `member` (index), `member_file` (file name in the sweep's
//! directory), `status` (0 complete, 1 not: only with `allow_missing`),
//! `passes`, `traffic`, `final_rms` (m), `max_update_ratio`, `cpu_seconds`
//! (s, the sum over its passages), `wear_per_passage` (m3, the mean volume
//! one real passage removes: the passages' volumes weighted by the real
//! passages they stand for; NaN for a study stopped before its first
//! passage), and on `wavelength`: `growth_rate` (dB per 1e5
//! real passages, the mean over the study: `sum_p rate_p m_p / sum_p m_p`,
//! i.e. the change of the contact-filtered amplitude in dB over the traffic)
//! and `initial_spectrum`, `final_spectrum` (m, the contact-filtered
//! amplitudes before the first passage and after the last).
//! A member that is not complete is refused, or with `allow_missing` its
//! values are NaN (`status` 1, root attribute `missing_members`).

use super::member::{MemberStatus, status};
use super::spec::{SweepSpec, dimension_name};
use crate::output::netcdf::{NcError, NcGroup, read_f64, write_atomically};
use ndarray::{Array1, ArrayD, IxDyn};
use std::path::{Path, PathBuf};
use toml::Value;

/// Why a sweep could not be collected.
#[derive(Debug, thiserror::Error)]
pub enum CollectError {
    /// Members are not complete (and missing ones are not allowed).
    #[error(
        "{} of {total} members are not complete (--allow-missing writes NaN for them):\n{}",
        unfinished.len(),
        unfinished.iter().map(|(i, s)| format!("  - member {i}: {s}")).collect::<Vec<_>>().join("\n")
    )]
    Unfinished {
        /// Members in the sweep.
        total: usize,
        /// (member, its status) of those not complete.
        unfinished: Vec<(usize, String)>,
    },
    /// No member is complete: nothing to take the wavelengths from.
    #[error("no member of the sweep is complete; nothing to collect")]
    Empty,
    /// Members' spectra are on different wavelengths.
    #[error(
        "member {member}'s spectrum has other wavelengths than member {first}'s ({path}): the sweep changes the \
         periodic stretch or its grid, so its spectra cannot share a wavelength dimension"
    )]
    Wavelengths {
        /// The first complete member.
        first: usize,
        /// The member that differs.
        member: usize,
        /// Its file.
        path: PathBuf,
    },
    /// A member file could not be read, or the output not written.
    #[error("{0}")]
    File(#[from] NcError),
}

/// One complete member's results.
struct Results {
    passes: f64,
    traffic: f64,
    final_rms: f64,
    max_update_ratio: f64,
    cpu_seconds: f64,
    wear_per_passage: f64,
    growth_rate: Vec<f64>,
    final_spectrum: Vec<f64>,
    initial_spectrum: Vec<f64>,
    wavelengths: Vec<f64>,
}

fn read_results(path: &Path) -> Result<Results, NcError> {
    let col =
        |name: &str| -> Result<Vec<f64>, NcError> { Ok(read_f64(path, "passes", name)?.iter().copied().collect()) };
    let table = |name: &str| -> Result<ndarray::Array2<f64>, NcError> {
        read_f64(path, "passes", name)?.into_dimensionality().map_err(|e| NcError::Invalid {
            path: path.to_owned(),
            what: format!("passes/{name}"),
            msg: e.to_string(),
        })
    };
    let (traffic, scale, rms, ratio, cpu, volume) = (
        col("traffic")?,
        col("traffic_scale")?,
        col("rms_corrugation")?,
        col("update_ratio")?,
        col("cpu_seconds")?,
        col("removed_volume")?,
    );
    let (rate, spectrum) = (table("growth_rate")?, table("filtered_spectrum")?);
    let wavelengths = col("wavelength")?;
    let n = traffic.len();
    if n == 0 {
        // A study that stopped (growth.stop = "saturation") before its first
        // passage could be recorded: complete, with nothing to report.
        let nan = vec![f64::NAN; wavelengths.len()];
        return Ok(Results {
            passes: 0.0,
            traffic: 0.0,
            final_rms: f64::NAN,
            max_update_ratio: f64::NAN,
            cpu_seconds: 0.0,
            wear_per_passage: f64::NAN,
            growth_rate: nan.clone(),
            final_spectrum: nan.clone(),
            initial_spectrum: nan,
            wavelengths,
        });
    }
    let total: f64 = scale.iter().sum();
    let per_real = |v: &dyn Fn(usize) -> f64| (0..n).map(|p| v(p) * scale[p]).sum::<f64>() / total;
    let growth_rate = (0..rate.ncols()).map(|k| per_real(&|p| rate[[p, k]])).collect();
    // Before the first passage: growth_rate[0] = 20 log10(A_1 / A_0) 1e5 / m_0
    // gives A_0 back (where the rate is 0, below the 1 pm floor, A_1).
    let initial_spectrum =
        (0..spectrum.ncols()).map(|k| spectrum[[0, k]] / 10f64.powf(rate[[0, k]] * scale[0] / 2e6)).collect();
    Ok(Results {
        initial_spectrum,
        passes: n as f64,
        traffic: traffic[n - 1],
        final_rms: rms[n - 1],
        max_update_ratio: ratio.iter().copied().fold(0.0, f64::max),
        cpu_seconds: cpu.iter().sum(),
        // Each simulated passage's volume is one real passage's of its kind;
        // weighted by the real passages it stands for.
        wear_per_passage: per_real(&|p| volume[p]),
        growth_rate,
        final_spectrum: spectrum.row(n - 1).to_vec(),
        wavelengths,
    })
}

/// A per-member scalar: (name, how to get it, units, long_name).
type Scalar<'a> = (&'a str, &'a dyn Fn(&Results) -> f64, &'a str, &'a str);

/// What `collect` wrote.
#[derive(Debug, Clone)]
pub struct Collected {
    /// Members in the sweep.
    pub members: usize,
    /// Members written as NaN (not complete).
    pub missing: Vec<usize>,
}

/// Collects the members of `spec` into `out` (written atomically).
/// `configs[i]` is member i's resolved config (TOML text), to tell a stale
/// file from a complete one.
pub fn collect(
    spec: &SweepSpec,
    configs: &[String],
    out: &Path,
    allow_missing: bool,
) -> Result<Collected, CollectError> {
    let statuses: Vec<MemberStatus> = (0..spec.len()).map(|i| status(spec, i, &configs[i])).collect();
    let unfinished: Vec<(usize, String)> =
        statuses.iter().enumerate().filter(|(_, s)| !s.is_complete()).map(|(i, s)| (i, describe(s))).collect();
    if !unfinished.is_empty() && !allow_missing {
        return Err(CollectError::Unfinished { total: spec.len(), unfinished });
    }
    let mut results: Vec<Option<Results>> = Vec::with_capacity(spec.len());
    for (i, s) in statuses.iter().enumerate() {
        results.push(if s.is_complete() { Some(read_results(&spec.member_file(i))?) } else { None });
    }
    let Some((first, reference)) = results.iter().enumerate().find_map(|(i, r)| r.as_ref().map(|r| (i, r))) else {
        return Err(CollectError::Empty);
    };
    let wavelengths = reference.wavelengths.clone();
    if let Some(member) = results.iter().position(|r| r.as_ref().is_some_and(|r| r.wavelengths != wavelengths)) {
        return Err(CollectError::Wavelengths { first, member, path: spec.member_file(member) });
    }
    let missing: Vec<usize> = unfinished.iter().map(|(i, _)| *i).collect();
    let shape: Vec<usize> = spec.dims.iter().map(|d| d.len()).collect();
    let dim_names: Vec<String> = spec.dims.iter().map(|d| d.name()).collect();
    let dims: Vec<&str> = dim_names.iter().map(String::as_str).collect();
    let spec_text = std::fs::read_to_string(&spec.path).unwrap_or_default();
    write_atomically(out, |root| {
        root.attr_str("title", "corrugation sweep")?;
        root.attr_str("program", "corrugation")?;
        root.attr_str("version", env!("CARGO_PKG_VERSION"))?;
        root.attr_str("sweep_spec", &spec_text)?;
        root.attr_str("sweep_directory", &spec.output.display().to_string())?;
        root.attr_str("base_config", &spec.base_text)?;
        root.attr_str("axes", &spec.dims.iter().flat_map(|d| d.keys.clone()).collect::<Vec<_>>().join(" "))?;
        let list = missing.iter().map(usize::to_string).collect::<Vec<_>>().join(" ");
        root.attr_str("missing_members", &list)?;
        root.attr_str(
            "comment",
            "NaN marks the members that were not complete when collected (status = 1, missing_members); cpu_seconds \
             is measured, not reproducible bit for bit",
        )?;
        for d in &spec.dims {
            write_axis(root, d)?;
        }
        root.coord_f64(
            "wavelength",
            &wavelengths,
            "m",
            "wavelength of the profile harmonic (stretch length / n)",
            false,
        )?;
        let per_member = |f: &dyn Fn(&Results) -> f64| -> ArrayD<f64> {
            on_axes(&shape, results.iter().map(|r| r.as_ref().map_or(f64::NAN, f)).collect())
        };
        let index: Vec<i64> = (0..spec.len() as i64).collect();
        root.var_i64("member", &dims, on_axes(&shape, index).view(), "1", "member index (sweep member --index)")?;
        let files: Vec<String> = (0..spec.len())
            .map(|i| spec.member_file(i).file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default())
            .collect();
        root.var_str(
            "member_file",
            &dims,
            on_axes(&shape, files).view(),
            "",
            "the member's run file in the sweep directory",
        )?;
        let flags: Vec<i8> = statuses.iter().map(|s| if s.is_complete() { 0 } else { 1 }).collect();
        root.var_i8("status", &dims, on_axes(&shape, flags).view(), "1", "member status when collected")?;
        root.var_attr_str("status", "flag_values", "0 1")?;
        root.var_attr_str("status", "flag_meanings", "complete not_complete")?;
        let scalars: [Scalar; 6] = [
            ("passes", &|r| r.passes, "1", "simulated passages"),
            ("traffic", &|r| r.traffic, "1", "real wheel passages represented"),
            ("final_rms", &|r| r.final_rms, "m", "rms corrugation of the centre line after the last passage"),
            ("max_update_ratio", &|r| r.max_update_ratio, "1", "largest relative profile change of an update"),
            ("cpu_seconds", &|r| r.cpu_seconds, "s", "CPU time of the member's passages"),
            (
                "wear_per_passage",
                &|r| r.wear_per_passage,
                "m3",
                "mean volume removed from the rail grid by one real passage",
            ),
        ];
        for (name, f, units, long_name) in scalars {
            root.var_f64(name, &dims, per_member(f).view(), units, long_name)?;
        }
        let mut spectral_dims = dims.clone();
        spectral_dims.push("wavelength");
        let mut spectral_shape = shape.clone();
        spectral_shape.push(wavelengths.len());
        let spectral = |f: &dyn Fn(&Results) -> &Vec<f64>| -> ArrayD<f64> {
            let v: Vec<f64> = results
                .iter()
                .flat_map(|r| match r {
                    Some(r) => f(r).clone(),
                    None => vec![f64::NAN; wavelengths.len()],
                })
                .collect();
            on_axes(&spectral_shape, v)
        };
        root.var_f64(
            "growth_rate",
            &spectral_dims,
            spectral(&|r| &r.growth_rate).view(),
            "dB/1e5 passages",
            "mean growth rate of each harmonic of the contact-filtered profile over the study",
        )?;
        root.var_f64(
            "initial_spectrum",
            &spectral_dims,
            spectral(&|r| &r.initial_spectrum).view(),
            "m",
            "amplitude spectrum of the contact-filtered profile before the first passage",
        )?;
        root.var_f64(
            "final_spectrum",
            &spectral_dims,
            spectral(&|r| &r.final_spectrum).view(),
            "m",
            "amplitude spectrum of the contact-filtered profile after the last passage",
        )
    })?;
    Ok(Collected { members: spec.len(), missing })
}

/// One value per member (row-major) on the sweep's axes of lengths `shape`.
fn on_axes<T>(shape: &[usize], values: Vec<T>) -> ArrayD<T> {
    ArrayD::from_shape_vec(IxDyn(shape), values).expect("one value per member")
}

/// One sweep dimension: its first key's values as the coordinate (numbers,
/// or strings for text and booleans), the other zipped keys as variables on
/// it.
fn write_axis(root: &NcGroup, d: &super::spec::Dimension) -> Result<(), NcError> {
    let name = d.name();
    for (k, (key, values)) in d.keys.iter().zip(&d.values).enumerate() {
        let units = crate::config::units::key_units(key).unwrap_or("");
        let long_name = format!("config key {key} (sweep axis)");
        let numbers: Option<Vec<f64>> = values
            .iter()
            .map(|v| match v {
                Value::Integer(i) => Some(*i as f64),
                Value::Float(f) => Some(*f),
                _ => None,
            })
            .collect();
        let var_name = dimension_name(key);
        match (k, numbers) {
            (0, Some(v)) => root.coord_f64(&name, &v, units, &long_name, false)?,
            (0, None) => root.coord_str(&name, &strings(values), units, &long_name)?,
            (_, Some(v)) => root.var_f64(&var_name, &[&name], Array1::from(v).view().into_dyn(), units, &long_name)?,
            (_, None) => {
                let s = Array1::from(strings(values));
                root.var_str(&var_name, &[&name], s.view().into_dyn(), units, &long_name)?
            }
        }
    }
    Ok(())
}

fn strings(values: &[Value]) -> Vec<String> {
    values
        .iter()
        .map(|v| match v {
            Value::String(s) => s.clone(),
            other => other.to_string(),
        })
        .collect()
}

/// A member's status in words, for messages and `sweep status`.
pub fn describe(s: &MemberStatus) -> String {
    match s {
        MemberStatus::Complete { passes } => format!("complete ({passes} passages)"),
        MemberStatus::Checkpoint { done, planned } => format!("checkpoint ({done} of {planned} passages)"),
        MemberStatus::Running { done, planned } => format!("running (checkpoint {done} of {planned} passages)"),
        MemberStatus::Failed { error } => {
            format!("failed: {}", error.lines().next().unwrap_or(""))
        }
        MemberStatus::Stale => "stale (its file holds another config: the spec changed; delete it)".into(),
        MemberStatus::Missing => "missing (not run)".into(),
    }
}
