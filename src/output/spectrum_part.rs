//! A part of a spectrum's measurement (`corrugation spectrum --part K/N`):
//! the root's resolved config; group `spectrum_part` with the attributes
//! `part`, `parts`, `linear_contact` (1 or 0), `passages`, `cpu_seconds`,
//! `wall_seconds`, `warnings` (one per line) and the responses it measured:
//! dimension `entry` (a perturbation: `entry_class`, `entry_slot`), its
//! values on the class's basis one after the other (`value`:
//! `response_real`, `response_imag`, `entry_start` the first value's
//! index), and on `rail` x `harmonic` the smooth and base rails' wear
//! (`forced_real`, `forced_imag`, `base_real`, `base_imag`) and
//! `mean_wear`. `corrugation spectrum merge` reads every part back
//! ([`read_part`]) and writes the spectrum file.

use super::netcdf::{Attrs, NcError, read_attr_str, read_f64, read_i64, write_atomically};
use crate::spectrum::measure::Responses;
use ndarray::{Array1, Array2, Ix1, Ix2};
use num_complex::Complex64;
use std::path::Path;

/// Writes part `k` of `n` of a measurement (`r`, of the resolved
/// `config`) to `path` atomically.
pub fn write_part(path: &Path, r: &Responses, (k, n): (usize, usize), config: &str) -> Result<(), NcError> {
    write_atomically(path, |root| {
        root.attr_str("title", "part of a linear growth spectrum's measurement")?;
        root.attr_str("program", "corrugation")?;
        root.attr_str("version", env!("CARGO_PKG_VERSION"))?;
        root.attr_str("config", config)?;
        let g = root.group("spectrum_part")?;
        g.attr_i64("part", k as i64)?;
        g.attr_i64("parts", n as i64)?;
        g.attr_i64("linear_contact", i64::from(r.linear_contact))?;
        g.attr_i64("passages", r.passages as i64)?;
        g.attr_f64("cpu_seconds", r.cpu_seconds)?;
        g.attr_f64("wall_seconds", r.wall_seconds)?;
        g.attr_str("warnings", &r.warnings.join("\n"))?;
        let labels: Vec<String> = r.resonances.iter().map(|(l, f)| format!("{f:e} {l}")).collect();
        g.attr_str("resonances", &labels.join("\n"))?;
        let (mut class, mut slot, mut start, mut values) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (c, slots) in r.columns.iter().enumerate() {
            for (t, column) in slots.iter().enumerate().filter(|(_, v)| !v.is_empty()) {
                class.push(c as i64);
                slot.push(t as i64);
                start.push(values.len() as i64);
                values.extend(column.iter().copied());
            }
        }
        let entries: Vec<i64> = (0..class.len() as i64).collect();
        g.coord_i64("entry", &entries, "1", "a perturbation this part measured", false)?;
        for (name, v, long) in [
            ("entry_class", &class, "the perturbation's Bloch class (index into the classes measured)"),
            ("entry_slot", &slot, "the perturbation's index in its class's plan"),
            ("entry_start", &start, "the index of its response's first value"),
        ] {
            g.var_i64(name, &["entry"], Array1::from(v.clone()).view().into_dyn(), "1", long)?;
        }
        let index: Vec<i64> = (0..values.len() as i64).collect();
        g.coord_i64("value", &index, "1", "a value of a response (the class's basis)", false)?;
        let re: Array1<f64> = values.iter().map(|v| v.re).collect();
        let im: Array1<f64> = values.iter().map(|v| v.im).collect();
        let long = "the response's contact-filtered wear on the class's basis, share-weighted (complex amplitude, m)";
        g.var_f64("response_real", &["value"], re.view().into_dyn(), "m", &format!("real part of {long}"))?;
        g.var_f64("response_imag", &["value"], im.view().into_dyn(), "m", &format!("imaginary part of {long}"))?;
        let rails: Vec<i64> = (0..r.rails as i64).collect();
        g.coord_i64("rail", &rails, "1", "rail (0: the first)", false)?;
        let harmonics: Vec<i64> = (1..=r.forced.first().map_or(0, Vec::len) as i64).collect();
        g.coord_i64("harmonic", &harmonics, "1", "harmonic n of the stretch (wavelength stretch / n)", false)?;
        for (name, rows) in [("forced", &r.forced), ("base", &r.base)] {
            let n = harmonics.len();
            let re = Array2::from_shape_fn((r.rails, n), |(a, b)| rows[a][b].re);
            let im = Array2::from_shape_fn((r.rails, n), |(a, b)| rows[a][b].im);
            let long = format!("the {name} rail's contact-filtered wear per wheel passage (complex amplitude)");
            g.var_f64(&format!("{name}_real"), &["rail", "harmonic"], re.view().into_dyn(), "m", &long)?;
            g.var_f64(&format!("{name}_imag"), &["rail", "harmonic"], im.view().into_dyn(), "m", &long)?;
        }
        let mean = Array1::from(r.mean_wear.clone());
        g.var_f64("mean_wear", &["rail"], mean.view().into_dyn(), "m", "the smooth rail's mean wear per wheel passage")
    })
}

