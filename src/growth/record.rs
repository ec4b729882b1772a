//! A measured roughness record as the rail's initial profile: the EN 15610
//! pre-processing steps a user asks for, a window of the stretch's length,
//! and its periodic, band-limited resampling onto the rail grid.
//!
//! * Spike removal (EN 15610 sec. 7, which leaves the detection rule open;
//!   Schwitzer et al., Proc. IMechE F 237 (2023), doi 10.1177/09544097221086487,
//!   compare implementations): sample i is part of a spike or pit where its
//!   second difference `c_i = h_{i-1} - 2 h_i + h_{i+1}` departs from the
//!   record's median second difference by more than `k` robust standard
//!   deviations (`sigma = 1.4826 MAD(c)`); each run of such samples is
//!   replaced by the straight line between its kept neighbours.
//! * Curvature processing (EN 15610 sec. 7.3): the height of the lowest
//!   point of a rigid wheel of radius `R` resting on the record above each
//!   sample, `y_i = max_j [h_j - (R - sqrt(R^2 - (x_j - x_i)^2))]`: dips
//!   narrower than the wheel can enter are bridged, crests kept.
//! * Detrending: the least-squares straight line through the window is
//!   removed.
//! * Resampling: the window's `M` samples, `L / M` apart on the periodic
//!   stretch of length `L`, are one period of a trigonometric polynomial;
//!   its harmonics `n` with `L/n` in `[wavelength_min, wavelength_max]`
//!   (and below the record's Nyquist number `M/2`) are the profile,
//!   `h(X) = sum_n A_n sin(2 pi n (X - x_min) / L + phi_n)`, exact at the
//!   rail nodes for a record that holds only those harmonics. The mean
//!   (n = 0) is dropped, as for every other roughness kind.

pub use crate::params::record::{MeasuredRoughness, Processing, RecordReport, RecordSamples, Spike};

use crate::levels::density::RoughnessDensity;
use crate::params::ProfileHarmonic;
use std::f64::consts::PI;

/// Removes spikes and pits from `h` (see the module doc); returns them.
pub fn remove_spikes(h: &mut [f64], threshold: f64) -> Vec<Spike> {
    let n = h.len();
    if n < 3 {
        return Vec::new();
    }
    let c: Vec<f64> = (1..n - 1).map(|i| h[i - 1] - 2.0 * h[i] + h[i + 1]).collect();
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let centre = median(&mut c.clone());
    let sigma = 1.4826 * median(&mut c.iter().map(|x| (x - centre).abs()).collect());
    let scale = h.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let limit = threshold * sigma.max(64.0 * f64::EPSILON * scale);
    let flagged: Vec<bool> = (0..n).map(|i| i > 0 && i < n - 1 && (c[i - 1] - centre).abs() > limit).collect();
    let mut spikes = Vec::new();
    let mut i = 1;
    while i < n - 1 {
        if !flagged[i] {
            i += 1;
            continue;
        }
        let a = i;
        while i < n - 1 && flagged[i] {
            i += 1;
        }
        let b = i - 1;
        // Replace a..=b by the line from h[a-1] to h[b+1].
        let (h0, h1) = (h[a - 1], h[b + 1]);
        let span = (b + 2 - a) as f64;
        let mut worst = (a, 0.0f64);
        for (k, v) in h.iter_mut().enumerate().take(b + 1).skip(a) {
            let line = h0 + (h1 - h0) * (k + 1 - a) as f64 / span;
            if (*v - line).abs() > worst.1.abs() {
                worst = (k, *v - line);
            }
            *v = line;
        }
        spikes.push(Spike { index: worst.0, width: b + 1 - a, height: worst.1 });
    }
    spikes
}

/// Curvature processing of `h` (samples `spacing` apart) with a wheel of
/// radius `radius` (see the module doc).
pub fn curvature_process(h: &[f64], spacing: f64, radius: f64) -> Vec<f64> {
    let n = h.len();
    let (lo, hi) = h.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), x| (l.min(*x), u.max(*x)));
    // Beyond this reach the wheel's sag exceeds the record's whole range.
    let reach = (2.0 * radius * (hi - lo)).sqrt().min(radius);
    let w = ((reach / spacing).ceil() as usize + 1).min(n);
    let sag: Vec<f64> = (0..=w)
        .map(|k| {
            let u = k as f64 * spacing;
            if u >= radius { f64::INFINITY } else { radius - (radius * radius - u * u).sqrt() }
        })
        .collect();
    (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(w), (i + w).min(n - 1));
            (a..=b).map(|j| h[j] - sag[i.abs_diff(j)]).fold(f64::NEG_INFINITY, f64::max)
        })
        .collect()
}

