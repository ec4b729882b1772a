//! The linear growth spectrum of a passage (book:
//! docs/src/theory/growth-spectrum.md): what grows on a track, as a
//! property of the track and the traffic rather than of one roughness.
//!
//! A passage's wear is `W(r) = W_0 + J r + O(r^2)` about the smooth rail
//! (or about any rail `r_0`, `W(r_0 + d) = W(r_0) + J d + O(d^2)`): `W_0`
//! the forced pattern (the sleeper passing and any imposed load, whatever
//! the roughness), `J` the roughness-driven part, which makes a pattern
//! grow or decay exponentially under `r <- r - W(r)` per wheel passage
//! (Hempelmann and Knothe's roughness-to-wear transfer; Meehan, Daniel and
//! Campey, Wear 258 (2005): growth as an instability across passages).
//! Here `J` is measured on the passage's own model chain ([`crate::growth::wear_map::WearMap`]:
//! the contact, the dynamics, the wear of a growth study) by finite
//! differences: perturbations `eps cos(q X + phi)`, uniform across the
//! head as roughness is, and the response's contact-filtered line (the
//! line the study's spectra and growth rates are of, `passes/
//! filtered_spectrum`),
//!
//! ```text
//! J d = (W(r0 + eps d) - W(r0 - eps d)) / (2 eps)        (central)
//! J d = (W(r0 + eps d) - W(r0)) / eps                    (forward)
//! ```
//!
//! Central differences cancel the even part of the error (a perturbation's
//! first and second order alike), so `eps` can be as small as the solvers
//! allow and as large as the chain stays linear.
//!
//! The stretch repeats (a periodic stretch of a growth study: on discrete
//! supports a whole number of sleeper bays), so `J` couples only the
//! harmonics of a Bloch class ([`bloch`]); a supercell of `M` stretches
//! carries the classes `kappa_j = 2 pi j / (M L)`, and every class is
//! measured at once, one perturbation of each per passage. The eigenvalues
//! of each class's `-J` are the growth rates and drifts, its eigenvectors
//! the patterns ([`modes`]). Under mixed traffic the update is the classes'
//! share-weighted sum, `J = sum_c s_c J_c`.

pub mod bloch;
pub mod forecast;
pub mod measure;
pub mod modes;
pub mod outlook;

use crate::build::{DynamicsError, study_grid};
use crate::params::{DynamicsKind, Scene};
use crate::passage::PassageError;
use bloch::{Class, Harmonic, Slot};
use measure::Responses;
use modes::Mode;
use ndarray::Array2;
use num_complex::Complex64;

pub use crate::params::spectrum::{Base, DEFAULT_PERTURBATION, Difference, SpectrumParams};

/// Why the spectrum could not be measured.
#[derive(Debug, thiserror::Error)]
pub enum SpectrumError {
    /// The dynamics in every direction could not be set up.
    #[error(transparent)]
    Dynamics(#[from] DynamicsError),
    /// A passage failed.
    #[error("{what}: {source}")]
    Passage {
        /// Which passage.
        what: String,
        /// Cause.
        source: PassageError,
    },
    /// The eigenproblem failed.
    #[error(transparent)]
    Eigen(#[from] modes::EigenError),
    /// The parts of a measurement do not make one.
    #[error("{0}")]
    Parts(String),
    /// A thread stopped because another thread's passage failed (that
    /// failure is the one reported).
    #[error("stopped: another thread's passage failed")]
    Stopped,
    /// The band holds no harmonic of the supercell.
    #[error(
        "spectrum.wavelength_min = {min} m to spectrum.wavelength_max = {max} m holds no harmonic of the {length} m \
         supercell resolved by the rail grid (wavelengths down to {shortest} m)"
    )]
    EmptyBand {
        /// Shortest wavelength (m).
        min: f64,
        /// Longest wavelength (m).
        max: f64,
        /// The supercell (m).
        length: f64,
        /// The shortest wavelength the rail grid resolves (m).
        shortest: f64,
    },
}

/// How far the measurement has come.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Supercell passages done.
    pub done: usize,
    /// Supercell passages in all.
    pub total: usize,
}