/// What a part file holds.
#[derive(Debug, Clone)]
pub struct Part {
    /// Its resolved config.
    pub config: String,
    /// Which part of how many.
    pub part: (usize, usize),
    /// Its responses, fitted to `layout` (the measurement's classes and
    /// plan, from the config).
    pub responses: Responses,
}

/// Reads the part file `path`, its responses laid out as `layout`'s (a
/// measurement of the same config with no perturbation measured).
pub fn read_part(path: &Path, mut layout: Responses) -> Result<Part, NcError> {
    let invalid = |what: &str, msg: String| NcError::Invalid { path: path.to_owned(), what: what.into(), msg };
    let group = "spectrum_part";
    let config = read_attr_str(path, "", "config")?;
    let a = Attrs::open(path, group)?;
    let part = (a.i64("part")? as usize, a.i64("parts")? as usize);
    let one = |name: &str| -> Result<Vec<i64>, NcError> {
        Ok(read_i64(path, group, name)?
            .into_dimensionality::<Ix1>()
            .map_err(|e| invalid(name, e.to_string()))?
            .to_vec())
    };
    let (class, slot, start) = (one("entry_class")?, one("entry_slot")?, one("entry_start")?);
    let values = |name: &str| -> Result<Vec<f64>, NcError> {
        Ok(read_f64(path, group, name)?
            .into_dimensionality::<Ix1>()
            .map_err(|e| invalid(name, e.to_string()))?
            .to_vec())
    };
    let (re, im) = (values("response_real")?, values("response_imag")?);
    for ((c, t), s) in class.iter().zip(&slot).zip(&start) {
        let (c, t, s) = (*c as usize, *t as usize, *s as usize);
        let Some(column) = layout.columns.get_mut(c).and_then(|v| v.get_mut(t)) else {
            return Err(invalid("entry_class", format!("perturbation ({c}, {t}) is not one of this config's")));
        };
        let n = layout.classes[c].basis.len();
        if s + n > re.len() {
            return Err(invalid("entry_start", format!("perturbation ({c}, {t}) runs past the values")));
        }
        *column = (s..s + n).map(|i| Complex64::new(re[i], im[i])).collect();
    }
    let table = |name: &str| -> Result<Array2<f64>, NcError> {
        read_f64(path, group, name)?.into_dimensionality::<Ix2>().map_err(|e| invalid(name, e.to_string()))
    };
    for (name, into) in [("forced", &mut layout.forced), ("base", &mut layout.base)] {
        let (re, im) = (table(&format!("{name}_real"))?, table(&format!("{name}_imag"))?);
        *into = (0..re.nrows())
            .map(|r| (0..re.ncols()).map(|k| Complex64::new(re[[r, k]], im[[r, k]])).collect())
            .collect();
    }
    layout.mean_wear = values("mean_wear")?;
    layout.linear_contact = a.i64("linear_contact")? == 1;
    layout.passages = a.i64("passages")? as usize;
    layout.cpu_seconds = read_f64_attr(path, group, "cpu_seconds")?;
    layout.wall_seconds = read_f64_attr(path, group, "wall_seconds")?;
    let warnings = a.str("warnings")?;
    layout.warnings = warnings.lines().filter(|l| !l.is_empty()).map(str::to_owned).collect();
    layout.resonances = a
        .str("resonances")?
        .lines()
        .filter_map(|l| l.split_once(' ').and_then(|(f, label)| Some((label.to_owned(), f.parse().ok()?))))
        .collect();
    Ok(Part { config, part, responses: layout })
}

/// A scalar `f64` attribute of `group`.
fn read_f64_attr(path: &Path, group: &str, name: &str) -> Result<f64, NcError> {
    let file = super::netcdf::open_file(path)?;
    let read = |e| NcError::Read { path: path.to_owned(), what: format!("attribute {name:?} of {group:?}"), source: e };
    file.group(group).and_then(|g| g.attr(name)).and_then(|a| a.read_scalar::<f64>()).map_err(read)
}