/// Removes the least-squares line through `h` (samples `spacing` apart);
/// returns its slope (1).
pub fn detrend(h: &mut [f64], spacing: f64) -> f64 {
    let n = h.len() as f64;
    let mean_k = (n - 1.0) / 2.0;
    let mean_h = h.iter().sum::<f64>() / n;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (k, v) in h.iter().enumerate() {
        let dk = k as f64 - mean_k;
        sxy += dk * (v - mean_h);
        sxx += dk * dk;
    }
    let b = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    for (k, v) in h.iter_mut().enumerate() {
        *v -= mean_h + b * (k as f64 - mean_k);
    }
    b / spacing
}

/// The harmonics of one period `h` (M samples) of the stretch of length
/// `length` starting at `x_min`, with wavelength in `[lo, hi]` (see the
/// module doc). A direct DFT (deterministic on every machine).
pub fn window_harmonics(h: &[f64], length: f64, x_min: f64, lo: f64, hi: f64) -> Vec<ProfileHarmonic> {
    let m = h.len();
    let mut out = Vec::new();
    for n in 1..m.div_ceil(2) {
        let wavelength = length / n as f64;
        if wavelength < lo * (1.0 - 1e-9) || wavelength > hi * (1.0 + 1e-9) {
            continue;
        }
        let (mut a, mut b) = (0.0, 0.0);
        for (k, v) in h.iter().enumerate() {
            let angle = 2.0 * PI * ((n * k) % m) as f64 / m as f64;
            a += v * angle.cos();
            b += v * angle.sin();
        }
        let (a, b) = (2.0 * a / m as f64, 2.0 * b / m as f64);
        let amplitude = a.hypot(b);
        if amplitude == 0.0 {
            continue;
        }
        let shift = 2.0 * PI * (n as f64 * x_min / length).fract();
        out.push(ProfileHarmonic { amplitude, wavelength, phase: a.atan2(b) - shift });
    }
    out
}

/// A record spacing (m) from which a file read in metres is taken to be
/// likely in millimetres (10 mm: trolley records sample at 1-2 mm).
const MM_READ_AS_M: f64 = 0.01;

/// The whole record processed as the study's window is (spikes,
/// curvature, and the detrend over the whole record rather than the
/// window): the heights its band levels are taken from (EN 15610; book:
/// docs/src/guide/when-to-grind.md).
pub fn processed_record(samples: &RecordSamples, p: &Processing) -> Vec<f64> {
    let d = samples.spacing();
    let mut h = samples.heights.clone();
    if let Some(k) = p.spike_threshold {
        remove_spikes(&mut h, k);
    }
    if let Some(r) = p.curvature_radius {
        h = curvature_process(&h, d, r);
    }
    if p.detrend {
        detrend(&mut h, d);
    }
    h
}

/// A measured record's roughness density from its whole processed record
/// ([`processed_record`]), its wavelengths from `roughness.wavelength_min`
/// to the record's length (the stretch bounds the study's wavelengths, not
/// the record's), and the record's length (m).
pub fn record_density(m: &MeasuredRoughness) -> (RoughnessDensity, f64) {
    let h = processed_record(&m.samples, &m.processing);
    let d = m.samples.spacing();
    let length = h.len() as f64 * d;
    (RoughnessDensity::from_record(&h, d, m.processing.wavelength_min, length), length)
}

