//! A track layout: the supports of one period of the stretch, each at its
//! own position with its own pad and sleeper, repeated along the rail
//! (periodic over the whole period, so that the growth loop and the
//! spectrum stay periodic). One bay of identical supports is the track the
//! program has always had; several bays describe irregular track: the
//! sleeper spacing scattering by centimetres, pads of mixed stiffness, a
//! failed support (Wu and Thompson, *Acustica* 86 (2000) 313-321: random
//! sleeper spacing suppresses the pinned-pinned peak; rolland's track
//! layouts give the pad stiffness, sleeper mass and sleeper distance per
//! support, constant, periodic or random).
//!
//! A random layout draws each bay's spacing, pad stiffness and sleeper
//! mass from normal distributions truncated to their bounds (rejection,
//! with a ChaCha8 generator seeded by the layout's seed: the same seed,
//! the same layout); the spacings are then shifted by one constant so that
//! they fill the period exactly (the sample's spread unchanged) and drawn
//! again where the shift leaves a bound.

use super::TrackConfig;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// One support of a layout.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Support {
    /// Position from the period's start (m, `0 <= x < period`).
    pub x: f64,
    /// Pad stiffness (N/m); the pad's lateral and longitudinal stiffnesses
    /// scale with it (a stiffer pad is stiffer every way).
    pub pad_stiffness: f64,
    /// Sleeper mass per rail (kg).
    pub sleeper_mass: f64,
}

/// The supports of one period of the track.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// The period (m).
    pub period: f64,
    /// Its supports, in ascending position, the first at 0.
    pub supports: Vec<Support>,
}

/// Why a layout was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LayoutError {
    /// The positions do not describe supports of a period.
    #[error("{0}")]
    Positions(String),
    /// A random layout's bounds cannot be met.
    #[error("{0}")]
    Bounds(String),
}

/// A random layout's spread: each quantity's standard deviation and
/// bounds (zero spread: the configured value everywhere).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scatter {
    /// Sleeper spacing's standard deviation (m) and bounds (m).
    pub spacing: (f64, (f64, f64)),
    /// Pad stiffness's standard deviation (N/m) and bounds (N/m).
    pub pad_stiffness: (f64, (f64, f64)),
    /// Sleeper mass's standard deviation (kg) and bounds (kg).
    pub sleeper_mass: (f64, (f64, f64)),
    /// The generator's seed.
    pub seed: u64,
}

/// Draws a truncated normal sample.
const MAX_DRAWS: usize = 10_000;

impl Layout {
    /// One bay of the configured track.
    pub fn uniform(track: &TrackConfig) -> Layout {
        Layout { period: track.sleeper_spacing, supports: vec![Self::configured(track, 0.0)] }
    }

    fn configured(track: &TrackConfig, x: f64) -> Support {
        Support { x, pad_stiffness: track.pad_stiffness, sleeper_mass: track.sleeper_mass }
    }

    /// Supports at `positions` (m, over one period of `period` m, the first
    /// at 0, ascending), each with the configured pad and sleeper.
    ///
    /// # Errors
    /// Where the positions are not ascending in `[0, period)` with the
    /// first at 0.
    pub fn at_positions(track: &TrackConfig, period: f64, positions: &[f64]) -> Result<Layout, LayoutError> {
        if positions.first() != Some(&0.0) {
            return Err(LayoutError::Positions("the first sleeper must be at 0 m (the stretch's start)".into()));
        }
        for (i, w) in positions.windows(2).enumerate() {
            if w[1] <= w[0] {
                return Err(LayoutError::Positions(format!(
                    "sleeper {} at {} m does not follow sleeper {} at {} m: positions must ascend",
                    i + 2,
                    w[1],
                    i + 1,
                    w[0]
                )));
            }
        }
        let last = *positions.last().expect("checked: not empty");
        if last >= period {
            return Err(LayoutError::Positions(format!(
                "the last sleeper at {last} m must lie before the period's end, {period} m (the next period's first sleeper)"
            )));
        }
        Ok(Layout { period, supports: positions.iter().map(|&x| Self::configured(track, x)).collect() })
    }