/// The spectrum: the classes, their matrices, the modes, the forced
/// pattern and what it cost.
#[derive(Debug, Clone)]
pub struct Spectrum {
    /// The stretch's length `L` (m).
    pub stretch: f64,
    /// The supercell's stretches `M`.
    pub cells: usize,
    /// The scene's speed (m/s).
    pub speed: f64,
    /// The classes measured (`0 <= j <= M / 2`).
    pub classes: Vec<Class>,
    /// Each class's `J = sum_c s_c J_c` on its basis (1 per wheel passage,
    /// row major).
    pub matrices: Vec<Vec<Complex64>>,
    /// The modes, fastest growing first.
    pub modes: Vec<Mode>,
    /// The stretch's harmonics' wavelengths `L / n`, n = 1 .. N/2 (m).
    pub wavelengths: Vec<f64>,
    /// The forced pattern on each rail: the amplitude of each harmonic of
    /// the contact-filtered wear one wheel passage leaves on the smooth rail
    /// (m per wheel passage, share-weighted over the traffic), on
    /// `wavelengths`.
    pub forced_wear: Vec<Vec<f64>>,
    /// The same as complex coefficients (m; amplitude `2 |c|`), per rail,
    /// harmonics `n = 1 ..` of the stretch: the forcing of a forecast
    /// ([`forecast`]).
    pub forced_coefficients: Vec<Vec<Complex64>>,
    /// The wear of one wheel passage over the base rail, the same way (m).
    pub base_wear: Vec<Vec<f64>>,
    /// The mean depth of the smooth rail's contact-filtered wear per wheel
    /// passage on each rail (m): the scale the forced pattern is small or
    /// large against.
    pub mean_wear: Vec<f64>,
    /// Positions along the stretch of the modes' envelopes (m from its start).
    pub positions: Vec<f64>,
    /// The discrete track's supports along the stretch (m from its start:
    /// the layout's period repeated over the stretch, the first support at
    /// 0); empty on a continuous track.
    pub supports: Vec<f64>,
    /// Rails in the model (1 or 2).
    pub rails: usize,
    /// Whether the passages took the linear profile contact (else the
    /// nonlinear one, or Hertz's).
    pub linear_contact: bool,
    /// Passages run, in passages over one stretch (supercell passages
    /// times `M`).
    pub passage_equivalents: f64,
    /// CPU seconds of the measurement (all threads).
    pub cpu_seconds: f64,
    /// Wall-clock seconds.
    pub wall_seconds: f64,
    /// What the user must know (passages that left the linear range).
    pub warnings: Vec<String>,
    /// The dynamics' resonances (label, Hz), for naming the modes.
    pub resonances: Vec<(String, f64)>,
}

/// The scene over a supercell of `cells` of its stretches: the rail grid
/// and the passage `cells - 1` stretches longer, everything else the same
/// (the stretch repeats, so its dynamics and contact do). The supercell's
/// grid is `cells` copies of the stretch's (its spacing the stretch's
/// own, `L / nx`, also where `rail.dx` does not divide `L`), so that a
/// shift by the stretch is a whole number of nodes.
pub fn supercell(scene: &Scene, cells: usize) -> Scene {
    let mut s = scene.clone();
    let length = scene.rail.x_max - scene.rail.x_min;
    s.rail.x_max = scene.rail.x_min + cells as f64 * length;
    if cells > 1 {
        s.rail.dx = study_grid(scene).dx;
    }
    s.end = scene.end + (cells - 1) as f64 * length;
    s
}

/// The supercell's band of positive harmonic indices for `params` on a
/// supercell of `nodes` nodes and length `length` (m): `L_s / lambda` in
/// the band, below the grid's Nyquist index.
pub fn band(params: &SpectrumParams, nodes: usize, length: f64) -> Option<(usize, usize)> {
    let low = (length / params.wavelength_max - 1e-9).ceil().max(1.0) as usize;
    let high = ((length / params.wavelength_min + 1e-9).floor() as usize).min(nodes / 2 - 1);
    (low <= high).then_some((low, high))
}

