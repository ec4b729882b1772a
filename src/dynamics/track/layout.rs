//! A track layout: the supports of one period of the stretch, each at its
//! own position with its own pad, sleeper and ballast, repeated along the rail
//! (periodic over the whole period, so that the growth loop and the
//! spectrum stay periodic). One bay of identical supports is the track the
//! program has always had; several bays describe irregular track: the
//! sleeper spacing scattering by centimetres, pads of mixed stiffness, a
//! failed support (Wu and Thompson, *Acustica* 86 (2000) 313-321: random
//! sleeper spacing suppresses the pinned-pinned peak; rolland's track
//! layouts give the pad stiffness, sleeper mass and sleeper distance per
//! support, constant, periodic or random).
//!
//! A random layout draws each bay's spacing and each support's values
//! from normal distributions truncated to their bounds (rejection,
//! with a ChaCha8 generator seeded by the layout's seed: the same seed,
//! the same layout); the spacings are then shifted by one constant so that
//! they fill the period exactly (the sample's spread unchanged) and drawn
//! again where the shift leaves a bound.

use super::{Damping, TrackConfig};
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
    /// Pad damping (a per-support loss factor, or the configured damping).
    pub pad_damping: Damping,
    /// Sleeper mass per rail (kg).
    pub sleeper_mass: f64,
    /// Ballast stiffness under the sleeper end (N/m); its lateral and
    /// longitudinal stiffnesses scale with it.
    pub ballast_stiffness: f64,
}

impl Support {
    /// The configured track's support at `x` (m).
    pub fn of(track: &TrackConfig, x: f64) -> Support {
        Support {
            x,
            pad_stiffness: track.pad_stiffness,
            pad_damping: track.pad_damping,
            sleeper_mass: track.sleeper_mass,
            ballast_stiffness: track.ballast_stiffness,
        }
    }

    /// Whether it is `other` but for the position.
    fn same_as(&self, other: &Support) -> bool {
        Support { x: other.x, ..*self } == *other
    }
}

/// A value a layout gives each support: its config key's stem
/// (`track.<name>_pattern`, `track.<name>_std`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Property {
    /// Pad stiffness (N/m).
    PadStiffness,
    /// Sleeper mass (kg).
    SleeperMass,
    /// Pad loss factor (1); only where the pads are damped by a loss factor.
    PadLossFactor,
    /// Ballast stiffness (N/m).
    BallastStiffness,
}

impl Property {
    /// Every property, in the order their random values are drawn (after
    /// the spacings).
    pub const ALL: [Property; 4] =
        [Property::PadStiffness, Property::SleeperMass, Property::PadLossFactor, Property::BallastStiffness];

    /// The config key's stem.
    pub fn name(self) -> &'static str {
        match self {
            Property::PadStiffness => "pad_stiffness",
            Property::SleeperMass => "sleeper_mass",
            Property::PadLossFactor => "pad_loss_factor",
            Property::BallastStiffness => "ballast_stiffness",
        }
    }

    /// The configured track's value (`None`: a viscous pad has no loss
    /// factor).
    pub fn configured(self, track: &TrackConfig) -> Option<f64> {
        match self {
            Property::PadStiffness => Some(track.pad_stiffness),
            Property::SleeperMass => Some(track.sleeper_mass),
            Property::PadLossFactor => match track.pad_damping {
                Damping::LossFactor(eta) => Some(eta),
                Damping::Viscous(_) => None,
            },
            Property::BallastStiffness => Some(track.ballast_stiffness),
        }
    }

    fn set(self, s: &mut Support, v: f64) {
        match self {
            Property::PadStiffness => s.pad_stiffness = v,
            Property::SleeperMass => s.sleeper_mass = v,
            Property::PadLossFactor => s.pad_damping = Damping::LossFactor(v),
            Property::BallastStiffness => s.ballast_stiffness = v,
        }
    }
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
    /// A random layout's bounds cannot be met: the key, and why.
    #[error("{0} {1}")]
    Bounds(String, String),
}

/// A random value's spread: the normal distribution's standard deviation
/// and the bounds it is truncated to (the value's unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spread {
    /// Standard deviation.
    pub std: f64,
    /// Lower and upper bounds.
    pub bounds: (f64, f64),
}

