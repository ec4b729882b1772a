//! The dynamic contact force of a wheel rolling over the discretely
//! supported rail ([`super::track::discrete`]), for the growth loop.
//!
//! A moving-irregularity model with a receptance that depends on where in
//! the sleeper bay the wheel is (the "position-dependent" approximation of
//! the extended linear models; Hempelmann and Knothe 1996 treat the exact
//! coupling of the harmonics `f + n V / d`, which this approximation drops,
//! valid while `V / d` is small against the frequencies of interest):
//!
//! ```text
//! P(X) = sum_n H(f_n, x(X)) r_n exp(i k_n X),
//! H(f, x) = 1 / (alpha_w(f) + alpha_c + alpha_r(x, f)),              (1)
//! ```
//!
//! `x(X)` the wheel's distance from the last sleeper (folded into
//! `[0, d/2]`: the bay is symmetric), `alpha_r` tabulated at
//! [`POSITIONS`] points across the half bay and the profile's harmonics up
//! to [`F_MAX`] and interpolated linearly in `x`. The profile seen includes
//! the **parametric excitation** of the supports: the wheel's own static
//! load `N0` deflects the rail by `alpha_r(x, 0) N0`, more at mid-span than
//! above a sleeper, so on a smooth rail the wheel runs on the path
//! `-alpha_r(x(X), 0) N0` (less its mean): a roughness at `V / d` and its
//! harmonics that the same transfer (1) turns into the sleeper-passing
//! force.

use super::receptance::WheelParams;
use super::track::discrete::DiscreteTrack;
use super::{ContactVariations, TrackDynamics};
use num_complex::Complex64;
use rayon::prelude::*;
use rustfft::FftPlanner;
use std::f64::consts::PI;

/// Points across the half bay at which the receptance is tabulated.
pub const POSITIONS: usize = 9;

/// Highest harmonic frequency of the profile the model transfers (Hz);
/// above it the force harmonics are dropped (the contact filters them far
/// more than the track: 5 kHz is a 5.6 mm wavelength at 100 km/h).
pub const F_MAX: f64 = 5000.0;

/// The harmonics of a stretch of `nodes` samples every `dx` (m) that the
/// model transfers at `speed` (m/s): those up to [`F_MAX`] and the Nyquist
/// harmonic. Tabulating them costs about 1 s per 100 on 2 cores.
pub fn harmonics(nodes: usize, dx: f64, speed: f64) -> usize {
    ((F_MAX * nodes as f64 * dx / speed.abs()).floor() as usize).min(nodes / 2)
}

/// The discrete track and wheel at one speed over one periodic stretch.
#[derive(Debug, Clone)]
pub struct DiscreteDynamics {
    track: DiscreteTrack,
    wheel: WheelParams,
    contact_stiffness: f64,
    /// Mean normal force (N), for the parametric excitation.
    mean_load: f64,
    /// First sleeper's position along the rail (m).
    sleeper_x0: f64,
    /// Speed (m/s) and stretch (nodes, spacing) the table was built for.
    key: (f64, usize, f64),
    /// H(f_n, x_p) for the harmonics n = 1..=n_max (rows) at the positions.
    table: Vec<[Complex64; POSITIONS]>,
}

impl DiscreteDynamics {
    /// The model for a stretch of `nodes` samples every `dx` (m) starting at
    /// a sleeper at `sleeper_x0` (m), at `speed` (m/s): tabulates `H`
    /// (about 1 s per 100 harmonics on 2 cores).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        track: DiscreteTrack,
        wheel: WheelParams,
        contact_stiffness: f64,
        mean_load: f64,
        sleeper_x0: f64,
        nodes: usize,
        dx: f64,
        speed: f64,
    ) -> Self {
        let length = nodes as f64 * dx;
        let n_max = harmonics(nodes, dx, speed);
        let positions: Vec<f64> =
            (0..POSITIONS).map(|p| track.spacing * 0.5 * p as f64 / (POSITIONS - 1) as f64).collect();
        let alpha_c = Complex64::new(1.0 / contact_stiffness, 0.0);
        let table = (1..=n_max)
            .into_par_iter()
            .map(|n| {
                let w = 2.0 * PI * n as f64 * speed.abs() / length;
                let alpha_w = Complex64::new(-1.0 / (wheel.unsprung_mass * w * w), 0.0);
                let mut row = [Complex64::new(0.0, 0.0); POSITIONS];
                for (v, alpha_r) in row.iter_mut().zip(track.receptances(&positions, w)) {
                    *v = 1.0 / (alpha_w + alpha_c + alpha_r);
                }
                row
            })
            .collect();
        DiscreteDynamics { track, wheel, contact_stiffness, mean_load, sleeper_x0, key: (speed, nodes, dx), table }
    }

    /// The wheel's distance from the last sleeper, folded into [0, d/2],
    /// as a fractional index into the tabulated positions.
    fn position_index(&self, x: f64) -> f64 {
        half_bay_index(self.track.spacing, self.sleeper_x0, x)
    }

    /// The path of a wheel on a smooth rail (m, positive up, zero mean):
    /// the static deflection under its own mean load, `-alpha_r(x, 0) N0`
    /// ([`parametric_path`]).
    pub fn parametric_profile(&self, nodes: usize, dx: f64) -> Vec<f64> {
        parametric_path(&self.track, self.mean_load, self.sleeper_x0, nodes, dx)
    }
}

