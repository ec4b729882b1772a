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
//! Here `J` is measured on the passage's own model chain ([`WearMap`]:
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
pub mod modes;

use crate::build::{DynamicsError, study_grid};
use crate::growth::wear_map::WearMap;
use crate::growth::{contact_filtered_line, mean_patch};
use crate::params::Scene;
use crate::passage::PassageError;
use bloch::{Class, Harmonic, Slot};
use modes::Mode;
use ndarray::Array2;
use num_complex::Complex64;
use rustfft::FftPlanner;

/// How the linearisation is differenced (`spectrum.difference`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, strum::EnumString, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "lowercase")]
pub enum Difference {
    /// `(W(r0 + eps d) - W(r0 - eps d)) / 2 eps`: two passages per round.
    Central,
    /// `(W(r0 + eps d) - W(r0)) / eps`: one passage per round.
    Forward,
}

/// The rail the passage is linearised about (`spectrum.base`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Base {
    /// The smooth rail: `J` about `r = 0`, `W(0)` the forced pattern.
    Smooth,
    /// The study's initial roughness (`[roughness]`: harmonics, random,
    /// levels or a measured record).
    Roughness,
}

/// What the spectrum measures (`[spectrum]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectrumParams {
    /// Shortest wavelength perturbed (m).
    pub wavelength_min: f64,
    /// Longest wavelength perturbed (m).
    pub wavelength_max: f64,
    /// Bloch classes `M`: the supercell's stretches (1: the stretch's own
    /// harmonics).
    pub classes: usize,
    /// Amplitude of each perturbation (m).
    pub perturbation: f64,
    /// The differences.
    pub difference: Difference,
    /// The rail it is linearised about.
    pub base: Base,
}

impl Default for SpectrumParams {
    fn default() -> Self {
        SpectrumParams {
            wavelength_min: 0.010,
            wavelength_max: 0.150,
            classes: 1,
            perturbation: DEFAULT_PERTURBATION,
            difference: Difference::Central,
            base: Base::Smooth,
        }
    }
}

/// Default `spectrum.perturbation` (m): 10 nm. On growth_exact.toml's
/// chain the central differences at 1 and 10 nm agree within 0.003 dB per
/// 1e5 at 10-60 mm; at 0.1 um the contact's third-order response moves the
/// 10 mm rate by 0.027 (docs/src/theory/growth-spectrum.md).
pub const DEFAULT_PERTURBATION: f64 = 1e-8;

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
    /// The wear of one wheel passage over the base rail, the same way (m).
    pub base_wear: Vec<Vec<f64>>,
    /// The mean depth of the smooth rail's contact-filtered wear per wheel
    /// passage on each rail (m): the scale the forced pattern is small or
    /// large against.
    pub mean_wear: Vec<f64>,
    /// Positions along the stretch of the modes' envelopes (m from its start).
    pub positions: Vec<f64>,
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
}

/// The scene over a supercell of `cells` of its stretches: the rail grid
/// and the passage `cells - 1` stretches longer, everything else the same
/// (the stretch repeats, so its dynamics and contact do).
pub fn supercell(scene: &Scene, cells: usize) -> Scene {
    let mut s = scene.clone();
    let length = scene.rail.x_max - scene.rail.x_min;
    s.rail.x_max = scene.rail.x_min + cells as f64 * length;
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
    let cell = study_grid(scene);
    let nodes = cell.nx * params.classes;
    let length = nodes as f64 * cell.dx;
    let (low, high) = band(params, nodes, length)?;
    let classes = bloch::classes(params.classes, low, high, rails);
    let rounds = bloch::rounds(&bloch::slots(&classes)).len();
    let per_round = if params.difference == Difference::Central { 2 } else { 1 };
    let traffic = scene.growth.as_ref().map_or(1, |g| g.classes.len().max(1));
    let smooth = usize::from(params.base != Base::Smooth);
    let passages = traffic * (1 + smooth + per_round * rounds);
    Some(Plan {
        supercell: length,
        classes: classes.iter().map(|c| (c.j, c.basis.len())).collect(),
        rounds,
        passages,
        passage_equivalents: passages * params.classes,
    })
}

