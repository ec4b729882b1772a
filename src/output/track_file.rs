//! The file `corrugation track` writes: group `track` with dimensions
//! `frequency` (Hz) and `position` (m from a sleeper), the discrete model's
//! rail point receptance `receptance_real(position, frequency)` and
//! `receptance_imag(position, frequency)` (m/N, time dependence
//! exp(+i w t)), the continuous model's and the wheel's on `frequency`, the
//! contact spring's as a scalar, and the resonances as attributes. With
//! several wheels (`[vehicle]`) also the transfer receptances between them:
//! dimensions `source` (m from a sleeper: 0 and d/2) and `distance` (m),
//! `transfer_real(source, distance, frequency)` and `transfer_imag` (the
//! rail's displacement at the distance ahead of a unit force at the
//! source), and the continuous model's `continuous_transfer_real(distance,
//! frequency)` and `continuous_transfer_imag`.

use super::netcdf::{NcError, write_atomically};
use crate::dynamics::track_response::TrackResponse;
use ndarray::{Array0, Array1, Array2, Array3};
use std::path::Path;

/// Writes `r` for the track named `rail` and the resolved `config` to `path`
/// atomically.
pub fn write_track_file(path: &Path, r: &TrackResponse, rail: &str, config: &str) -> Result<(), NcError> {
    write_atomically(path, |root| {
        root.attr_str("title", "track receptances")?;
        root.attr_str("program", "corrugation")?;
        root.attr_str("version", env!("CARGO_PKG_VERSION"))?;
        root.attr_str("config", config)?;
        let g = root.group("track")?;
        g.attr_str("rail", rail)?;
        g.attr_f64("span_frequency_hz", r.span_frequency)?;
        g.attr_f64("pinned_pinned_hz", r.pinned_pinned)?;
        g.attr_f64("rail_on_pad_hz", r.rail_on_pad)?;
        g.attr_f64("track_on_ballast_hz", r.track_on_ballast)?;
        g.coord_f64("frequency", &r.frequency, "Hz", "frequency", false)?;
        g.coord_f64("position", &r.position, "m", "load position from a sleeper (0: above it; d/2: mid-span)", false)?;
        let table = |f: fn(&num_complex::Complex64) -> f64| {
            Array2::from_shape_fn((r.position.len(), r.frequency.len()), |(p, k)| f(&r.rail[p][k]))
        };
        let dims = ["position", "frequency"];
        let long = "rail point receptance of the Timoshenko rail on discrete supports (exp(+i w t); Im <= 0)";
        g.var_f64(
            "receptance_real",
            &dims,
            table(|c| c.re).view().into_dyn(),
            "m/N",
            &format!("real part of the {long}"),
        )?;
        g.var_f64(
            "receptance_imag",
            &dims,
            table(|c| c.im).view().into_dyn(),
            "m/N",
            &format!("imaginary part of the {long}"),
        )?;
        let line = |f: fn(&num_complex::Complex64) -> f64| r.continuous.iter().map(f).collect::<Array1<f64>>();
        let cont = "rail point receptance of the continuously supported Euler-Bernoulli rail (the receptance model)";
        g.var_f64(
            "continuous_receptance_real",
            &["frequency"],
            line(|c| c.re).view().into_dyn(),
            "m/N",
            &format!("real part of the {cont}"),
        )?;
        g.var_f64(
            "continuous_receptance_imag",
            &["frequency"],
            line(|c| c.im).view().into_dyn(),
            "m/N",
            &format!("imaginary part of the {cont}"),
        )?;
        let wheel = Array1::from(r.wheel.clone());
        g.var_f64(
            "wheel_receptance",
            &["frequency"],
            wheel.view().into_dyn(),
            "m/N",
            "wheel receptance -1 / (M w^2) (unsprung mass, free)",
        )?;
        if !r.distance.is_empty() {
            g.coord_f64("source", &r.source, "m", "force position from a sleeper (0: above it; d/2: mid-span)", false)?;
            g.coord_f64("distance", &r.distance, "m", "distance between two wheels of the vehicle", false)?;
            let dims = ["source", "distance", "frequency"];
            let shape = (r.source.len(), r.distance.len(), r.frequency.len());
            let long = "rail transfer receptance of the Timoshenko rail on discrete supports: displacement at the \
                        distance ahead of a unit force at the source (exp(+i w t))";
            for (name, part, f) in [
                ("transfer_real", "real", (|c: &num_complex::Complex64| c.re) as fn(&num_complex::Complex64) -> f64),
                ("transfer_imag", "imaginary", |c| c.im),
            ] {
                let a = Array3::from_shape_fn(shape, |(s, l, k)| f(&r.transfer[s][l][k]));
                g.var_f64(name, &dims, a.view().into_dyn(), "m/N", &format!("{part} part of the {long}"))?;
            }
            let long = "rail transfer receptance of the continuously supported Euler-Bernoulli rail";
            for (name, part, f) in [
                (
                    "continuous_transfer_real",
                    "real",
                    (|c: &num_complex::Complex64| c.re) as fn(&num_complex::Complex64) -> f64,
                ),
                ("continuous_transfer_imag", "imaginary", |c| c.im),
            ] {
                let a = Array2::from_shape_fn((r.distance.len(), r.frequency.len()), |(l, k)| {
                    f(&r.continuous_transfer[l][k])
                });
                g.var_f64(
                    name,
                    &["distance", "frequency"],
                    a.view().into_dyn(),
                    "m/N",
                    &format!("{part} part of the {long}"),
                )?;
            }
        }
        let contact = Array0::from_elem((), r.contact);
        g.var_f64(
            "contact_receptance",
            &[],
            contact.view().into_dyn(),
            "m/N",
            "contact receptance 1 / k_H (Hertz spring at the mean load)",
        )?;
        Ok(())
    })
}