/// The path of a wheel of mean load `mean_load` (N) on a smooth rail of
/// the track `track` (m, positive up, zero mean) at `nodes` samples every
/// `dx` (m) from a sleeper at `sleeper_x0` (m): the static deflection under
/// its own load, `-alpha_r(x, 0) N0`, with the static receptance (0.1 Hz)
/// tabulated at [`POSITIONS`] places over the half bay and interpolated
/// linearly.
pub fn parametric_path(track: &DiscreteTrack, mean_load: f64, sleeper_x0: f64, nodes: usize, dx: f64) -> Vec<f64> {
    let w0 = 2.0 * PI * 0.1;
    let d = track.spacing;
    let places: Vec<f64> = (0..POSITIONS).map(|p| d * 0.5 * p as f64 / (POSITIONS - 1) as f64).collect();
    let statics: Vec<f64> = track.receptances(&places, w0).iter().map(|a| a.re).collect();
    let path: Vec<f64> = (0..nodes)
        .map(|i| {
            let s = half_bay_index(d, sleeper_x0, sleeper_x0 + i as f64 * dx);
            let p = (s.floor() as usize).min(POSITIONS - 2);
            let t = s - p as f64;
            -((1.0 - t) * statics[p] + t * statics[p + 1]) * mean_load
        })
        .collect();
    let mean = path.iter().sum::<f64>() / nodes.max(1) as f64;
    path.iter().map(|v| v - mean).collect()
}

/// The distance of `x` (m) from the last sleeper (sleepers every `d` from
/// `sleeper_x0`), folded into [0, d/2], as a fractional index into the
/// [`POSITIONS`] places over the half bay.
fn half_bay_index(d: f64, sleeper_x0: f64, x: f64) -> f64 {
    let u = (x - sleeper_x0).rem_euclid(d);
    let folded = u.min(d - u);
    folded / (0.5 * d) * (POSITIONS - 1) as f64
}

impl DiscreteDynamics {
    /// The dynamic normal force (N, zero mean) at the profile's sample
    /// points `X_j = j dx` (see [`TrackDynamics::contact_variations`]).
    pub fn force_from_profile(&self, profile: &[f64], dx: f64, speed: f64) -> Vec<f64> {
        let n = profile.len();
        assert_eq!(
            (speed, n, dx),
            self.key,
            "the discrete dynamics is tabulated for one speed and stretch (built with the growth study's)"
        );
        // The profile the wheel runs on: the rail's plus the supports' path.
        let parametric = self.parametric_profile(n, dx);
        let mut buf: Vec<Complex64> =
            profile.iter().zip(&parametric).map(|(r, p)| Complex64::new(r + p, 0.0)).collect();
        FftPlanner::<f64>::new().plan_fft_forward(n).process(&mut buf);
        let length = n as f64 * dx;
        let sign = speed.signum();
        (0..n)
            .map(|i| {
                let x = i as f64 * dx;
                let s = self.position_index(self.sleeper_x0 + x);
                let p = (s.floor() as usize).min(POSITIONS - 2);
                let t = s - p as f64;
                let mut force = 0.0;
                for (m, row) in self.table.iter().enumerate() {
                    let k = m + 1;
                    let h = (1.0 - t) * row[p] + t * row[p + 1];
                    // A real profile: harmonic k and its mirror N - k give
                    // 2 Re[H r_k exp(i k_k x)] / N; the direction of travel
                    // conjugates H (f < 0).
                    let h = if sign >= 0.0 { h } else { h.conj() };
                    let phase = Complex64::from_polar(1.0, 2.0 * PI * k as f64 * x / length);
                    let weight = if 2 * k == n { 1.0 } else { 2.0 };
                    force += weight * (h * buf[k] * phase).re / n as f64;
                }
                force
            })
            .collect()
    }
}

impl TrackDynamics for DiscreteDynamics {
    fn contact_variations(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<ContactVariations> {
        vec![ContactVariations::Normal(self.force_from_profile(&profiles[0], dx, speed))]
    }

    fn describe_resonances(&self) -> Vec<(String, f64)> {
        let _ = (self.wheel, self.contact_stiffness);
        vec![("pinned-pinned: the rail between two sleepers".into(), self.track.pinned_pinned_frequency())]
    }

    fn forces_smooth_rail(&self) -> bool {
        true
    }
}
