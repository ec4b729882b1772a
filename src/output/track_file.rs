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
//!
//! With the dynamics in every direction (`dynamics.directions = "all"`) the
//! rail head's receptances in three directions too, on the coordinates
//! `response` and `force` (`x` along the rail, `y` across to the right,
//! `z` down; the contact `contact_offset` m right of the centre line, an
//! attribute): `head_receptance_real(position, frequency, response,
//! force)` and `_imag` (discrete track), `continuous_head_receptance_real
//! (frequency, response, force)` and `_imag`, and with several wheels
//! `head_transfer_real(source, distance, frequency, response, force)`,
//! `continuous_head_transfer_real(distance, frequency, response, force)`
//! and their `_imag`; beside each, the head's rotation about `z`:
//! `<name>_rotation_real(..., force)` (rad/N per force in `x`, `y`, `z`; by
//! reciprocity the displacement per moment about `z`) and
//! `<name>_rotation_per_moment_real(...)` (rad/(N m)), and their `_imag`.
//!
//! On a track layout of several supports per period (`[track]`'s layout
//! keys), group `layout` (attribute `period`, m) with dimensions
//! `frequency` (Hz), `support` (m from the period's start) and `place` (m:
//! each support, then the mid-span after it): `pad_stiffness(support)`
//! (N/m), `pad_loss_factor(support)` (1; where the pads are damped by a
//! loss factor), `sleeper_mass(support)` (kg), `ballast_stiffness(support)`
//! (N/m), each span's `span_frequency`,
//! `pinned_pinned_frequency` (Hz) and `pinned_pinned_receptance` (m/N) on
//! `support` (the span after it), the vertical `receptance_real(place,
//! frequency)` and `_imag`, and with the head in three directions
//! `head_receptance_real(place, frequency, response, force)` and `_imag`.

use super::netcdf::{NcError, write_atomically};
use crate::dynamics::track::Damping;
use crate::dynamics::track::head::HeadResponse;
use crate::dynamics::track::response::{LayoutResponse, TrackResponse};
use crate::dynamics::track::section::Mat4;
use ndarray::{Array0, Array1, Array2, Array3, ArrayD, Dimension, IxDyn};
use std::path::Path;

