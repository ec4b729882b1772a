//! Traffic scaling and its stability criterion.
//!
//! One simulated passage stands for `m` real ones: `r <- r - m W`, an
//! explicit Euler step of `dr/dn = -W(r)` over `m` real passages (n counts
//! real passages). Per harmonic k of the centre-line profile, with complex
//! Fourier coefficients `R_k` (profile) and `W_k` (wear of one passage), the
//! update is `R_k <- R_k (1 - m W_k / R_k)`. Where the wear follows the
//! profile linearly (`W_k = c_k R_k`, c_k complex: a pattern whose wear is
//! out of phase with it travels along the rail), the exact evolution over the
//! same traffic is `R_k exp(-m c_k)`. The Euler factor `1 - m c_k` errs in
//! the log-amplitude change per real passage by about `m |c_k|^2 / 2`, i.e.
//! by `q |c_k| / 2` with `q = m |c_k|`: about q/2 of the growth rate for a
//! standing pattern (real c_k), more for a travelling one (|c_k| > |Re c_k|).
//! A standing decaying harmonic changes sign beyond `m c_k = 1` and grows
//! spuriously beyond 2; a travelling one grows spuriously at any m
//! (`|1 - i m Im c_k| > 1`), by about `q |c_k| / 2`. So the quantity to bound
//! is the relative profile change per update
//!
//! ```text
//! q = m max_k |W_k| / max(|R_k|, s max_j |R_j|)
//! ```
//!
//! For the harmonics that carry the corrugation (amplitude at least `s` =
//! [`SIGNIFICANT`] of the largest) this is their relative change; a small
//! harmonic's change counts relative to `s max_j |R_j|`, so that wear
//! building up a new, still negligible harmonic (a forced, linear
//! accumulation, which the Euler update integrates exactly) does not hold `m`
//! down, while it still counts once it is a visible part of the corrugation.
//! The default bound is 0.05 (growth rates within 2.5 % for standing
//! patterns; measured +16 % at q = 0.1 for the travelling 15 mm pattern of
//! growth_fastsim). With `imposed` dynamics the wear does not depend on the
//! profile, the update is exact for any `m`, and `q` is reported as 0.
//!
//! Wear that does not depend on the profile at all (forced: the discrete
//! supports' parametric excitation wears the sleeper-passing harmonics on a
//! smooth rail) is integrated exactly by the Euler update whatever m; where
//! the track forces it, the growth loop passes `W - W_0` here, `W_0` the wear
//! of one passage of the same class over the smooth rail, so that only the
//! profile-dependent wear bounds m (measured on growth_discrete.toml at
//! 80 km/h: m 634-1793 -> 2000-4000 over the first passages, the
//! sleeper-passing harmonics having bounded it).
//!
//! The wear `W` of a passage is computed from the profile before the update
//! and does not depend on `m`, so the adaptive controller picks the passage's
//! `m` after computing `W`: `m_n = min(m_max, 2 m_{n-1}, q_max / rho_n)`,
//! `rho_n = q / m`, and never below 1.

use crate::params::TrafficScaling;
use num_complex::Complex64;
use rustfft::FftPlanner;

/// Harmonics whose amplitude is at least this fraction of the largest count
/// with their own amplitude in the criterion; smaller ones relative to this
/// fraction of the largest (1).
pub const SIGNIFICANT: f64 = 0.1;

/// The largest factor by which the adaptive controller raises `m` from one
/// passage to the next (1).
pub const MAX_RAISE: f64 = 2.0;

/// Relative profile change per real passage, `rho = max_k |W_k| /
/// max(|R_k|, s max_j |R_j|)` (1 per passage), of the centre-line `profile`
/// and the wear `wear` of one passage (m, same sampling, one period). 0 for
/// a line without corrugation.
pub fn change_rate(profile: &[f64], wear: &[f64]) -> f64 {
    let n = profile.len();
    let fft = FftPlanner::new().plan_fft_forward(n);
    let transform = |line: &[f64]| {
        let mut buf: Vec<Complex64> = line.iter().map(|v| Complex64::new(*v, 0.0)).collect();
        fft.process(&mut buf);
        buf
    };
    let (r, w) = (transform(profile), transform(wear));
    let harmonics = 1..=n / 2;
    let largest = harmonics.clone().map(|k| r[k].norm()).fold(0.0f64, f64::max);
    if largest == 0.0 {
        return 0.0;
    }
    harmonics.map(|k| w[k].norm() / r[k].norm().max(SIGNIFICANT * largest)).fold(0.0f64, f64::max)
}

