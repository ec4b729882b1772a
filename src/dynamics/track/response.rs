//! The receptances of a configured track and wheel over a frequency sweep
//! (what `corrugation track` writes): the rail point receptance of the
//! discrete model at positions across a sleeper bay, the continuous
//! model's, the wheel's and the contact spring's, the resonances, and the
//! transfer receptances between the wheels of a vehicle; on a layout of
//! several supports per period, the receptances at every support and
//! mid-span and each span's pinned-pinned peak.

use super::TrackConfig;
use super::discrete::DiscreteTrack;
use super::discrete3::{Discrete3, Discrete3Error, layout_at};
use super::layout::Layout;
use super::section::Mat4;
use crate::dynamics::receptance::{TrackParams, WheelParams};
use num_complex::Complex64;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Lowest frequency of the sweep (Hz).
pub const SWEEP_FROM: f64 = 20.0;
/// Highest frequency of the sweep (Hz).
pub const SWEEP_TO: f64 = 5000.0;
/// Log-spaced frequencies of the sweep by default (a ratio of 1.023
/// between neighbours; `corrugation track --points`).
pub const SWEEP_POINTS: usize = 241;

/// The track's response.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackResponse {
    /// Frequencies (Hz).
    pub frequency: Vec<f64>,
    /// Positions from a sleeper (m): 0 (above it) to d/2 (mid-span).
    pub position: Vec<f64>,
    /// Rail point receptance of the discrete model (m/N), (position, frequency).
    pub rail: Vec<Vec<Complex64>>,
    /// Rail point receptance of the continuous model (m/N), (frequency).
    pub continuous: Vec<Complex64>,
    /// Places of the force for the transfer receptances (m from a sleeper):
    /// above it and mid-span.
    pub source: Vec<f64>,
    /// Distances between wheels (m), increasing (empty for one wheel).
    pub distance: Vec<f64>,
    /// The discrete model's rail displacement at each distance ahead of a
    /// unit force at each source (m/N), (source, distance, frequency).
    pub transfer: Vec<Vec<Vec<Complex64>>>,
    /// The continuous model's (m/N), (distance, frequency).
    pub continuous_transfer: Vec<Vec<Complex64>>,
    /// Wheel receptance `-1 / (M w^2)` (m/N), (frequency).
    pub wheel: Vec<f64>,
    /// Contact receptance `1 / k_H` (m/N).
    pub contact: f64,
    /// The simply supported span's first bending frequency (Hz).
    pub span_frequency: f64,
    /// The pinned-pinned resonance: the peak of the mid-span receptance
    /// within a factor 1.5 of the span frequency (Hz).
    pub pinned_pinned: f64,
    /// The rail-on-pad resonance with the sleepers blocked,
    /// `sqrt(k_p / (m_r d)) / 2 pi` (Hz).
    pub rail_on_pad: f64,
    /// The whole track bouncing on the ballast: the peak of the continuous
    /// model's receptance below 300 Hz (Hz).
    pub track_on_ballast: f64,
}

/// The response of `track` with `wheel` on a contact spring
/// `contact_stiffness` (N/m), and the transfer receptances at `distances`
/// (m) between wheels, at `points` frequencies log-spaced over
/// [`SWEEP_FROM`]-[`SWEEP_TO`].
pub fn track_response(
    track: &TrackConfig,
    wheel: WheelParams,
    contact_stiffness: f64,
    distances: &[f64],
    points: usize,
) -> TrackResponse {
    let discrete = DiscreteTrack::new(track);
    let continuous: TrackParams = track.smeared();
    let frequency: Vec<f64> =
        (0..points).map(|k| SWEEP_FROM * (SWEEP_TO / SWEEP_FROM).powf(k as f64 / (points - 1) as f64)).collect();
    let d = track.sleeper_spacing;
    let position: Vec<f64> = (0..=4).map(|k| d * k as f64 / 8.0).collect();
    let by_frequency: Vec<Vec<Complex64>> =
        frequency.par_iter().map(|f| discrete.receptances(&position, 2.0 * PI * f)).collect();
    let rail = by_place(&by_frequency);
    let cont: Vec<Complex64> = frequency.iter().map(|f| continuous.rail_receptance(2.0 * PI * f)).collect();
    let source = vec![0.0, 0.5 * d];
    // [frequency][source][distance], turned into [source][distance][frequency].
    let by_frequency_transfer: Vec<Vec<Vec<Complex64>>> = frequency
        .par_iter()
        .map(|f| source.iter().map(|&x0| discrete.transfer_receptances(x0, distances, 2.0 * PI * f)).collect())
        .collect();
    let transfer: Vec<Vec<Vec<Complex64>>> = if distances.is_empty() {
        Vec::new()
    } else {
        (0..source.len())
            .map(|s| {
                (0..distances.len()).map(|l| by_frequency_transfer.iter().map(|row| row[s][l]).collect()).collect()
            })
            .collect()
    };
    let continuous_transfer: Vec<Vec<Complex64>> = distances
        .iter()
        .map(|&l| frequency.iter().map(|f| continuous.rail_transfer_receptance(2.0 * PI * f, l)).collect())
        .collect();
    let wheel_r: Vec<f64> = frequency.iter().map(|f| -1.0 / (wheel.unsprung_mass * (2.0 * PI * f).powi(2))).collect();
    let span = discrete.pinned_pinned_frequency();
    let peak = |values: &[Complex64], lo: f64, hi: f64| {
        frequency
            .iter()
            .zip(values)
            .filter(|(f, _)| (lo..=hi).contains(*f))
            .max_by(|a, b| a.1.norm().total_cmp(&b.1.norm()))
            .map_or(f64::NAN, |(f, _)| *f)
    };
    let pinned_pinned = peak(&rail[rail.len() - 1], span / 1.5, span * 1.5);
    let rail_on_pad = (continuous.pad_stiffness / continuous.rail_mass).sqrt() / (2.0 * PI);
    let track_on_ballast = peak(&cont, SWEEP_FROM, 300.0);
    TrackResponse {
        frequency,
        position,
        rail,
        continuous: cont,
        source,
        distance: distances.to_vec(),
        transfer,
        continuous_transfer,
        wheel: wheel_r,
        contact: 1.0 / contact_stiffness,
        span_frequency: span,
        pinned_pinned,
        rail_on_pad,
        track_on_ballast,
    }
}

