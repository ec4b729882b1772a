//! Vehicle-track dynamics for the corrugation growth loop (book:
//! docs/src/theory/track.md): the dynamic wheel-rail normal force excited by the rail
//! profile of the current passage.
//!
//! The rail profile `r(X)` over the periodic stretch of length `L` is expanded
//! in Fourier harmonics `n` (wavenumber `k = 2 pi n / L`, wavelength
//! `lambda = L / n`). A wheel running at speed `V` meets harmonic `n` at the
//! frequency `f = V / lambda = V n / L`, and a linear model answers with a
//! force harmonic `H(f) r_n`. The static load is not part of this force: the
//! mean (DC) harmonic is always dropped, the caller adds the mean load.
//!
//! Conventions of every model here:
//! - time dependence `exp(+i w t)`, `w = 2 pi f`; a harmonic `exp(i k X)` of the
//!   profile, met by a wheel moving in `+X` (`X = V t`), has `w = k V`;
//! - `r > 0`: the rail top is higher (a bump), which presses the wheel harder;
//! - the force is the compressive contact force (N), positive = more load.
//!
//! Laid out by body: [`track`] the rail and its supports (the rail's
//! sections, the continuous and discrete track, their receptances at the
//! rail head in every direction), [`wheelset`] the wheelset (rigid,
//! torsion, modal), [`coupling`] the contact between them (the contact
//! point's closure, the creep forces' response); [`model`] assembles them
//! into the one vehicle-track model ([`model::VehicleTrack`]: one wheel or
//! a vehicle on one or two rails, the continuous or the discrete track,
//! the vertical direction or every direction), on the vertical closed
//! forms of [`receptance`].
//!
//! [`TrackDynamics`] is the interface the pass loop uses: one question,
//! so that a richer model (a track of irregular bays, a curve) composes
//! without touching the loop.

// The bodies: the rail and its supports, the wheelset, the contact
// coupling between them.
pub mod coupling;
pub mod track;
pub mod wheelset;

// The vehicle-track model assembled from them, and the vertical
// closed forms it builds on.
pub mod model;
pub mod receptance;

pub use receptance::{
    DynamicsError, ReceptanceModel, TrackParams, WheelParams, hertz_stiffness, winkler_point_receptance,
};

use num_complex::Complex64;
use rustfft::FftPlanner;

/// A linear (or linearised) vehicle-track model: the one question the
/// growth loop asks of it is each wheel's contact variations along the
/// periodic stretch from the profiles the wheels meet
/// ([`TrackDynamics::contact_variations`]); the rest describes it.
pub trait TrackDynamics {
    /// Each wheel's contact variations (zero mean) when the wheel is at
    /// `X_j = j dx`, for a vehicle at speed `speed` (m/s; the sign gives
    /// the direction of travel along `X`), from the profile each wheel sees
    /// (`profiles[wheel]`, m, rail top height, positive up: one period of
    /// a periodic signal sampled every `dx` (m); wheels of different loads
    /// see the rail through different patches). A vertical model gives the
    /// normal force alone, a model in every direction the creep force's
    /// and creepages' variations beside it.
    fn contact_variations(&self, profiles: &[Vec<f64>], dx: f64, speed: f64) -> Vec<ContactVariations>;

    /// The model's resonances as (label, frequency in Hz), for reports.
    fn describe_resonances(&self) -> Vec<(String, f64)>;

    /// Whether the model forces a dynamic force on a smooth rail (the
    /// discrete supports' parametric excitation): wear that does not depend
    /// on the profile, which the growth loop's update bound leaves out.
    fn forces_smooth_rail(&self) -> bool {
        false
    }

    /// The wheels of the vehicle the model couples through the rail (1:
    /// a single wheel).
    fn wheels(&self) -> usize {
        1
    }

    /// The rail wheel `wheel` runs on: 0 the first, 1 the wheelset's
    /// second rail.
    fn rail_of(&self, wheel: usize) -> usize {
        let _ = wheel;
        0
    }
}

/// The dynamic variations of one wheel's contact along the stretch (zero
/// mean), at the profile's samples.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSignals {
    /// Normal force (N).
    pub normal: Vec<f64>,
    /// Longitudinal creep force on the wheel (N).
    pub force_x: Vec<f64>,
    /// Longitudinal creepage (1).
    pub creepage_x: Vec<f64>,
    /// Lateral creepage (1).
    pub creepage_y: Vec<f64>,
    /// Spin (1/m; zeros without the spin's channel).
    pub spin: Vec<f64>,
}

/// One wheel's contact variations along the stretch (see
/// [`TrackDynamics::contact_variations`]).
#[derive(Debug, Clone, PartialEq)]
pub enum ContactVariations {
    /// A vertical model: the dynamic normal force (N, zero mean). The
    /// creepage then follows the wheelset's torsion where the scene has
    /// one.
    Normal(Vec<f64>),
    /// A model in every direction: the normal force, the longitudinal
    /// creep force, the creepages and the spin.
    Every(ContactSignals),
}

impl ContactVariations {
    /// The dynamic normal force (N, zero mean).
    pub fn normal(&self) -> &[f64] {
        match self {
            ContactVariations::Normal(n) => n,
            ContactVariations::Every(s) => &s.normal,
        }
    }