impl TrafficScaling {
    /// The scale of a passage with change rate `rho` (1 per passage), after
    /// a passage with scale `previous` (None for the first).
    pub fn scale(&self, previous: Option<f64>, rho: f64) -> f64 {
        match *self {
            TrafficScaling::Fixed { scale, .. } => scale,
            TrafficScaling::Adaptive { initial, max, max_update_ratio } => {
                let cap = previous.map_or(initial, |p| (MAX_RAISE * p).min(max));
                let bound = if rho > 0.0 { max_update_ratio / rho } else { f64::INFINITY };
                cap.min(bound).max(1.0)
            }
        }
    }

    /// The bound on `q` the run is checked against (1).
    pub fn max_update_ratio(&self) -> f64 {
        match *self {
            TrafficScaling::Fixed { max_update_ratio, .. } | TrafficScaling::Adaptive { max_update_ratio, .. } => {
                max_update_ratio
            }
        }
    }
}

/// Default bound on the relative profile change per update (1): the growth
/// rate is then within about 2.5 %.
pub const DEFAULT_MAX_UPDATE_RATIO: f64 = 0.05;

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn sine(n: usize, k: usize, amp: f64, phase: f64) -> Vec<f64> {
        (0..n).map(|i| amp * (2.0 * PI * (k * i) as f64 / n as f64 + phase).sin()).collect()
    }

    #[test]
    fn change_rate_is_wear_over_profile_amplitude() {
        // One corrugation harmonic, wear in quadrature with it: |W|/|R|.
        let p = sine(256, 8, 1e-6, 0.0);
        let w: Vec<f64> = sine(256, 8, 3e-12, PI / 2.0).iter().map(|v| v + 1e-9).collect();
        assert!((change_rate(&p, &w) - 3e-6).abs() < 1e-15);
        // A harmonic under 10 % of the largest counts relative to 10 % of it:
        // 2e-12 / 1e-7 = 2e-5.
        let small: Vec<f64> = p.iter().zip(sine(256, 3, 0.5e-8, 0.0)).map(|(a, b)| a + b).collect();
        let w2: Vec<f64> = w.iter().zip(sine(256, 3, 2e-12, 0.0)).map(|(a, b)| a + b).collect();
        assert!((change_rate(&small, &w2) - 2e-5).abs() < 1e-13);
        // A significant one (20 %) with its own amplitude: 2e-12 / 2e-7 = 1e-5.
        let big: Vec<f64> = p.iter().zip(sine(256, 3, 2e-7, 0.0)).map(|(a, b)| a + b).collect();
        assert!((change_rate(&big, &w2) - 1e-5).abs() < 1e-13);
        assert_eq!(change_rate(&[0.0; 16], &[1.0; 16]), 0.0);
    }

    #[test]
    fn adaptive_scale_respects_the_bound_and_the_raise() {
        let a = TrafficScaling::Adaptive { initial: 1e3, max: 1e6, max_update_ratio: 0.05 };
        assert_eq!(a.scale(None, 1e-6), 1e3);
        assert_eq!(a.scale(Some(1e3), 1e-6), 2e3);
        assert!((a.scale(Some(4e4), 1e-6) - 5e4).abs() < 1e-9);
        assert_eq!(a.scale(Some(8e5), 0.0), 1e6);
        assert_eq!(a.scale(Some(10.0), 1.0), 1.0);
        assert_eq!(TrafficScaling::Fixed { scale: 7.0, max_update_ratio: 0.05 }.scale(Some(3.0), 1.0), 7.0);
    }
}