/// What a spectrum of a scene will measure, before measuring it.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// The supercell's length `M L` (m).
    pub supercell: f64,
    /// The classes measured, and how many harmonics (both signs, every
    /// rail) each holds.
    pub classes: Vec<(usize, usize)>,
    /// Rounds of perturbations (one passage each, two with central
    /// differences).
    pub rounds: usize,
    /// Supercell passages in all (every traffic class, the base, the
    /// smooth rail where the base is not smooth).
    pub passages: usize,
    /// The same in passages over one stretch.
    pub passage_equivalents: usize,
}

/// The plan of `params` on `scene` (a growth study's) with `rails` rails;
/// None where the band holds no harmonic.
pub fn plan(scene: &Scene, params: &SpectrumParams, rails: usize) -> Option<Plan> {
    let (classes, _, rounds) = measure::layout(scene, params, rails).ok()?;
    let cell = study_grid(scene);
    let per_round = if params.difference == Difference::Central { 2 } else { 1 };
    let traffic = scene.growth.as_ref().map_or(1, |g| g.classes.len().max(1));
    let smooth = usize::from(params.base != Base::Smooth);
    let passages = traffic * (1 + smooth + per_round * rounds.len());
    Some(Plan {
        supercell: cell.nx as f64 * cell.dx * params.classes as f64,
        classes: classes.iter().map(|c| (c.j, c.basis.len())).collect(),
        rounds: rounds.len(),
        passages,
        passage_equivalents: passages * params.classes,
    })
}

/// The growth spectrum of `scene` (a growth study's scene: its contact,
/// dynamics, traffic) about the rails `base` (m, on the study's grid; the
/// first rail's, then the second's), as `params` ask: every round measured
/// ([`measure::measure`], on `jobs` threads) and the classes' matrices
/// assembled and solved ([`Spectrum::from_responses`]).
pub fn linear_spectrum(
    scene: &Scene,
    base: &[Array2<f64>],
    params: &SpectrumParams,
    jobs: usize,
    progress: &mut dyn FnMut(Progress),
) -> Result<Spectrum, SpectrumError> {
    let responses = measure::measure(scene, base, params, None, jobs, progress)?;
    Spectrum::from_responses(scene, params, responses)
}

/// `scene`'s discrete supports along a stretch of `stretch` (m) from its
/// start (its first support there): the layout's period repeated; none on
/// a continuous track.
fn supports_along(scene: &Scene, stretch: f64) -> Vec<f64> {
    let discrete = scene.growth.as_ref().is_some_and(|g| matches!(g.dynamics, DynamicsKind::Discrete { .. }));
    if !discrete {
        return Vec::new();
    }
    let layout = &scene.layout;
    let periods = ((stretch / layout.period).round() as usize).max(1);
    (0..periods).flat_map(|r| layout.supports.iter().map(move |s| r as f64 * layout.period + s.x)).collect()
}

/// How near a resonance a mode's frequency must be to be named after it
/// (relative).
pub const RESONANCE_BAND: f64 = 0.1;

/// Points along the stretch at which a mode's envelope is given.
pub const ENVELOPE_POINTS: usize = 120;

/// Points per support interval at which a mode's deepest place is sought.
pub const SPAN_POINTS: usize = 64;

