//! What `check` prints of the inputs: the measured record's processing
//! and the config's numbers with their units.

use super::*;

/// What became of a measured record (for `check` and the start of `run`).
pub fn record_lines(m: &MeasuredRoughness) -> Vec<String> {
    let (r, p, s) = (&m.report, &m.processing, &m.samples);
    let n = s.positions.len();
    let um = |v: f64| format!("{:.3} um", v * 1e6);
    let mut out = vec![format!(
        "{}: {n} samples, {:.4} .. {:.4} m at {:.4} mm (file units: position {}, height {}); sha256 {}",
        s.file.display(),
        s.positions[0],
        s.positions[n - 1],
        s.spacing() * 1e3,
        s.position_unit,
        s.height_unit,
        &s.sha256()[..16],
    )];
    let (k0, start, m_samples) = r.window;
    out.push(format!(
        "window {start:.4} .. {:.4} m (samples {} .. {}) onto the stretch; the record holds {} whole window(s){}",
        start + m_samples as f64 * s.spacing(),
        k0 + 1,
        k0 + m_samples,
        r.windows,
        if r.windows > 1 { " (roughness.window_start picks another)" } else { "" }
    ));
    match p.spike_threshold {
        Some(k) if r.spikes.is_empty() => out.push(format!("spikes: none beyond {k} robust standard deviations")),
        Some(k) => {
            let list: Vec<String> =
                r.spikes.iter().take(10).map(|(x, h, w)| format!("{x:.4} m ({}, {w} sample(s))", um(*h))).collect();
            let more = if r.spikes.len() > 10 { format!(", and {} more", r.spikes.len() - 10) } else { String::new() };
            out.push(format!(
                "spikes removed: {} beyond {k} robust standard deviations, at {}{more}",
                r.spikes.len(),
                list.join(", ")
            ));
        }
        None => out.push("spikes: not removed (roughness.remove_spikes = false)".into()),
    }
    match (p.curvature_radius, r.filled) {
        (Some(radius), Some((deepest, raised))) => out.push(format!(
            "curvature processing with a {radius} m wheel: {raised} sample(s) raised, the deepest by {}",
            um(deepest)
        )),
        _ => out.push("curvature processing: off (roughness.curvature_processing = false)".into()),
    }
    if let Some(slope) = r.slope {
        out.push(format!("detrended: slope {slope:.3e} removed"));
    }
    let (seam, steps) = r.seam;
    out.push(format!(
        "periodic seam: the last sample joins the first with a step of {} (rms step between neighbours {}{})",
        um(seam),
        um(steps),
        if seam.abs() > 3.0 * steps {
            "; a step this large adds a 1/n tail to the spectrum: roughness.detrend or another window helps"
        } else {
            ""
        }
    ));
    out.push(format!(
        "profile: {} harmonics, wavelengths {:.2} .. {:.1} mm; rms {} of the window, {} kept",
        m.harmonics.len(),
        p.wavelength_min * 1e3,
        p.wavelength_max.min(f64::MAX) * 1e3,
        um(r.rms.0),
        um(r.rms.1)
    ));
    out.extend(leaks(m));
    out
}

/// Bands the stretch's window holds more than 3 dB off the whole record's
/// level (a wave that is not a harmonic of the stretch spreads onto its
/// neighbours), among the record's bands within 20 dB of its strongest.
fn leaks(m: &MeasuredRoughness) -> Option<String> {
    use corrugation::levels::{BandSet, all_bands, level};
    let (record, length) = corrugation::growth::record::record_density(m);
    let stretch = m.report.window.2 as f64 * m.samples.spacing();
    let bands: Vec<_> = all_bands(BandSet::ThirdOctave)
        .into_iter()
        .filter(|b| b.lower >= m.processing.wavelength_min && b.upper <= stretch && b.wavelength <= length / 4.0)
        .collect();
    let own: Vec<f64> = bands.iter().map(|b| level(record.between_wavelengths(b.lower, b.upper))).collect();
    let held: Vec<f64> = bands
        .iter()
        .map(|b| {
            level(m.harmonics.iter().filter(|h| b.contains(h.wavelength)).map(|h| h.amplitude.powi(2) / 2.0).sum())
        })
        .collect();
    let strongest = own.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let off: Vec<String> = (0..bands.len())
        .filter(|&k| own[k] >= strongest - 20.0 && (held[k] - own[k]).abs() > 3.0)
        .map(|k| {
            let on = if held[k] <= corrugation::levels::LEVEL_FLOOR {
                "no harmonic on the stretch".to_string()
            } else {
                format!("{:.1} dB on the stretch", held[k])
            };
            format!("{} {:.1} dB in the record, {on}", bands[k].label(), own[k])
        })
        .collect();
    (!off.is_empty()).then(|| {
        format!(
            "the stretch misrepresents the record's bands: {} (a wave that is not a harmonic of the {} mm stretch \
             spreads onto its neighbours; `corrugation spectrum` forecasts from the whole record)",
            off.join("; "),
            stretch * 1e3
        )
    })
}

/// Every physical input of the resolved config in SI and, where an
/// engineer writes it otherwise, in engineering units.
pub(super) fn print_inputs(toml: &str) {
    let Ok(t) = toml.parse::<toml::Table>() else { return };
    let mut rows = Vec::new();
    collect_inputs(&t, "", &mut rows);
    println!("inputs             (SI, as the run uses them; engineering units beside)");
    for (key, v, unit) in rows {
        let eng = engineering(v, unit).map(|e| format!("  = {e}")).unwrap_or_default();
        let unit = if unit == "1" { "" } else { unit };
        let si = if v != 0.0 && !(1e-3..1e5).contains(&v.abs()) { format!("{v:e}") } else { format!("{v}") };
        println!("  {key:<38} {si:>18} {unit}{eng}");
    }
}

fn collect_inputs(t: &toml::Table, prefix: &str, out: &mut Vec<(String, f64, &'static str)>) {
    for (k, v) in t {
        let key = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
        match v {
            toml::Value::Table(t) => collect_inputs(t, &key, out),
            toml::Value::Array(a) => {
                for (i, item) in a.iter().enumerate() {
                    match item {
                        toml::Value::Table(t) => collect_inputs(t, &format!("{key}[{i}]"), out),
                        other => {
                            if let (Some(x), Some(u)) = (number(other), key_units(&key)) {
                                out.push((format!("{key}[{i}]"), x, u));
                            }
                        }
                    }
                }
            }
            other => {
                if let (Some(x), Some(u)) = (number(other), key_units(&key)) {
                    out.push((key, x, u));
                }
            }
        }
    }
}

fn number(v: &toml::Value) -> Option<f64> {
    v.as_float().or(v.as_integer().map(|i| i as f64))
}