    /// `bays` bays of the configured track's mean spacing, each support's
    /// spacing to the next, pad stiffness and sleeper mass drawn from
    /// `scatter`.
    ///
    /// # Errors
    /// Where a quantity's bounds exclude its configured mean, or the
    /// spacings cannot fill the period within their bounds.
    pub fn random(track: &TrackConfig, bays: usize, scatter: &Scatter) -> Result<Layout, LayoutError> {
        let d = track.sleeper_spacing;
        for (name, mean, (std, (lo, hi))) in [
            ("spacing", d, scatter.spacing),
            ("pad_stiffness", track.pad_stiffness, scatter.pad_stiffness),
            ("sleeper_mass", track.sleeper_mass, scatter.sleeper_mass),
        ] {
            if !(lo <= mean && mean <= hi && lo < hi || std == 0.0) {
                return Err(LayoutError::Bounds(format!(
                    "{name}'s bounds [{lo}, {hi}] must hold its mean {mean} (and be a range)"
                )));
            }
        }
        let mut rng = ChaCha8Rng::seed_from_u64(scatter.seed);
        let period = bays as f64 * d;
        let spacings = 'draw: {
            for _ in 0..MAX_DRAWS {
                let s: Vec<f64> = (0..bays)
                    .map(|_| truncated(&mut rng, d, scatter.spacing))
                    .collect::<Option<_>>()
                    .ok_or_else(|| LayoutError::Bounds("spacing: no sample within its bounds".into()))?;
                let shift = (period - s.iter().sum::<f64>()) / bays as f64;
                let s: Vec<f64> = s.iter().map(|v| v + shift).collect();
                let (lo, hi) = scatter.spacing.1;
                if scatter.spacing.0 == 0.0 || s.iter().all(|v| (lo..=hi).contains(v)) {
                    break 'draw s;
                }
            }
            return Err(LayoutError::Bounds(format!(
                "spacing: {MAX_DRAWS} draws of {bays} spacings did not fill the period {period} m within the bounds {:?}",
                scatter.spacing.1
            )));
        };
        let mut x = 0.0;
        let mut supports = Vec::with_capacity(bays);
        for s in spacings {
            let pad = truncated(&mut rng, track.pad_stiffness, scatter.pad_stiffness);
            let mass = truncated(&mut rng, track.sleeper_mass, scatter.sleeper_mass);
            let (Some(pad_stiffness), Some(sleeper_mass)) = (pad, mass) else {
                return Err(LayoutError::Bounds("pad stiffness or sleeper mass: no sample within its bounds".into()));
            };
            supports.push(Support { x, pad_stiffness, sleeper_mass });
            x += s;
        }
        Ok(Layout { period, supports })
    }

    /// The shortest period over which the supports repeat (the layout
    /// itself where they do not): `r` repetitions of the first `M / r`
    /// supports, each shifted by `period / r`.
    pub fn minimal(&self) -> Layout {
        let m = self.supports.len();
        for parts in (2..=m).rev() {
            if !m.is_multiple_of(parts) {
                continue;
            }
            let (cell, len) = (self.period / parts as f64, m / parts);
            let repeats = self.supports.iter().enumerate().all(|(i, s)| {
                let first = &self.supports[i % len];
                let shift = (i / len) as f64 * cell;
                (s.x - (first.x + shift)).abs() <= 1e-12 * self.period
                    && s.pad_stiffness == first.pad_stiffness
                    && s.sleeper_mass == first.sleeper_mass
            });
            if repeats {
                return Layout { period: cell, supports: self.supports[..len].to_vec() };
            }
        }
        self.clone()
    }

    /// The track of support `m`: the configured one with this support's
    /// pad (every direction scaled with its vertical stiffness) and
    /// sleeper, its spacing the period.
    pub fn track_of(&self, track: &TrackConfig, m: usize) -> TrackConfig {
        let s = &self.supports[m];
        let scale = s.pad_stiffness / track.pad_stiffness;
        let mut t = *track;
        t.sleeper_spacing = self.period;
        t.pad_stiffness = s.pad_stiffness;
        t.sleeper_mass = s.sleeper_mass;
        t.supports.pad_lateral_stiffness *= scale;
        t.supports.pad_longitudinal_stiffness *= scale;
        t
    }

    /// The number of supports.
    pub fn len(&self) -> usize {
        self.supports.len()
    }

    /// Whether it has no support (never, once built).
    pub fn is_empty(&self) -> bool {
        self.supports.is_empty()
    }
}