impl Spectrum {
    /// The spectrum of the measured `responses` (every slot of every class
    /// measured) of `scene` with `params`: each class's `J` assembled
    /// ([`bloch::assemble`]), its modes, the forced pattern's amplitudes.
    pub fn from_responses(scene: &Scene, params: &SpectrumParams, r: Responses) -> Result<Self, SpectrumError> {
        let missing = r.columns.iter().flatten().filter(|c| c.is_empty()).count();
        if missing > 0 {
            return Err(SpectrumError::Parts(format!("{missing} perturbations of the measurement are missing")));
        }
        let matrices = bloch::assemble(&r.classes, &r.plan, params.perturbation, |slot: &Slot, target: &Harmonic| {
            let class = &r.classes[slot.class];
            let k = r.plan[slot.class].iter().position(|s| s == slot).expect("the slot is in its class's plan");
            let row = class.basis.iter().position(|h| h == target).expect("the target is in its class's basis");
            r.columns[slot.class][k][row]
        });
        let modes = modes::modes(&r.classes, &matrices)?;
        let cell = study_grid(scene);
        let amplitude = |v: &Vec<Complex64>| v.iter().map(|c| 2.0 * c.norm()).collect::<Vec<f64>>();
        let points = cell.nx.min(ENVELOPE_POINTS);
        let stretch = cell.nx as f64 * cell.dx;
        Ok(Spectrum {
            stretch,
            cells: r.cells,
            speed: scene.speed,
            classes: r.classes,
            matrices,
            modes,
            wavelengths: crate::harmonics::wavelengths(cell.nx, cell.dx),
            forced_wear: r.forced.iter().map(amplitude).collect(),
            forced_coefficients: r.forced.clone(),
            base_wear: r.base.iter().map(amplitude).collect(),
            mean_wear: r.mean_wear,
            positions: (0..points).map(|k| stretch * k as f64 / points as f64).collect(),
            supports: supports_along(scene, stretch),
            rails: r.rails,
            linear_contact: r.linear_contact,
            passage_equivalents: (r.passages * r.cells) as f64,
            cpu_seconds: r.cpu_seconds,
            wall_seconds: r.wall_seconds,
            warnings: r.warnings,
            resonances: r.resonances,
        })
    }

    /// The supercell's length `M L` (m).
    pub fn supercell(&self) -> f64 {
        self.stretch * self.cells as f64
    }

    /// Mode `k`'s class.
    pub fn class_of(&self, k: usize) -> &Class {
        &self.classes[self.modes[k].class]
    }

    /// Mode `k`'s wavelength (m): its largest harmonic's.
    pub fn wavelength(&self, k: usize) -> f64 {
        let h = self.class_of(k).basis[self.modes[k].dominant].index;
        self.supercell() / h.unsigned_abs() as f64
    }

    /// The support intervals along the stretch (m from its start: each
    /// support and the next, the last ending at the first's next image).
    fn spans(&self) -> Vec<(f64, f64)> {
        let ends = self.supports.iter().skip(1).copied().chain(self.supports.first().map(|x| x + self.stretch));
        self.supports.iter().copied().zip(ends).collect()
    }

    /// Mode `k`'s envelope over the supports against mid-span: its mean at
    /// the supports over its mean at the spans' middles (one bay with a
    /// support at the stretch's start: over the sleeper against mid-span;
    /// on a continuous track: at the stretch's start over its middle).
    pub fn support_ratio(&self, k: usize) -> f64 {
        let spans = if self.supports.is_empty() { vec![(0.0, self.stretch)] } else { self.spans() };
        let at: Vec<f64> = spans.iter().map(|s| s.0).chain(spans.iter().map(|s| 0.5 * (s.0 + s.1))).collect();
        let e = self.modes[k].envelope(self.class_of(k), 0, &at, self.supercell());
        let (supports, middles) = e.split_at(spans.len());
        let middle = middles.iter().sum::<f64>();
        if middle > 0.0 { supports.iter().sum::<f64>() / middle } else { f64::NAN }
    }

    /// Where mode `k`'s pattern is deepest on the first rail, on the
    /// discrete track: the place (m from the stretch's start) and its
    /// share of its support interval (0 at the support before it, 0.5
    /// mid-span), sought at [`SPAN_POINTS`] places per interval; None on a
    /// continuous track.
    pub fn deepest(&self, k: usize) -> Option<(f64, f64)> {
        let spans = self.spans();
        let places: Vec<(f64, f64)> = spans
            .iter()
            .flat_map(|&(a, b)| {
                (0..SPAN_POINTS)
                    .map(move |i| (a + (b - a) * i as f64 / SPAN_POINTS as f64, i as f64 / SPAN_POINTS as f64))
            })
            .collect();
        let x: Vec<f64> = places.iter().map(|p| p.0).collect();
        let e = self.modes[k].envelope(self.class_of(k), 0, &x, self.supercell());
        (0..e.len()).max_by(|&a, &b| e[a].total_cmp(&e[b])).map(|i| places[i])
    }