/// The growth spectrum of `scene` (a growth study's scene: its contact,
/// dynamics, traffic) about the rails `base` (m, on the study's grid; the
/// first rail's, then the second's), as `params` ask.
pub fn linear_spectrum(
    scene: &Scene,
    base: &[Array2<f64>],
    params: &SpectrumParams,
    progress: &mut dyn FnMut(Progress),
) -> Result<Spectrum, SpectrumError> {
    let clock = cpu_time::ProcessTime::now();
    let wall = std::time::Instant::now();
    let cell = study_grid(scene);
    let stretch = cell.nx as f64 * cell.dx;
    let cells = params.classes;
    let big = supercell(scene, cells);
    let classes_traffic = scene.growth.as_ref().map(|g| g.classes.clone()).unwrap_or_default();
    let mut map = WearMap::new(&big, &classes_traffic)?;
    let grid = map.grid().clone();
    let nodes = grid.nx;
    let length = nodes as f64 * grid.dx;
    let rails = base.len();
    let (low, high) = band(params, nodes, length).ok_or(SpectrumError::EmptyBand {
        min: params.wavelength_min,
        max: params.wavelength_max,
        length,
        shortest: 2.0 * length / nodes as f64,
    })?;
    let classes = bloch::classes(cells, low, high, rails);
    let plan = bloch::slots(&classes);
    let rounds = bloch::rounds(&plan);
    // The base rails over the supercell.
    let tiled: Vec<Array2<f64>> =
        base.iter().map(|b| Array2::from_shape_fn((grid.ny, nodes), |(j, i)| b[[j, i % cell.nx]])).collect();
    let smooth = tiled.iter().all(|b| b.iter().all(|v| *v == 0.0));
    let b = mean_patch(scene, &map.derived().shape).1;
    let filtered = |w: &Array2<f64>| contact_filtered_line(w, &grid, b);
    let fft = FftPlanner::new().plan_fft_forward(nodes);
    let dft = |line: &[f64]| {
        let mut buf: Vec<Complex64> = line.iter().map(|v| Complex64::new(*v, 0.0)).collect();
        fft.process(&mut buf);
        buf
    };
    let per_round = match params.difference {
        Difference::Central => 2,
        Difference::Forward => 1,
    };
    let shares: Vec<f64> =
        if classes_traffic.is_empty() { vec![1.0] } else { classes_traffic.iter().map(|c| c.share).collect() };
    let extra = usize::from(!smooth);
    let total = shares.len() * (1 + extra + per_round * rounds.len());
    let mut done = 0;
    let mut step = |done: &mut usize| {
        *done += 1;
        progress(Progress { done: *done, total });
    };
    let mut matrices: Vec<Vec<Complex64>> =
        classes.iter().map(|c| vec![Complex64::default(); c.basis.len().pow(2)]).collect();
    let cell_harmonics = cell.nx / 2;
    let mut forced = vec![vec![Complex64::default(); cell_harmonics]; rails];
    let mut mean_wear = vec![0.0; rails];
    let mut base_wear = vec![vec![Complex64::default(); cell_harmonics]; rails];
    let mut warnings = Vec::new();
    let mut linear_contact = false;
    let on_cell = |coefficients: &[Complex64], into: &mut [Complex64], share: f64| {
        // The stretch's harmonic n is the supercell's n M.
        for (n, v) in into.iter_mut().enumerate() {
            *v += share * bloch::coefficient(coefficients, ((n + 1) * cells) as i64);
        }
    };
    for (c, share) in shares.iter().enumerate() {
        let fail = |what: String| move |source| SpectrumError::Passage { what, source };
        let refs: Vec<&Array2<f64>> = tiled.iter().collect();
        // The base passage: its wear, and which normal contact it took
        // (every perturbed passage takes the same).
        let g = map.passage(c, &refs, false, &mut |_, _| {}).map_err(fail("the base rail's passage".into()))?;
        step(&mut done);
        linear_contact = g.linear_contact;
        map.pin_normal(g.linear_contact);
        let base_lines: Vec<Vec<f64>> = g.rails.iter().map(|r| filtered(&r.wear)).collect();
        for (r, line) in base_lines.iter().enumerate() {
            on_cell(&dft(line), &mut base_wear[r], *share);
        }
        let smooth_lines = if smooth {
            base_lines.clone()
        } else {
            let zero = Array2::zeros((grid.ny, nodes));
            let z: Vec<&Array2<f64>> = vec![&zero; rails];
            let g = map.passage(c, &z, false, &mut |_, _| {}).map_err(fail("the smooth rail's passage".into()))?;
            step(&mut done);
            g.rails.iter().map(|r| filtered(&r.wear)).collect()
        };
        for (r, line) in smooth_lines.iter().enumerate() {
            let spectrum = dft(line);
            on_cell(&spectrum, &mut forced[r], *share);
            mean_wear[r] += share * bloch::coefficient(&spectrum, 0).re;
        }
        // Each round's responses, per class and slot: the coefficients of
        // the class's basis.
        let mut responses: Vec<Vec<Vec<Complex64>>> = plan.iter().map(|s| vec![Vec::new(); s.len()]).collect();
        for (t, round) in rounds.iter().enumerate() {
            let perturbed = |sign: f64| -> Vec<Array2<f64>> {
                tiled
                    .iter()
                    .enumerate()
                    .map(|(r, b)| {
                        let d = bloch::perturbation(round, r, nodes, sign * params.perturbation);
                        Array2::from_shape_fn((grid.ny, nodes), |(j, i)| b[[j, i]] + d[i])
                    })
                    .collect()
            };
            let mut run = |profiles: Vec<Array2<f64>>, what: String| -> Result<Vec<Vec<f64>>, SpectrumError> {
                let refs: Vec<&Array2<f64>> = profiles.iter().collect();
                let g = map.passage(c, &refs, false, &mut |_, _| {}).map_err(fail(what.clone()))?;
                step(&mut done);
                if g.linear_contact != linear_contact || g.rerun.is_some() {
                    warnings.push(format!("{what} took another normal contact than the base rail's"));
                }
                for (r, rail) in g.rails.iter().enumerate() {
                    if rail.clipped_steps > 0 || rail.contact_loss_steps > 0 {
                        warnings.push(format!(
                            "{what}: rail {r} left the linear range ({} steps with the patch opened inside, {} without \
                             contact): lower spectrum.perturbation",
                            rail.clipped_steps, rail.contact_loss_steps
                        ));
                    }
                }
                Ok(g.rails.iter().map(|r| filtered(&r.wear)).collect())
            };
            let plus = run(perturbed(1.0), format!("round {} of {}, +", t + 1, rounds.len()))?;
            let lines: Vec<Vec<f64>> = match params.difference {
                Difference::Central => {
                    let minus = run(perturbed(-1.0), format!("round {} of {}, -", t + 1, rounds.len()))?;
                    plus.iter()
                        .zip(&minus)
                        .map(|(p, m)| p.iter().zip(m).map(|(a, b)| 0.5 * (a - b)).collect())
                        .collect()
                }
                Difference::Forward => {
                    plus.iter().zip(&base_lines).map(|(p, m)| p.iter().zip(m).map(|(a, b)| a - b).collect()).collect()
                }
            };
            let spectra: Vec<Vec<Complex64>> = lines.iter().map(|l| dft(l)).collect();
            for slot in round {
                let class = &classes[slot.class];
                responses[slot.class][t] =
                    class.basis.iter().map(|h: &Harmonic| bloch::coefficient(&spectra[h.rail], h.index)).collect();
            }
        }
        let found = bloch::assemble(&classes, &plan, params.perturbation, |slot: &Slot, target: &Harmonic| {
            let class = &classes[slot.class];
            let k = plan[slot.class].iter().position(|s| s == slot).expect("the slot is in its class's plan");
            let row = class.basis.iter().position(|h| h == target).expect("the target is in its class's basis");
            responses[slot.class][k][row]
        });
        for (total, part) in matrices.iter_mut().zip(found) {
            total.iter_mut().zip(part).for_each(|(t, p)| *t += share * p);
        }
    }
    let modes = modes::modes(&classes, &matrices)?;
    let amplitude = |v: &Vec<Complex64>| v.iter().map(|c| 2.0 * c.norm()).collect::<Vec<f64>>();
    let points = cell.nx.min(ENVELOPE_POINTS);
    Ok(Spectrum {
        stretch,
        cells,
        speed: scene.speed,
        classes,
        matrices,
        modes,
        wavelengths: crate::growth::spectrum::wavelengths(cell.nx, cell.dx),
        forced_wear: forced.iter().map(amplitude).collect(),
        base_wear: base_wear.iter().map(amplitude).collect(),
        mean_wear,
        positions: (0..points).map(|k| stretch * k as f64 / points as f64).collect(),
        rails,
        linear_contact,
        passage_equivalents: (done * cells) as f64,
        cpu_seconds: clock.elapsed().as_secs_f64(),
        wall_seconds: wall.elapsed().as_secs_f64(),
        warnings,
    })
}

/// Points along the stretch at which a mode's envelope is given.
pub const ENVELOPE_POINTS: usize = 120;

impl Spectrum {
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

    /// Mode `k`'s frequency at the scene's speed (Hz).
    pub fn frequency(&self, k: usize) -> f64 {
        self.speed / self.wavelength(k)
    }
}