/// A normal sample of `mean` and `(std, bounds)` within the bounds
/// (rejection); `mean` where `std` is zero; `None` after [`MAX_DRAWS`]
/// rejections.
fn truncated(rng: &mut ChaCha8Rng, mean: f64, (std, (lo, hi)): (f64, (f64, f64))) -> Option<f64> {
    if std == 0.0 {
        return Some(mean);
    }
    (0..MAX_DRAWS).map(|_| mean + std * standard_normal(rng)).find(|v| (lo..=hi).contains(v))
}

/// A standard normal sample (Box-Muller).
fn standard_normal(rng: &mut ChaCha8Rng) -> f64 {
    let u: f64 = 1.0 - rng.random::<f64>();
    let v: f64 = rng.random::<f64>();
    (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scatter(std: f64, seed: u64) -> Scatter {
        Scatter {
            spacing: (std, (0.45, 0.75)),
            pad_stiffness: (0.0, (0.0, 0.0)),
            sleeper_mass: (0.0, (0.0, 0.0)),
            seed,
        }
    }

    #[test]
    fn a_random_layout_is_its_seeds_and_fills_its_period_within_bounds() {
        let t = TrackConfig::default();
        let a = Layout::random(&t, 10, &scatter(0.03, 7)).unwrap();
        assert_eq!(a, Layout::random(&t, 10, &scatter(0.03, 7)).unwrap(), "same seed, same layout");
        assert_ne!(a, Layout::random(&t, 10, &scatter(0.03, 8)).unwrap(), "another seed, another layout");
        assert!((a.period - 6.0).abs() < 1e-12);
        let mut x: Vec<f64> = a.supports.iter().map(|s| s.x).collect();
        x.push(a.period);
        let s: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        assert!((s.iter().sum::<f64>() - 6.0).abs() < 1e-12);
        assert!(s.iter().all(|v| (0.45..=0.75).contains(v)), "{s:?}");
        let mean = s.iter().sum::<f64>() / 10.0;
        let std = (s.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 9.0).sqrt();
        // Ten samples of a 3 cm spread: within a factor of two.
        assert!((0.015..0.06).contains(&std), "sample spread {std}");
    }

    #[test]
    fn bounds_that_exclude_the_mean_are_refused() {
        let t = TrackConfig::default();
        let mut s = scatter(0.03, 1);
        s.spacing.1 = (0.62, 0.8);
        let e = Layout::random(&t, 4, &s).unwrap_err().to_string();
        assert!(e.contains("spacing") && e.contains("0.62"), "{e}");
    }

    #[test]
    fn identical_bays_reduce_to_one_and_irregular_ones_do_not() {
        let t = TrackConfig::default();
        let three = Layout::at_positions(&t, 1.8, &[0.0, 0.6, 1.2]).unwrap();
        assert_eq!(three.minimal(), Layout::uniform(&t));
        let irregular = Layout::at_positions(&t, 1.8, &[0.0, 0.55, 1.2]).unwrap();
        assert_eq!(irregular.minimal(), irregular);
        let pairs = Layout::at_positions(&t, 2.4, &[0.0, 0.5, 1.2, 1.7]).unwrap().minimal();
        assert_eq!(pairs.supports.len(), 2);
        assert!((pairs.period - 1.2).abs() < 1e-15);
        let e = Layout::at_positions(&t, 1.8, &[0.0, 1.2, 0.6]).unwrap_err().to_string();
        assert!(e.contains("ascend"), "{e}");
        assert!(Layout::at_positions(&t, 1.2, &[0.0, 1.2]).is_err(), "the period's end is the next period's start");
    }
}