impl Spread {
    /// Whether the bounds hold `mean` strictly: the error names
    /// `<name>_min` (and `<name>_max`), the mean's key `mean_key` and the
    /// values with `unit`.
    fn holds(&self, mean: f64, (name, mean_key, unit): (&str, &str, &str)) -> Result<(), LayoutError> {
        let (lo, hi) = self.bounds;
        if lo < mean && mean < hi {
            return Ok(());
        }
        Err(LayoutError::Bounds(
            format!("{name}_min"),
            format!(
                "= {}{unit} and {name}_max = {}{unit} must hold the mean {mean_key} = {}{unit}",
                show(lo),
                show(hi),
                show(mean)
            ),
        ))
    }
}

/// How the supports of a period are placed.
#[derive(Debug, Clone, PartialEq)]
pub enum Spacing {
    /// Every `sleeper_spacing`.
    Uniform,
    /// At these positions (m from the period's start, the first at 0).
    Positions(Vec<f64>),
    /// Each bay's spacing drawn (m).
    Random(Spread),
}

/// A support's value ([`Property`]) along the period.
#[derive(Debug, Clone, PartialEq)]
pub enum PerSupport {
    /// The configured value at every support.
    Uniform,
    /// These values, support after support, repeated.
    Pattern(Vec<f64>),
    /// Each support's drawn.
    Random(Spread),
}

/// A layout as configured (`[track]`), before the period is known.
#[derive(Debug, Clone, PartialEq)]
pub struct LayoutSpec {
    /// The supports' positions.
    pub spacing: Spacing,
    /// Each [`Property`]'s values, in the order of [`Property::ALL`].
    pub values: [PerSupport; 4],
    /// The generator's seed (random forms).
    pub seed: u64,
}

impl LayoutSpec {
    /// One bay of the configured track, repeated (the default).
    pub fn uniform() -> LayoutSpec {
        LayoutSpec { spacing: Spacing::Uniform, values: std::array::from_fn(|_| PerSupport::Uniform), seed: 0 }
    }

    /// `property`'s values.
    pub fn value(&self, property: Property) -> &PerSupport {
        &self.values[property as usize]
    }

    /// This spec with `property`'s values `v`.
    pub fn with(mut self, property: Property, v: PerSupport) -> LayoutSpec {
        self.values[property as usize] = v;
        self
    }

    /// Whether it lays out nothing (the seed aside): one bay of the
    /// configured track.
    pub fn is_uniform(&self) -> bool {
        let u = Self::uniform();
        (&self.spacing, &self.values) == (&u.spacing, &u.values)
    }
}

/// The most draws of a truncated normal sample, and of a set of spacings.
const MAX_DRAWS: usize = 10_000;

impl Layout {
    /// One bay of the configured track.
    pub fn uniform(track: &TrackConfig) -> Layout {
        Layout { period: track.sleeper_spacing, supports: vec![Support::of(track, 0.0)] }
    }

