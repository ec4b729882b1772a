//! The file `corrugation spectrum` writes (book: docs/src/reference/
//! spectrum-file.md): the root's resolved config, program and version; group
//! `spectrum` with
//!
//! * dimension `mode` (fastest growing first): `growth_rate` (dB per 1e5
//!   wheel passages), `wavelength` (m, the mode's largest harmonic),
//!   `frequency` (Hz at the scene's speed), `drift` (m per 1e5 wheel
//!   passages, + in the direction of travel), `bloch_wavenumber` (1/m, the
//!   class's `kappa`), `purity` (1, the largest harmonic's share),
//!   `support_ratio` (1, the envelope's mean over the discrete track's
//!   supports over its mean at mid-span; on a continuous track at the
//!   stretch's start over its middle), `eigenvalue_real` and `eigenvalue_imag` (1 per wheel
//!   passage), with two rails `rail_share` (1, on the first rail);
//! * dimensions (`mode`, `position`): `envelope` (1, rms 1 over the stretch);
//! * on the discrete track, dimension `support`: the supports' positions
//!   (m from the stretch's start); per mode `deepest` (m, where the
//!   pattern is deepest) and `deepest_in_span` (1, that place's share of
//!   its support interval: 0 at the support before it, 0.5 mid-span);
//! * dimension `wavelength` (the stretch's harmonics `L / n`, given by
//!   `forced_wavelength`: the name `wavelength` is the modes'; netCDF stores
//!   that variable as `_nc4_non_coord_wavelength`, which xarray and netCDF
//!   readers show as `wavelength`): `forced_wear` (m per wheel passage, the
//!   smooth rail's pattern) and
//!   `base_wear` (the base rail's wear, the same way), with two rails the
//!   second's as `second_rail_forced_wear`, `second_rail_base_wear`; the
//!   scalar `mean_wear` (m per wheel passage, the smooth rail's mean depth;
//!   `second_rail_mean_wear`);
//! * dimension `harmonic` (every perturbed harmonic of every class):
//!   `harmonic_wavelength` (m), `harmonic_wavenumber` (1/m, signed),
//!   `harmonic_class`, `harmonic_rail`, `diagonal_rate` (dB per 1e5 wheel
//!   passages: the rate of the harmonic alone, `-Re J(s, s)`) and
//!   `diagonal_drift` (m per 1e5 wheel passages).
//!
//! * dimensions (`harmonic`, `source`): `jacobian_real`, `jacobian_imag`
//!   (1 per wheel passage), the map `J` itself, zero between classes.
//!
//! Attributes of the group: the stretch (m), the supercell's stretches, the
//! perturbation (m), the difference scheme, the normal contact, the cost.

use super::forecast_group::{ForecastGroup, write_forecast};
use super::netcdf::{NcError, write_atomically};
use crate::spectrum::modes::DB_PER_NEPER;
use crate::spectrum::{Spectrum, SpectrumParams};
use ndarray::{Array1, Array2};
use std::f64::consts::PI;
use std::path::Path;