    /// The variations in every direction, where the model has them.
    pub fn every(&self) -> Option<&ContactSignals> {
        match self {
            ContactVariations::Normal(_) => None,
            ContactVariations::Every(s) => Some(s),
        }
    }

    /// The normal forces of a vertical model's wheels.
    pub fn normals(forces: Vec<Vec<f64>>) -> Vec<ContactVariations> {
        forces.into_iter().map(ContactVariations::Normal).collect()
    }
}

/// Applies a frequency response to one period of a sampled periodic profile:
/// `F(X) = sum_{n != 0} H(f_n) r_n exp(i k_n X)`, with `r_n` the discrete
/// Fourier coefficients of `profile`, `k_n = 2 pi m / L` for the signed
/// harmonic index `m` (`m = n` for `n <= N/2`, `m = n - N` above),
/// `L = N dx`, and `f_n = speed k_n / (2 pi)`.
///
/// `h(f)` is the response at a frequency `f >= 0` (Hz); for `f < 0` the
/// transform of a real system `H(-f) = conj(H(f))` is used, so the result is
/// real. The Nyquist harmonic of an even `N` (`m = N/2`, a sampled
/// `cos(pi X / dx)` whose phase the samples cannot resolve) is multiplied by
/// `Re H(f_Nyquist)`, the response of a zero-phase cosine. The mean harmonic
/// is dropped. The result is deterministic (a fixed FFT plan per length).
///
/// # Panics
/// If `dx` is not finite and positive or `speed` is not finite.
pub fn apply_periodic_response<F>(profile: &[f64], dx: f64, speed: f64, h: F) -> Vec<f64>
where
    F: Fn(f64) -> Complex64,
{
    assert!(dx.is_finite() && dx > 0.0, "sample spacing dx = {dx} m must be finite and > 0");
    assert!(speed.is_finite(), "speed = {speed} m/s must be finite");
    let n = profile.len();
    if n < 2 {
        return vec![0.0; n];
    }
    let length = n as f64 * dx;
    let mut planner = FftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(n);
    let inverse = planner.plan_fft_inverse(n);
    let mut buf: Vec<Complex64> = profile.iter().map(|&r| Complex64::new(r, 0.0)).collect();
    forward.process(&mut buf);
    buf[0] = Complex64::new(0.0, 0.0);
    for (bin, c) in buf.iter_mut().enumerate().skip(1) {
        let m = if 2 * bin <= n { bin as f64 } else { bin as f64 - n as f64 };
        let f = speed * m / length;
        let hf = if f >= 0.0 { h(f) } else { h(-f).conj() };
        *c *= if 2 * bin == n { Complex64::new(hf.re, 0.0) } else { hf };
    }
    inverse.process(&mut buf);
    // rustfft does not normalise: the inverse of the forward is N times the input.
    let scale = 1.0 / n as f64;
    buf.iter().map(|c| c.re * scale).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn identity_response_removes_only_the_mean() {
        let n = 37;
        let profile: Vec<f64> = (0..n).map(|j| 1.0 + (j as f64 * 0.7).sin() + 0.1 * j as f64).collect();
        let mean = profile.iter().sum::<f64>() / n as f64;
        let out = apply_periodic_response(&profile, 1e-3, 20.0, |_| Complex64::new(1.0, 0.0));
        for (o, p) in out.iter().zip(&profile) {
            assert!((o - (p - mean)).abs() < 1e-12, "{o} vs {}", p - mean);
        }
    }

    #[test]
    fn pure_delay_shifts_a_harmonic() {
        // H(f) = exp(-i 2 pi f tau) delays the signal by tau, i.e. shifts it by V tau along X.
        let (n, dx, speed) = (64, 1e-3, 10.0);
        let length = n as f64 * dx;
        let k = 2.0 * PI * 3.0 / length;
        let tau = 1.3e-5;
        let profile: Vec<f64> = (0..n).map(|j| (k * j as f64 * dx).cos()).collect();
        let out = apply_periodic_response(&profile, dx, speed, |f| Complex64::from_polar(1.0, -2.0 * PI * f * tau));
        for (j, o) in out.iter().enumerate() {
            let expect = (k * (j as f64 * dx - speed * tau)).cos();
            assert!((o - expect).abs() < 1e-12, "j = {j}: {o} vs {expect}");
        }
    }

    #[test]
    fn nyquist_harmonic_takes_the_real_part() {
        // An alternating profile is the Nyquist harmonic: it is scaled by Re H(f_Nyquist).
        let (n, dx, speed) = (16, 1e-3, 10.0);
        let profile: Vec<f64> = (0..n).map(|j| if j % 2 == 0 { 1.0 } else { -1.0 }).collect();
        let h = |f: f64| Complex64::new(2.0, 3.0 + f);
        let out = apply_periodic_response(&profile, dx, speed, h);
        let f_nyquist = speed / (2.0 * dx);
        for (o, p) in out.iter().zip(&profile) {
            assert!((o - 2.0 * p).abs() < 1e-12, "{o} vs {}", 2.0 * p);
        }
        assert!(h(f_nyquist).im != 0.0);
    }

    #[test]
    fn short_profiles_give_zero() {
        assert!(apply_periodic_response(&[], 1e-3, 1.0, |_| Complex64::new(1.0, 0.0)).is_empty());
        assert_eq!(apply_periodic_response(&[3.0], 1e-3, 1.0, |_| Complex64::new(1.0, 0.0)), vec![0.0]);
    }
}