    /// Supports at `positions` (m, over one period of `period` m, the first
    /// at 0, ascending), each the configured track's support.
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
        Ok(Layout { period, supports: positions.iter().map(|&x| Support::of(track, x)).collect() })
    }

    /// The layout of `spec` over a period of `length` (m, a whole number of
    /// `track.sleeper_spacing` where the spacing is uniform or random),
    /// reduced to its shortest repeating period; one bay of the configured
    /// track where it repeats that (the same layout as [`Self::uniform`],
    /// bit for bit). Random values are drawn in order: the spacings, then
    /// each [`Property`]'s in the order of [`Property::ALL`] (a seed
    /// gives the layouts it gave before the pad loss factor and ballast
    /// could be drawn).
    ///
    /// # Errors
    /// Where the positions are not those of a period, or random values'
    /// bounds cannot be met (the message names the key).
    pub fn from_spec(track: &TrackConfig, spec: &LayoutSpec, length: f64) -> Result<Layout, LayoutError> {
        let d = track.sleeper_spacing;
        let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
        let bays = ((length / d).round() as usize).max(1);
        let positions: Vec<f64> = match &spec.spacing {
            Spacing::Uniform => (0..bays).map(|i| i as f64 * d).collect(),
            Spacing::Positions(p) => p.clone(),
            Spacing::Random(spread) => {
                let spacings = random_spacings(&mut rng, d, spread, bays)?;
                spacings.iter().scan(0.0, |x, s| Some(std::mem::replace(x, *x + s))).collect()
            }
        };
        let period = if matches!(spec.spacing, Spacing::Positions(_)) { length } else { bays as f64 * d };
        let mut layout = Layout::at_positions(track, period, &positions)?;
        let m = layout.len();
        for property in Property::ALL {
            let which = spec.value(property);
            if *which == PerSupport::Uniform {
                continue;
            }
            let key = format!("track.{}", property.name());
            let mean = property.configured(track).ok_or_else(|| {
                LayoutError::Bounds(
                    format!("{key}{}", if matches!(which, PerSupport::Pattern(_)) { "_pattern" } else { "_std" }),
                    "gives the pads loss factors: the pads are damped viscously (track.pad_damping)".into(),
                )
            })?;
            for (s, v) in layout.supports.iter_mut().zip(per_support(&mut rng, which, mean, m, &key)?) {
                property.set(s, v);
            }
        }
        let minimal = layout.minimal();
        let one_bay = Layout::uniform(track);
        let repeats_one_bay =
            minimal.len() == 1 && minimal.supports[0] == one_bay.supports[0] && (minimal.period - d).abs() <= 1e-9 * d;
        Ok(if repeats_one_bay { one_bay } else { minimal })
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
                (s.x - (first.x + shift)).abs() <= 1e-12 * self.period && s.same_as(first)
            });
            if repeats {
                return Layout { period: cell, supports: self.supports[..len].to_vec() };
            }
        }
        self.clone()
    }

    /// The track of support `m`: the configured one with this support's
    /// pad, sleeper and ballast (the pad's and the ballast's stiffnesses in
    /// the other directions scaled with their vertical ones).
    pub fn track_of(&self, track: &TrackConfig, m: usize) -> TrackConfig {
        let s = &self.supports[m];
        let (pad, ballast) = (s.pad_stiffness / track.pad_stiffness, s.ballast_stiffness / track.ballast_stiffness);
        let mut t = *track;
        (t.pad_stiffness, t.pad_damping, t.sleeper_mass, t.ballast_stiffness) =
            (s.pad_stiffness, s.pad_damping, s.sleeper_mass, s.ballast_stiffness);
        t.supports.pad_lateral_stiffness *= pad;
        t.supports.pad_longitudinal_stiffness *= pad;
        t.supports.ballast_lateral_stiffness *= ballast;
        t.supports.ballast_longitudinal_stiffness *= ballast;
        t
    }

    /// Whether it is one bay of spacing `spacing` (m) with the support
    /// `support`: the one-bay models then serve it.
    pub fn is_one_bay_of(&self, spacing: f64, support: Support) -> bool {
        self.period == spacing && self.supports == [Support { x: 0.0, ..support }]
    }

    /// Whether it is one bay of the configured `track`.
    pub fn is_one_bay(&self, track: &TrackConfig) -> bool {
        self.is_one_bay_of(track.sleeper_spacing, Support::of(track, 0.0))
    }

    /// The supports' positions (m) and the period's end: each span's
    /// start and end, pairwise.
    pub fn bounds(&self) -> Vec<f64> {
        self.supports.iter().map(|s| s.x).chain([self.period]).collect()
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

/// `bays` spacings of mean `d` (m) drawn within their bounds and shifted
/// by one constant to fill `bays d` exactly (drawn again where the shift
/// leaves a bound).
fn random_spacings(rng: &mut ChaCha8Rng, d: f64, spread: &Spread, bays: usize) -> Result<Vec<f64>, LayoutError> {
    spread.holds(d, ("track.spacing", "track.sleeper_spacing", " m"))?;
    let (std, (lo, hi)) = (spread.std, spread.bounds);
    for _ in 0..MAX_DRAWS {
        let s: Vec<f64> = (0..bays).map(|_| truncated(rng, d, spread)).collect::<Option<_>>().ok_or_else(|| {
            LayoutError::Bounds("track.spacing_std".into(), format!("= {std} m: no sample within [{lo}, {hi}] m"))
        })?;
        let shift = (bays as f64 * d - s.iter().sum::<f64>()) / bays as f64;
        let s: Vec<f64> = s.iter().map(|v| v + shift).collect();
        if s.iter().all(|v| (lo..=hi).contains(v)) {
            return Ok(s);
        }
    }
    Err(LayoutError::Bounds(
        "track.spacing_std".into(),
        format!(
            "= {std} m: {MAX_DRAWS} draws of {bays} spacings did not fill the stretch within track.spacing_min = {lo} m \
             and track.spacing_max = {hi} m"
        ),
    ))
}

/// Each of `m` supports' value of `which` (the configured `mean` where
/// uniform), `key` the value's config key.
fn per_support(
    rng: &mut ChaCha8Rng,
    which: &PerSupport,
    mean: f64,
    m: usize,
    key: &str,
) -> Result<Vec<f64>, LayoutError> {
    match which {
        PerSupport::Uniform => Ok(vec![mean; m]),
        PerSupport::Pattern(p) => Ok((0..m).map(|i| p[i % p.len()]).collect()),
        PerSupport::Random(spread) => {
            spread.holds(mean, (key, key, ""))?;
            let (std, (lo, hi)) = (spread.std, spread.bounds);
            (0..m).map(|_| truncated(rng, mean, spread)).collect::<Option<_>>().ok_or_else(|| {
                LayoutError::Bounds(
                    format!("{key}_std"),
                    format!("= {}: no sample within [{}, {}]", show(std), show(lo), show(hi)),
                )
            })
        }
    }
}

/// A value as a config would write it (`2e8`, `0.6`).
fn show(v: f64) -> String {
    if v != 0.0 && !(1e-3..1e5).contains(&v.abs()) { format!("{v:e}") } else { format!("{v}") }
}

/// A normal sample of `mean` and `(std, bounds)` within the bounds
/// (rejection); `mean` where `std` is zero; `None` after [`MAX_DRAWS`]
/// rejections.
fn truncated(rng: &mut ChaCha8Rng, mean: f64, spread: &Spread) -> Option<f64> {
    let (std, (lo, hi)) = (spread.std, spread.bounds);
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

    fn random(std: f64, seed: u64) -> LayoutSpec {
        LayoutSpec { spacing: Spacing::Random(Spread { std, bounds: (0.45, 0.75) }), seed, ..LayoutSpec::uniform() }
    }

    #[test]
    fn a_random_layout_is_its_seeds_and_fills_its_period_within_bounds() {
        let t = TrackConfig::default();
        let a = Layout::from_spec(&t, &random(0.03, 7), 6.0).unwrap();
        assert_eq!(a, Layout::from_spec(&t, &random(0.03, 7), 6.0).unwrap(), "same seed, same layout");
        assert_ne!(a, Layout::from_spec(&t, &random(0.03, 8), 6.0).unwrap(), "another seed, another layout");
        assert_eq!(a.len(), 10);
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
    fn bounds_that_exclude_the_mean_are_refused_naming_the_key() {
        let t = TrackConfig::default();
        let spec =
            LayoutSpec { spacing: Spacing::Random(Spread { std: 0.03, bounds: (0.62, 0.8) }), ..random(0.03, 1) };
        let e = Layout::from_spec(&t, &spec, 2.4).unwrap_err().to_string();
        assert!(e.contains("track.spacing_min = 0.62"), "{e}");
        let spec = LayoutSpec::uniform()
            .with(Property::PadStiffness, PerSupport::Random(Spread { std: 1e7, bounds: (1e6, 1e8) }));
        let e = Layout::from_spec(&t, &spec, 2.4).unwrap_err().to_string();
        assert!(e.contains("track.pad_stiffness_max"), "{e}");
    }

    #[test]
    fn a_pattern_repeats_and_a_uniform_stretch_is_one_bay() {
        let t = TrackConfig::default();
        assert_eq!(Layout::from_spec(&t, &LayoutSpec::uniform(), 3.0).unwrap(), Layout::uniform(&t));
        let spec = LayoutSpec::uniform().with(Property::PadStiffness, PerSupport::Pattern(vec![1e8, 3e8]));
        let l = Layout::from_spec(&t, &spec, 2.4).unwrap();
        assert_eq!(l.len(), 2, "two bays repeat over four");
        assert_eq!(l.supports[1].pad_stiffness, 3e8);
        let spec = LayoutSpec { spacing: Spacing::Positions(vec![0.0, 0.6, 1.2]), ..LayoutSpec::uniform() };
        assert_eq!(Layout::from_spec(&t, &spec, 1.8).unwrap(), Layout::uniform(&t), "identical bays: one bay");
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