/// Writes `r` (and the head's receptances in three directions `head`, if
/// given, on the same frequencies, positions, sources and distances; the
/// layout's `layout`, if given, on the same frequencies) for the track
/// named `rail` and the resolved `config` to `path` atomically.
pub fn write_track_file(
    path: &Path,
    r: &TrackResponse,
    head: Option<&HeadResponse>,
    layout: Option<&LayoutResponse>,
    rail: &str,
    config: &str,
) -> Result<(), NcError> {
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
        if let Some(h) = head {
            write_head(&g, r, h)?;
        }
        if let Some(l) = layout {
            write_layout(&root.group("layout")?, &r.frequency, l)?;
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

/// The layout's group (see the module's doc).
fn write_layout(g: &super::netcdf::NcGroup, frequency: &[f64], l: &LayoutResponse) -> Result<(), NcError> {
    let supports = &l.layout.supports;
    g.attr_f64("period", l.layout.period)?;
    g.coord_f64("frequency", frequency, "Hz", "frequency", false)?;
    let x: Vec<f64> = supports.iter().map(|s| s.x).collect();
    g.coord_f64("support", &x, "m", "support position from the period's start", false)?;
    let column = |v: Vec<f64>| Array1::from(v);
    let mut values: Vec<(&str, Vec<f64>, &str, &str)> = vec![
        ("pad_stiffness", supports.iter().map(|s| s.pad_stiffness).collect(), "N/m", "the support's pad stiffness"),
        (
            "sleeper_mass",
            supports.iter().map(|s| s.sleeper_mass).collect(),
            "kg",
            "the support's sleeper mass per rail",
        ),
        (
            "ballast_stiffness",
            supports.iter().map(|s| s.ballast_stiffness).collect(),
            "N/m",
            "the ballast's stiffness under the support's sleeper end",
        ),
    ];
    let loss: Option<Vec<f64>> = supports
        .iter()
        .map(|s| match s.pad_damping {
            Damping::LossFactor(eta) => Some(eta),
            Damping::Viscous(_) => None,
        })
        .collect();
    if let Some(loss) = loss {
        values.push(("pad_loss_factor", loss, "1", "the support's pad loss factor"));
    }
    for (name, v, units, long) in values {
        g.var_f64(name, &["support"], column(v).view().into_dyn(), units, long)?;
    }
    for (name, k, units, long) in [
        ("span_frequency", 0, "Hz", "first bending frequency of the span after the support, simply supported"),
        ("pinned_pinned_frequency", 1, "Hz", "peak of the span's mid-span receptance within a factor 1.5 of it"),
        ("pinned_pinned_receptance", 2, "m/N", "magnitude of the span's mid-span receptance at its pinned-pinned peak"),
    ] {
        let v = column(l.pinned_pinned.iter().map(|p| [p.0, p.1, p.2][k]).collect());
        g.var_f64(name, &["support"], v.view().into_dyn(), units, long)?;
    }
    g.coord_f64(
        "place",
        &l.place,
        "m",
        "place from the period's start: each support, then the mid-span after it",
        false,
    )?;
    let dims = ["place", "frequency"];
    let long = "vertical rail point receptance on the layout (exp(+i w t); Im <= 0)";
    for (suffix, part, re) in [("real", "real", true), ("imag", "imaginary", false)] {
        let a =
            Array2::from_shape_fn(
                (l.place.len(), frequency.len()),
                |(p, k)| {
                    if re { l.rail[p][k].re } else { l.rail[p][k].im }
                },
            );
        g.var_f64(
            &format!("receptance_{suffix}"),
            &dims,
            a.view().into_dyn(),
            "m/N",
            &format!("{part} part of the {long}"),
        )?;
    }
    if let Some(head) = &l.head {
        let axes: Vec<String> = ["x", "y", "z"].iter().map(|s| s.to_string()).collect();
        g.coord_str("response", &axes, "", "direction of the head's displacement: x along the rail, y across, z down")?;
        g.coord_str("force", &axes, "", "direction of the force on the head")?;
        let long = "rail head point receptance in three directions on the layout (exp(+i w t))";
        for (suffix, part, re) in [("real", "real", true), ("imag", "imaginary", false)] {
            let a = ArrayD::from_shape_fn(IxDyn(&[l.place.len(), frequency.len(), 3, 3]), |ix: IxDyn| {
                let v = head[ix[0]][ix[1]][(ix[2], ix[3])];
                if re { v.re } else { v.im }
            });
            g.var_f64(
                &format!("head_receptance_{suffix}"),
                &["place", "frequency", "response", "force"],
                a.view(),
                "m/N",
                &format!("{part} part of the {long}"),
            )?;
        }
    }
    Ok(())
}

/// The head's receptances in three directions (see the module's doc).
fn write_head(g: &super::netcdf::NcGroup, r: &TrackResponse, h: &HeadResponse) -> Result<(), NcError> {
    let axes: Vec<String> = ["x", "y", "z"].iter().map(|s| s.to_string()).collect();
    let along = "x along the rail (travel), y across to the right, z down";
    g.coord_str("response", &axes, "", &format!("direction of the head's displacement: {along}"))?;
    g.coord_str("force", &axes, "", &format!("direction of the force on the head: {along}"))?;
    g.attr_f64("contact_offset", h.contact_offset)?;
    // (outer indices..., frequency) -> the 4 x 4 matrices: the 3 x 3
    // translations (m/N), the rotation about z per force (rad/N; by
    // reciprocity the displacement per moment) and per moment (rad/(N m)).
    let write = |name: &str, dims: &[&str], shape: &[usize], at: &dyn Fn(&[usize]) -> Mat4, long: &str| {
        // (name's tail, inner dimensions, first entry, units, what).
        type Part<'a> = (&'a str, &'a [&'a str], [usize; 2], &'a str, &'a str);
        let parts: [Part; 3] = [
            ("", &["response", "force"], [0, 0], "m/N", ""),
            (
                "_rotation",
                &["force"],
                [3, 0],
                "rad/N",
                ": the head's rotation about z per force (by reciprocity its displacement per moment about z, m/(N m))",
            ),
            ("_rotation_per_moment", &[], [3, 3], "rad/(N m)", ": the head's rotation about z per moment about z"),
        ];
        for (tail, inner, [r0, c0], units, what) in parts {
            let mut full = shape.to_vec();
            full.extend(std::iter::repeat_n(3, inner.len()));
            for (suffix, part, re) in [("real", "real", true), ("imag", "imaginary", false)] {
                let a = ArrayD::from_shape_fn(IxDyn(&full), |ix: IxDyn| {
                    let ix: Vec<usize> = (0..ix.ndim()).map(|k| ix[k]).collect();
                    let (outer, rest) = ix.split_at(shape.len());
                    let (r, c) = match rest {
                        [r, c] => (r0 + r, c0 + c),
                        [c] => (r0, c0 + c),
                        _ => (r0, c0),
                    };
                    let v = at(outer)[(r, c)];
                    if re { v.re } else { v.im }
                });
                let mut all: Vec<&str> = dims.to_vec();
                all.extend(inner);
                g.var_f64(
                    &format!("{name}{tail}_{suffix}"),
                    &all,
                    a.view(),
                    units,
                    &format!("{part} part of the {long}{what}"),
                )?;
            }
        }
        Ok::<(), NcError>(())
    };
    let (np, nf) = (r.position.len(), r.frequency.len());
    write(
        "head_receptance",
        &["position", "frequency"],
        &[np, nf],
        &|i| h.discrete[i[0]][i[1]],
        "rail head's point receptance in three directions on discrete supports (exp(+i w t))",
    )?;
    write(
        "continuous_head_receptance",
        &["frequency"],
        &[nf],
        &|i| h.continuous[i[0]],
        "rail head's point receptance in three directions on continuous supports",
    )?;
    if !h.transfer.is_empty() {
        let nd = r.distance.len();
        write(
            "head_transfer",
            &["source", "distance", "frequency"],
            &[r.source.len(), nd, nf],
            &|i| h.transfer[i[0]][i[1]][i[2]],
            "rail head's transfer receptance in three directions on discrete supports: displacement at the distance \
             ahead of a unit force at the source",
        )?;
        write(
            "continuous_head_transfer",
            &["distance", "frequency"],
            &[nd, nf],
            &|i| h.continuous_transfer[i[0]][i[1]],
            "rail head's transfer receptance in three directions on continuous supports",
        )?;
    }
    Ok(())
}