/// Rows by frequency, each of values by place, turned into rows by place.
fn by_place<T: Copy>(by_frequency: &[Vec<T>]) -> Vec<Vec<T>> {
    let places = by_frequency.first().map_or(0, Vec::len);
    (0..places).map(|p| by_frequency.iter().map(|row| row[p]).collect()).collect()
}

/// The track's response on a layout of several supports per period
/// (`corrugation track` with the layout's keys): at every support and
/// every mid-span.
#[derive(Debug, Clone, PartialEq)]
pub struct LayoutResponse {
    /// The layout.
    pub layout: Layout,
    /// The places (m from the period's start): support `m` at `2 m`, the
    /// mid-span after it at `2 m + 1`.
    pub place: Vec<f64>,
    /// The vertical rail point receptance (m/N), (place, frequency).
    pub rail: Vec<Vec<Complex64>>,
    /// The rail head's point receptances in every direction (m/N; the
    /// translations, padded to 4 x 4), (place, frequency), where asked.
    pub head: Option<Vec<Vec<Mat4>>>,
    /// Per span (after each support): its simply supported bending
    /// frequency (Hz), and the frequency (Hz) and magnitude (m/N) of its
    /// mid-span receptance's largest local peak within a factor 1.5 of it
    /// (the pinned-pinned peak; `NaN` where the sweep holds none).
    pub pinned_pinned: Vec<(f64, f64, f64)>,
}

/// The response of `track` laid out by `layout` at `frequency` (Hz), the
/// head's in every direction with the contact `head_offset` (m) right of
/// the centre line where given.
///
/// # Errors
/// Where the semi-infinite track does not converge (an undamped track).
pub fn layout_response(
    track: &TrackConfig,
    layout: &Layout,
    frequency: &[f64],
    head_offset: Option<f64>,
) -> Result<LayoutResponse, Discrete3Error> {
    let vertical = DiscreteTrack::new(track);
    let bounds = layout.bounds();
    let place: Vec<f64> = bounds.windows(2).flat_map(|w| [w[0], 0.5 * (w[0] + w[1])]).collect();
    let pairs: Vec<(f64, f64)> = place.iter().map(|&x| (x, x)).collect();
    let by_frequency: Vec<Vec<Complex64>> = frequency
        .par_iter()
        .map(|f| {
            let omega = 2.0 * PI * f;
            vertical.layout_receptances(layout, &pairs, omega).map_err(layout_at(omega))
        })
        .collect::<Result<_, _>>()?;
    let rail = by_place(&by_frequency);
    let head = match head_offset {
        Some(offset) => {
            let head = Discrete3::new(track, offset);
            let by_frequency: Vec<Vec<Mat4>> = frequency
                .par_iter()
                .map(|f| head.layout_heads(layout, &pairs, 2.0 * PI * f, false))
                .collect::<Result<_, _>>()?;
            Some(by_place(&by_frequency))
        }
        None => None,
    };
    let pinned_pinned = bounds
        .windows(2)
        .enumerate()
        .map(|(m, w)| {
            let span = DiscreteTrack { spacing: w[1] - w[0], ..vertical }.pinned_pinned_frequency();
            let a: Vec<f64> = rail[2 * m + 1].iter().map(|v| v.norm()).collect();
            let (f, a) = (1..a.len().saturating_sub(1))
                .filter(|&k| (span / 1.5..=span * 1.5).contains(&frequency[k]) && a[k] >= a[k - 1] && a[k] >= a[k + 1])
                .map(|k| (frequency[k], a[k]))
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap_or((f64::NAN, f64::NAN));
            (span, f, a)
        })
        .collect();
    Ok(LayoutResponse { layout: layout.clone(), place, rail, head, pinned_pinned })
}