    /// Mode `k`'s frequency at the scene's speed (Hz).
    pub fn frequency(&self, k: usize) -> f64 {
        self.speed / self.wavelength(k)
    }

    /// Mode `k`'s mean frequency at the scene's speed (Hz): its harmonics'
    /// frequencies weighted by their shares of its energy (a mode the
    /// sleepers couple holds several, `n V / L` apart).
    pub fn mean_frequency(&self, k: usize) -> f64 {
        let class = self.class_of(k);
        let m = &self.modes[k];
        let (mut weighted, mut total) = (0.0, 0.0);
        for (b, v) in class.basis.iter().zip(&m.vector) {
            let f = self.speed * b.index.unsigned_abs() as f64 / self.supercell();
            weighted += v.norm_sqr() * f;
            total += v.norm_sqr();
        }
        if total > 0.0 { weighted / total } else { self.frequency(k) }
    }

    /// The resonance nearest mode `k`'s mean frequency within
    /// `RESONANCE_BAND` of it (index into `resonances`), if any: the body
    /// and direction it is near (a frequency match, not a modal analysis of
    /// the coupled loop).
    pub fn near_resonance(&self, k: usize) -> Option<usize> {
        let f = self.mean_frequency(k);
        self.resonances
            .iter()
            .enumerate()
            .filter(|(_, (_, r))| (f / r - 1.0).abs() <= RESONANCE_BAND)
            .min_by(|a, b| (f / a.1.1).ln().abs().total_cmp(&(f / b.1.1).ln().abs()))
            .map(|(i, _)| i)
    }
}

#[cfg(test)]
mod tests {
    use super::forecast::fixture::diagonal;
    use super::*;

    /// A mode of two harmonics `n` and `n + 1` of equal amplitude on a
    /// stretch `L`: its envelope `|1 + exp(2 pi i x / L)| = 2 |cos(pi x /
    /// L)|`, deepest at 0 and nil at `L / 2`.
    fn beating(supports: Vec<f64>) -> Spectrum {
        let mut s = diagonal(1.2, &[1e-6; 20], &[Complex64::default(); 20]);
        let basis = &s.classes[0].basis;
        let at = |index: i64| basis.iter().position(|b| b.index == index).unwrap();
        let mut vector = vec![Complex64::default(); basis.len()];
        vector[at(15)] = Complex64::new(0.5f64.sqrt(), 0.0);
        vector[at(16)] = Complex64::new(0.5f64.sqrt(), 0.0);
        s.modes = vec![Mode {
            class: 0,
            eigenvalue: Complex64::new(1e-6, 0.0),
            dominant: at(15),
            dual: vector.clone(),
            vector,
        }];
        s.supports = supports;
        s
    }

    #[test]
    fn the_support_ratio_and_the_deepest_place_follow_the_supports() {
        // Supports at 0 and 0.6 m: the envelope 2 and 0 there, sqrt 2 at
        // both mid-spans: the ratio (2 + 0) / 2 over sqrt 2.
        let s = beating(vec![0.0, 0.6]);
        assert!((s.support_ratio(0) - 0.5f64.sqrt()).abs() < 1e-12, "{}", s.support_ratio(0));
        let (x, share) = s.deepest(0).unwrap();
        assert!(x.abs() < 1e-12 && share == 0.0, "{x} {share}");
        // Supports at 0.3 and 0.9 m: the envelope sqrt 2 at both, 0 and 2 at
        // the mid-spans 0.6 and 1.2 (the stretch's start again) m: deepest
        // in the middle of the second span.
        let s = beating(vec![0.3, 0.9]);
        assert!((s.support_ratio(0) - 2.0f64.sqrt()).abs() < 1e-12, "{}", s.support_ratio(0));
        let (x, share) = s.deepest(0).unwrap();
        assert!((x - 1.2).abs() < 1e-12 && share == 0.5, "{x} {share}");
        // On a continuous track: at the stretch's start over its middle,
        // and no supports to be deepest between.
        let s = beating(Vec::new());
        assert!(s.support_ratio(0).is_nan() || s.support_ratio(0) > 1e6);
        assert_eq!(s.deepest(0), None);
    }
}