/// Writes `s` (measured as `params` say) for the resolved `config` to
/// `path` atomically, with the `forecasts` made from it as groups.
pub fn write_spectrum_file(
    path: &Path,
    s: &Spectrum,
    params: &SpectrumParams,
    config: &str,
    forecasts: &[ForecastGroup],
) -> Result<(), NcError> {
    write_atomically(path, |root| {
        root.attr_str("title", "linear growth spectrum")?;
        root.attr_str("program", "corrugation")?;
        root.attr_str("version", env!("CARGO_PKG_VERSION"))?;
        root.attr_str("config", config)?;
        let g = root.group("spectrum")?;
        g.attr_f64("stretch", s.stretch)?;
        g.attr_i64("bloch_classes", s.cells as i64)?;
        g.attr_f64("perturbation", params.perturbation)?;
        g.attr_str("difference", params.difference.into())?;
        g.attr_str("normal_contact", if s.linear_contact { "linear" } else { "nonlinear or Hertz" })?;
        g.attr_f64("passage_equivalents", s.passage_equivalents)?;
        g.attr_f64("cpu_seconds", s.cpu_seconds)?;
        g.attr_f64("wall_seconds", s.wall_seconds)?;
        g.attr_f64("speed", s.speed)?;
        let n = s.modes.len();
        let index: Vec<i64> = (0..n as i64).collect();
        g.coord_i64("mode", &index, "1", "mode, fastest growing first", false)?;
        // The forced pattern's dimension `wavelength` has no coordinate
        // variable (the name is the modes' wavelength's): its wavelengths are
        // `forced_wavelength`, named in `forced_wear`'s `coordinates`.
        g.dim("wavelength", s.wavelengths.len())?;
        let supercell = s.supercell();
        let per_mode = |f: &dyn Fn(usize) -> f64| (0..n).map(f).collect::<Array1<f64>>();
        let columns: [(&str, Array1<f64>, &str, &str); 10] = [
            (
                "growth_rate",
                per_mode(&|k| s.modes[k].growth_rate()),
                "dB/1e5 passages",
                "exponential growth rate of the mode (dB per 1e5 wheel passages)",
            ),
            ("wavelength", per_mode(&|k| s.wavelength(k)), "m", "wavelength of the mode's largest harmonic"),
            ("frequency", per_mode(&|k| s.frequency(k)), "Hz", "frequency of the mode's largest harmonic at the speed"),
            (
                "mean_frequency",
                per_mode(&|k| s.mean_frequency(k)),
                "Hz",
                "the mode's harmonics' frequencies weighted by their shares of its energy",
            ),
            (
                "drift",
                per_mode(&|k| s.modes[k].drift(s.class_of(k), supercell) * 1e5),
                "m/1e5 passages",
                "drift of the mode's pattern along the rail per 1e5 wheel passages (+: direction of travel)",
            ),
            (
                "bloch_wavenumber",
                per_mode(&|k| 2.0 * PI * s.class_of(k).j as f64 / supercell),
                "1/m",
                "Bloch wavenumber kappa of the mode's class (its harmonics are kappa + 2 pi n / stretch)",
            ),
            ("purity", per_mode(&|k| s.modes[k].purity()), "1", "share of the mode's energy in its largest harmonic"),
            (
                "support_ratio",
                per_mode(&|k| s.support_ratio(k)),
                "1",
                "envelope of the pattern: its mean over the discrete track's supports over its mean at mid-span (on a \
                 continuous track: at the stretch's start over its middle)",
            ),
            (
                "eigenvalue_real",
                per_mode(&|k| s.modes[k].eigenvalue.re),
                "1",
                "real part of the eigenvalue of the per-passage update (growth per wheel passage, neper)",
            ),
            (
                "eigenvalue_imag",
                per_mode(&|k| s.modes[k].eigenvalue.im),
                "1",
                "imaginary part of the eigenvalue (phase turn of the pattern per wheel passage, rad)",
            ),
        ];
        for (name, values, units, long) in &columns {
            g.var_f64(name, &["mode"], values.view().into_dyn(), units, long)?;
        }
        if s.rails == 2 {
            let share = per_mode(&|k| s.modes[k].rail_share(s.class_of(k), 0));
            g.var_f64(
                "rail_share",
                &["mode"],
                share.view().into_dyn(),
                "1",
                "share of the mode's energy on the first rail",
            )?;
        }
        // The dynamics' resonances, and the one each mode is near.
        let freq: Vec<f64> = s.resonances.iter().map(|r| r.1).collect();
        let labels: Vec<String> = s.resonances.iter().map(|r| r.0.clone()).collect();
        g.coord_f64("resonance", &freq, "Hz", "a resonance of the dynamics (the track's, the wheelset's)", false)?;
        g.var_str(
            "resonance_label",
            &["resonance"],
            ndarray::Array1::from(labels).view().into_dyn(),
            "",
            "the body and motion of the resonance",
        )?;
        let near = (0..n).map(|k| s.near_resonance(k).map_or(-1, |i| i as i64)).collect::<Array1<i64>>();
        g.var_i64(
            "near_resonance",
            &["mode"],
            near.view().into_dyn(),
            "1",
            "the resonance within 10 % of the mode's mean frequency nearest it (index into resonance; -1: none)",
        )?;
        g.coord_f64("position", &s.positions, "m", "position along the stretch from its start", false)?;
        let mut envelope = Array2::zeros((n, s.positions.len()));
        for (k, mut row) in envelope.rows_mut().into_iter().enumerate() {
            let e = s.modes[k].envelope(s.class_of(k), 0, &s.positions, supercell);
            row.iter_mut().zip(e).for_each(|(d, v)| *d = v);
        }
        g.var_f64(
            "envelope",
            &["mode", "position"],
            envelope.view().into_dyn(),
            "1",
            "local amplitude of the mode's pattern along the stretch (first rail; rms 1)",
        )?;
        if !s.supports.is_empty() {
            g.coord_f64(
                "support",
                &s.supports,
                "m",
                "the discrete track's supports along the stretch from its start",
                false,
            )?;
            let deepest: Vec<(f64, f64)> = (0..n).map(|k| s.deepest(k).expect("the track has supports")).collect();
            for (name, values, units, long) in [
                (
                    "deepest",
                    deepest.iter().map(|d| d.0).collect::<Array1<f64>>(),
                    "m",
                    "where the mode's pattern is deepest (first rail), from the stretch's start",
                ),
                (
                    "deepest_in_span",
                    deepest.iter().map(|d| d.1).collect(),
                    "1",
                    "that place's share of its support interval (0: the support before it; 0.5: mid-span)",
                ),
            ] {
                g.var_f64(name, &["mode"], values.view().into_dyn(), units, long)?;
            }
        }
        let waves = Array1::from(s.wavelengths.clone());
        g.var_f64(
            "forced_wavelength",
            &["wavelength"],
            waves.view().into_dyn(),
            "m",
            "wavelength of the stretch's harmonic (stretch / n) of the forced and base wear",
        )?;
        let names = [("", 0usize), ("second_rail_", 1)];
        for (prefix, r) in names.iter().take(s.rails) {
            let forced = Array1::from(s.forced_wear[*r].clone());
            g.var_f64(
                &format!("{prefix}forced_wear"),
                &["wavelength"],
                forced.view().into_dyn(),
                "m",
                "amplitude of the contact-filtered wear one wheel passage leaves on the smooth rail (the forced \
                 pattern; per wheel passage)",
            )?;
            g.var_attr_str(&format!("{prefix}forced_wear"), "coordinates", "forced_wavelength")?;
            let base = Array1::from(s.base_wear[*r].clone());
            g.var_f64(
                &format!("{prefix}base_wear"),
                &["wavelength"],
                base.view().into_dyn(),
                "m",
                "amplitude of the contact-filtered wear one wheel passage leaves on the base rail (per wheel passage)",
            )?;
            g.var_attr_str(&format!("{prefix}base_wear"), "coordinates", "forced_wavelength")?;
            let mean = ndarray::Array0::from_elem((), s.mean_wear[*r]);
            g.var_f64(
                &format!("{prefix}mean_wear"),
                &[],
                mean.view().into_dyn(),
                "m",
                "mean depth of the contact-filtered wear one wheel passage leaves on the smooth rail (per wheel passage)",
            )?;
        }
        // Every perturbed harmonic.
        let mut rows: Vec<HarmonicRow> = Vec::new();
        for (class, j) in s.classes.iter().zip(&s.matrices) {
            let m = class.basis.len();
            for (k, h) in class.basis.iter().enumerate() {
                let q = 2.0 * PI * h.index as f64 / supercell;
                let c = j[k * m + k];
                let rate = -DB_PER_NEPER * c.re * 1e5;
                let drift = c.im / q * 1e5;
                rows.push((supercell / h.index.unsigned_abs() as f64, q, class.j as i64, h.rail as i64, rate, drift));
            }
        }
        let idx: Vec<i64> = (0..rows.len() as i64).collect();
        g.coord_i64("harmonic", &idx, "1", "perturbed harmonic (every class's basis)", false)?;
        let col = |f: &dyn Fn(&HarmonicRow) -> f64| rows.iter().map(f).collect::<Array1<f64>>();
        let icol = |f: &dyn Fn(&HarmonicRow) -> i64| rows.iter().map(f).collect::<Array1<i64>>();
        g.var_f64("harmonic_wavelength", &["harmonic"], col(&|r| r.0).view().into_dyn(), "m", "wavelength")?;
        g.var_f64(
            "harmonic_wavenumber",
            &["harmonic"],
            col(&|r| r.1).view().into_dyn(),
            "1/m",
            "signed wavenumber of the harmonic",
        )?;
        g.var_i64("harmonic_class", &["harmonic"], icol(&|r| r.2).view().into_dyn(), "1", "Bloch class j")?;
        g.var_i64("harmonic_rail", &["harmonic"], icol(&|r| r.3).view().into_dyn(), "1", "rail (0: the first)")?;
        g.var_f64(
            "diagonal_rate",
            &["harmonic"],
            col(&|r| r.4).view().into_dyn(),
            "dB/1e5 passages",
            "growth rate of the harmonic alone, without its coupling to the others (-Re J(s, s))",
        )?;
        // The map itself: J on every class's basis (zero across classes).
        g.coord_i64("source", &idx, "1", "perturbed harmonic the response is to (as harmonic)", false)?;
        let total = rows.len();
        let (mut re, mut im) = (Array2::<f64>::zeros((total, total)), Array2::<f64>::zeros((total, total)));
        let mut offset = 0;
        for (class, j) in s.classes.iter().zip(&s.matrices) {
            let m = class.basis.len();
            for r in 0..m {
                for c in 0..m {
                    re[[offset + r, offset + c]] = j[r * m + c].re;
                    im[[offset + r, offset + c]] = j[r * m + c].im;
                }
            }
            offset += m;
        }
        for (name, part, a) in [("jacobian_real", "real", &re), ("jacobian_imag", "imaginary", &im)] {
            g.var_f64(
                name,
                &["harmonic", "source"],
                a.view().into_dyn(),
                "1",
                &format!(
                    "{part} part of the linearised wear map J per wheel passage: the complex amplitude of the \
                     contact-filtered wear at the harmonic per unit complex amplitude of the profile at the source"
                ),
            )?;
        }
        // Each mode's eigenvector and dual on the harmonics (zero off its
        // class): the pattern, and the mode's amplitude in any roughness
        // (sum over the harmonics of dual times the roughness's complex
        // amplitude).
        let offsets: Vec<usize> = s
            .classes
            .iter()
            .scan(0, |o, c| {
                let start = *o;
                *o += c.basis.len();
                Some(start)
            })
            .collect();
        let fill = |f: &dyn Fn(&crate::spectrum::modes::Mode, usize) -> f64| {
            let mut a = Array2::<f64>::zeros((n, total));
            for (k, m) in s.modes.iter().enumerate() {
                for r in 0..m.vector.len() {
                    a[[k, offsets[m.class] + r]] = f(m, r);
                }
            }
            a
        };
        for (name, long, f) in [
            (
                "vector_real",
                "real part of the mode's eigenvector (unit norm)",
                (|m: &crate::spectrum::modes::Mode, r: usize| m.vector[r].re)
                    as fn(&crate::spectrum::modes::Mode, usize) -> f64,
            ),
            ("vector_imag", "imaginary part of the mode's eigenvector", |m, r| m.vector[r].im),
            (
                "dual_real",
                "real part of the mode's dual vector (its amplitude in a roughness R: sum dual R)",
                |m, r| m.dual[r].re,
            ),
            ("dual_imag", "imaginary part of the mode's dual vector", |m, r| m.dual[r].im),
        ] {
            g.var_f64(name, &["mode", "harmonic"], fill(&f).view().into_dyn(), "1", long)?;
        }
        g.var_f64(
            "diagonal_drift",
            &["harmonic"],
            col(&|r| r.5).view().into_dyn(),
            "m/1e5 passages",
            "drift of the harmonic alone (Im J(s, s) / q)",
        )?;
        for f in forecasts {
            write_forecast(root, f)?;
        }
        Ok(())
    })
}

/// A perturbed harmonic's row: wavelength (m), signed wavenumber (1/m),
/// class, rail, its rate alone (dB per 1e5 wheel passages) and drift alone
/// (m per 1e5 wheel passages).
type HarmonicRow = (f64, f64, i64, i64, f64, f64);