/// The rail's initial irregularity from `samples` on the periodic stretch
/// `[x_min, x_min + length)`. Errors: (the config key to name, message).
pub fn measured_roughness(
    samples: RecordSamples,
    p: Processing,
    x_min: f64,
    length: f64,
) -> Result<MeasuredRoughness, (&'static str, String)> {
    let d = samples.spacing();
    let n = samples.positions.len();
    let x0 = samples.positions[0];
    let last = samples.positions[n - 1];
    if 2.0 * d >= p.wavelength_min * (1.0 - 1e-9) {
        // A spacing of centimetres or more in a file read in metres is most
        // likely a record in millimetres (trolleys sample at 1-2 mm).
        let unit_hint = if samples.position_unit == "m" && d >= MM_READ_AS_M {
            format!(
                " (a spacing of {:.0} mm: if the file's positions are in millimetres, set roughness.position_unit = \
                 \"mm\"; they were read as metres)",
                d * 1e3
            )
        } else {
            String::new()
        };
        return Err((
            "roughness.file",
            format!(
                "{}: the record's spacing {:.4} mm resolves wavelengths down to {:.4} mm (two samples a wavelength); \
                 the study needs them down to roughness.wavelength_min = {:.4} mm: the sampling is too coarse. Use a \
                 record sampled finer than {:.4} mm, or a larger roughness.wavelength_min{unit_hint}",
                samples.at(1),
                d * 1e3,
                2.0 * d * 1e3,
                p.wavelength_min * 1e3,
                p.wavelength_min * 1e3 / 2.0
            ),
        ));
    }
    let m_real = length / d;
    let m = m_real.round() as usize;
    if (m_real - m as f64).abs() > 0.01 || m < 4 {
        return Err((
            "roughness.file",
            format!(
                "{}: the stretch rail.x_max - rail.x_min = {length} m is {m_real:.3} record spacings ({d} m): it must \
                 be a whole number of them (e.g. {} m or {} m)",
                samples.file.display(),
                m_real.floor().max(1.0) * d,
                m_real.ceil() * d
            ),
        ));
    }
    let start = p.window_start.unwrap_or(x0);
    let k0 = ((start - x0) / d).round();
    if k0 < 0.0 || k0 as usize >= n {
        return Err((
            "roughness.window_start",
            format!("= {start} m lies outside the record {} ({x0} .. {last} m)", samples.file.display()),
        ));
    }
    let k0 = k0 as usize;
    if k0 + m > n {
        return Err((
            "roughness.file",
            format!(
                "{}: the record is too short for the stretch: from the window's start {} m it holds {} samples \
                 ({:.4} m) to its last line, the stretch rail.x_max - rail.x_min = {length} m needs {m} at its \
                 spacing {d} m{}",
                samples.at(n - 1),
                samples.positions[k0],
                n - k0,
                (n - k0) as f64 * d,
                if k0 > 0 { "; an earlier roughness.window_start may fit" } else { "" }
            ),
        ));
    }
    let mut h = samples.heights.clone();
    let spikes = match p.spike_threshold {
        Some(k) => remove_spikes(&mut h, k),
        None => Vec::new(),
    };
    let filled = p.curvature_radius.map(|r| {
        let y = curvature_process(&h, d, r);
        let deepest = y.iter().zip(&h).map(|(a, b)| a - b).fold(0.0, f64::max);
        let raised = y.iter().zip(&h).filter(|(a, b)| a > b).count();
        h = y;
        (deepest, raised)
    });
    let mut window = h[k0..k0 + m].to_vec();
    let slope = p.detrend.then(|| detrend(&mut window, d));
    let mean = window.iter().sum::<f64>() / m as f64;
    let rms = (window.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / m as f64).sqrt();
    let steps = (window.windows(2).map(|w| (w[1] - w[0]).powi(2)).sum::<f64>() / (m - 1) as f64).sqrt();
    let seam = window[0] - window[m - 1];
    let harmonics = window_harmonics(&window, length, x_min, p.wavelength_min, p.wavelength_max);
    let kept = (harmonics.iter().map(|h| h.amplitude.powi(2) / 2.0).sum::<f64>()).sqrt();
    let report = RecordReport {
        spikes: spikes.iter().map(|s| (samples.positions[s.index], s.height, s.width)).collect(),
        filled,
        slope,
        window: (k0, samples.positions[k0], m),
        windows: n / m,
        seam: (seam, steps),
        rms: (rms, kept),
    };
    Ok(MeasuredRoughness { samples, processing: p, harmonics, report })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sine(n: usize, amplitude: f64, period: f64, phase: f64) -> Vec<f64> {
        (0..n).map(|k| amplitude * (2.0 * PI * k as f64 / period + phase).sin()).collect()
    }

    #[test]
    fn a_spike_and_a_pit_are_removed_and_reported() {
        // A 2 um sine of 40 samples' wavelength, a 30 um spike at 50 and a
        // 20 um pit two samples wide at 120.
        let clean = sine(200, 2e-6, 40.0, 0.3);
        let mut h = clean.clone();
        h[50] += 30e-6;
        h[120] -= 20e-6;
        h[121] -= 20e-6;
        let spikes = remove_spikes(&mut h, 5.0);
        assert_eq!(spikes.len(), 2, "{spikes:?}");
        assert_eq!(spikes[0].index, 50);
        assert!((spikes[0].height - 30e-6).abs() < 1e-6, "{spikes:?}");
        assert!(spikes[1].index == 120 || spikes[1].index == 121);
        assert!((spikes[1].height + 20e-6).abs() < 1.5e-6, "{spikes:?}");
        // The line through the neighbours of a spike on a smooth sine: the
        // sine's curvature over the replaced span, here below 0.2 um.
        let worst = h.iter().zip(&clean).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(worst < 0.2e-6, "{worst}");
        // A clean record loses nothing.
        let mut c = clean.clone();
        assert!(remove_spikes(&mut c, 5.0).is_empty());
        assert_eq!(c, clean);
    }

    #[test]
    fn the_wheel_bridges_a_pit_and_follows_a_gentle_sine() {
        // A pit 10 um deep, one sample wide at 1 mm spacing, under a 0.5 m
        // wheel: the wheel rests on the neighbours, its lowest point
        // R - sqrt(R^2 - d^2) = 1.000001 um below them.
        let (d, r) = (1e-3, 0.5);
        let mut h = vec![0.0; 21];
        h[10] = -10e-6;
        let y = curvature_process(&h, d, r);
        let sag = r - (r * r - d * d).sqrt();
        assert!((y[10] + sag).abs() < 1e-18, "{}", y[10]);
        assert!(y.iter().enumerate().all(|(i, v)| i == 10 || *v == 0.0));
        // A sine whose curvature A k^2 stays below 1/R: 10 um at 100 mm
        // (A k^2 R = 0.02). On the samples the wheel rests on a neighbour
        // instead only where the profile rises by more than the wheel's sag
        // over one sample, a slope above d / (2 R) = 1e-3; this sine's
        // steepest slope is A k = 6.3e-4: it is kept as it is.
        let h = sine(400, 10e-6, 100.0, 0.0);
        let y = curvature_process(&h, d, r);
        assert_eq!(y, h);
        assert_eq!(y[25], h[25], "a crest");
        // 50 um at 10 mm (A k^2 R = 9.9): troughs filled, crests kept.
        let h = sine(100, 50e-6, 10.0, 0.0);
        let y = curvature_process(&h, d, r);
        assert!(y.iter().zip(&h).all(|(a, b)| a >= b));
        assert_eq!(y[52], h[52], "a crest");
        assert!(y[57] - h[57] > 40e-6, "the trough: {} {}", y[57], h[57]);
    }

    #[test]
    fn detrend_removes_a_line() {
        let mut h: Vec<f64> = (0..50).map(|k| 3e-6 + 2e-7 * k as f64).collect();
        let slope = detrend(&mut h, 1e-3);
        assert!((slope - 2e-4).abs() < 1e-15, "{slope}");
        assert!(h.iter().all(|v| v.abs() < 1e-18), "{h:?}");
    }

    #[test]
    fn harmonics_of_a_window_are_exact() {
        // 120 samples over L = 0.12 m: harmonics 3 (40 mm) and 10 (12 mm)
        // and 50 (2.4 mm, filtered out by wavelength_min = 5 mm).
        let (m, length) = (120, 0.12);
        let h: Vec<f64> = (0..m)
            .map(|k| {
                let u = k as f64 / m as f64;
                2e-6 * (2.0 * PI * 3.0 * u + 0.4).sin()
                    + 1e-6 * (2.0 * PI * 10.0 * u - 1.0).sin()
                    + 3e-6 * (2.0 * PI * 50.0 * u).sin()
            })
            .collect();
        let hs = window_harmonics(&h, length, 0.0, 0.005, f64::INFINITY);
        let big: Vec<&ProfileHarmonic> = hs.iter().filter(|h| h.amplitude > 1e-18).collect();
        assert_eq!(big.len(), 2, "{hs:?}");
        assert!((big[0].wavelength - 0.04).abs() < 1e-15 && (big[0].amplitude - 2e-6).abs() < 1e-18);
        assert!((big[0].phase - 0.4).abs() < 1e-12);
        assert!((big[1].wavelength - 0.012).abs() < 1e-15 && (big[1].amplitude - 1e-6).abs() < 1e-18);
        assert!((big[1].phase + 1.0).abs() < 1e-12);
    }
}
