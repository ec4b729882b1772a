//! Automatic choice of the tangential contact model and mesh
//! (`contact.model = "auto"`): the cheapest (model, mesh) whose measured wear
//! error at the scene's shortest wavelength is within `contact.tolerance`.
//!
//! The map ([`AccuracyMap::builtin`], `accuracy_map.csv` next to this file,
//! made by `scripts/accuracy_map.sh`) holds, per model and mesh, the relative
//! L2 error of the centre-line wear profile against the converged exact
//! transient solution (Richardson extrapolation of 20 x 20 and 28 x 28) and
//! the CPU time per contact step (the exact model's Gauss-Seidel solver on
//! the adapted mesh, its CG solver on the fixed grid),
//! at load wavelengths of 10 ... 60 mm, `lambda / 2a_max` from 0.74 to 4.45
//! (paper_normal_30mm: N = 100 kN +/- 45 kN, F_x = 20 kN, eps = 1e-5 m/s,
//! V dt = 0.2 mm).
//!
//! Prediction: the error and cost at the scene's `lambda / 2a_max` are
//! interpolated linearly in `ln(lambda / 2a)` between measured wavelengths.
//! Above the measured range the values at its top are used (errors fall as
//! lambda / 2a grows: the contact forgets faster than the load changes);
//! below it the scene is outside the map and "auto" is refused. A candidate
//! counts as meeting the tolerance when its predicted error is within
//! [`SAFETY`] of it, a margin for the interpolation and for scenes that
//! differ from the map's.

pub mod hertz_validity;

use crate::params::Candidate;
use crate::params::ContactModelKind;
use std::sync::OnceLock;

/// A candidate meets a tolerance T when its predicted error is <= SAFETY T.
pub const SAFETY: f64 = 0.9;

/// Map name of the exact-transient model on the fixed grid, whose `mesh`
/// is the element length in um (dy = 2.5 dx, the step the element).
pub const FIXED_GRID: &str = "exact-fixed";

/// Element width over length of the fixed grids of the map.
pub const FIXED_ASPECT: f64 = 2.5;

/// One measured point of the map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapPoint {
    /// Contact model.
    pub model: ContactModelKind,
    /// The exact model on the fixed grid (`mesh` is then its element length
    /// in um).
    pub fixed: bool,
    /// Elements per side (mesh n x n), or the fixed grid's element length (um).
    pub mesh: usize,
    /// lambda / 2a_max (1).
    pub lambda_over_2a: f64,
    /// Relative L2 error of the centre-line wear profile (1).
    pub wear_error: f64,
    /// CPU time per 0.2 mm rolled (s; a step of the adapted mesh's
    /// configs), on the machine that made the map.
    pub cpu_per_step: f64,
}

/// The measured accuracy map.
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracyMap {
    points: Vec<MapPoint>,
}

/// What "auto" chose, and the alternatives it weighed.
#[derive(Debug, Clone, PartialEq)]
pub struct Choice {
    /// The cheapest candidate within the tolerance.
    pub chosen: Candidate,
    /// The cheapest exact-transient mesh within the tolerance (the model
    /// the choice must never be slower than), if the map has one.
    pub exact: Option<Candidate>,
    /// lambda / 2a_max of the scene (infinite without a wavelength).
    pub lambda_over_2a: f64,
    /// The tolerance asked for.
    pub tolerance: f64,
    /// Every candidate, cheapest first.
    pub candidates: Vec<Candidate>,
}

/// Why no choice could be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChoiceError {
    /// The scene's wavelength is shorter than the map covers.
    #[error("lambda / 2a_max = {lambda_over_2a:.3} is below the measured map (>= {min:.3})")]
    OutsideMap {
        /// The scene's ratio.
        lambda_over_2a: f64,
        /// The smallest measured ratio.
        min: f64,
    },
    /// No model and mesh of the map is predicted to meet the tolerance.
    #[error(
        "no model meets {tolerance}: the most accurate, {label}, is predicted at {best:.4} \
         (a tolerance must be >= the predicted error / {SAFETY})"
    )]
    Unreachable {
        /// The tolerance asked for.
        tolerance: f64,
        /// The smallest predicted error.
        best: f64,
        /// Its model and mesh ([`Candidate::label`]).
        label: String,
    },
}

impl AccuracyMap {
    /// The map compiled into the program.
    pub fn builtin() -> &'static AccuracyMap {
        static MAP: OnceLock<AccuracyMap> = OnceLock::new();
        MAP.get_or_init(|| AccuracyMap::parse(include_str!("accuracy_map.csv")).expect("the built-in map parses"))
    }

    /// Parses the CSV of `corrugation_post accuracy-map` (columns model,
    /// mesh, wavelength, lambda_over_2a, wear_error, cpu_per_step).
    pub fn parse(text: &str) -> Result<AccuracyMap, String> {
        let mut lines = text.lines().filter(|l| !l.trim().is_empty());
        let header: Vec<&str> = lines.next().ok_or("empty map")?.split(',').map(str::trim).collect();
        let col = |name: &str| header.iter().position(|h| *h == name).ok_or(format!("map has no column {name}"));
        let (m, n, r, e, c) =
            (col("model")?, col("mesh")?, col("lambda_over_2a")?, col("wear_error")?, col("cpu_per_step")?);
        let mut points = Vec::new();
        for (i, line) in lines.enumerate() {
            let f: Vec<&str> = line.split(',').map(str::trim).collect();
            let bad = |what: &str| format!("map line {}: bad {what}", i + 2);
            let number = |k: usize, what: &str| {
                f.get(k).and_then(|v| v.parse::<f64>().ok()).filter(|v| v.is_finite() && *v >= 0.0).ok_or(bad(what))
            };
            let name = f.get(m).ok_or(bad("model"))?;
            let fixed = *name == FIXED_GRID;
            let model = if fixed {
                ContactModelKind::ExactTransient
            } else {
                ContactModelKind::ALL.into_iter().find(|k| k.name() == *name).ok_or(bad("model"))?
            };
            points.push(MapPoint {
                model,
                fixed,
                mesh: f.get(n).and_then(|v| v.parse().ok()).ok_or(bad("mesh"))?,
                lambda_over_2a: number(r, "lambda_over_2a")?,
                wear_error: number(e, "wear_error")?,
                cpu_per_step: number(c, "cpu_per_step")?,
            });
        }
        if points.is_empty() {
            return Err("map has no points".into());
        }
        Ok(AccuracyMap { points })
    }

    /// The measured points.
    pub fn points(&self) -> &[MapPoint] {
        &self.points
    }

    /// Smallest and largest measured lambda / 2a.
    pub fn range(&self) -> (f64, f64) {
        let r = self.points.iter().map(|p| p.lambda_over_2a);
        (r.clone().fold(f64::INFINITY, f64::min), r.fold(0.0, f64::max))
    }

    /// Predicted error and cost of (model, mesh) at `lambda_over_2a`, or
    /// None when the map does not hold that pair or the ratio is below it.
    pub fn predict(&self, model: ContactModelKind, fixed: bool, mesh: usize, lambda_over_2a: f64) -> Option<Candidate> {
        let mut pts: Vec<&MapPoint> =
            self.points.iter().filter(|p| p.model == model && p.fixed == fixed && p.mesh == mesh).collect();
        pts.sort_by(|a, b| a.lambda_over_2a.total_cmp(&b.lambda_over_2a));
        let (first, last) = (pts.first()?, pts.last()?);
        let at =
            |p: &MapPoint| Candidate { model, fixed, mesh, wear_error: p.wear_error, cpu_per_step: p.cpu_per_step };
        if lambda_over_2a < first.lambda_over_2a * (1.0 - 1e-9) {
            return None;
        }
        if lambda_over_2a >= last.lambda_over_2a {
            return Some(at(last));
        }
        let i = pts.windows(2).position(|w| lambda_over_2a <= w[1].lambda_over_2a)?;
        let (a, b) = (pts[i], pts[i + 1]);
        let t = ((lambda_over_2a / a.lambda_over_2a).ln() / (b.lambda_over_2a / a.lambda_over_2a).ln()).clamp(0.0, 1.0);
        let lerp = |x: f64, y: f64| x + t * (y - x);
        Some(Candidate {
            model,
            fixed,
            mesh,
            wear_error: lerp(a.wear_error, b.wear_error),
            cpu_per_step: lerp(a.cpu_per_step, b.cpu_per_step),
        })
    }

    /// Every (model, mesh) of the map predicted at `lambda_over_2a`,
    /// cheapest first.
    pub fn candidates(&self, lambda_over_2a: f64) -> Vec<Candidate> {
        let mut keys: Vec<(ContactModelKind, bool, usize)> =
            self.points.iter().map(|p| (p.model, p.fixed, p.mesh)).collect();
        keys.sort_by_key(|(m, f, n)| (m.name(), *f, *n));
        keys.dedup();
        let mut out: Vec<Candidate> =
            keys.into_iter().filter_map(|(m, f, n)| self.predict(m, f, n, lambda_over_2a)).collect();
        out.sort_by(|a, b| a.cpu_per_step.total_cmp(&b.cpu_per_step).then(a.wear_error.total_cmp(&b.wear_error)));
        out
    }

    /// The cheapest (model, mesh) predicted within [`SAFETY`] `tolerance`
    /// (relative wear error) at `lambda_over_2a` (infinite: no wavelength, the
    /// top of the map).
    pub fn choose(&self, lambda_over_2a: f64, tolerance: f64) -> Result<Choice, ChoiceError> {
        let (min, _) = self.range();
        let candidates = self.candidates(lambda_over_2a);
        if candidates.is_empty() {
            return Err(ChoiceError::OutsideMap { lambda_over_2a, min });
        }
        let meets = |c: &&Candidate| c.wear_error <= SAFETY * tolerance;
        let Some(chosen) = candidates.iter().find(meets).copied() else {
            let best = candidates.iter().min_by(|a, b| a.wear_error.total_cmp(&b.wear_error)).expect("not empty");
            return Err(ChoiceError::Unreachable { tolerance, best: best.wear_error, label: best.label() });
        };
        let exact = candidates.iter().filter(|c| c.model == ContactModelKind::ExactTransient).find(meets).copied();
        Ok(Choice { chosen, exact, lambda_over_2a, tolerance, candidates })
    }
}

#[cfg(test)]
mod tests;

/// Where a scene leaves the conditions the map was measured in (the
/// prediction is then an extrapolation): one line per departure.
pub fn departures(scene: &crate::params::Scene) -> Vec<String> {
    let mut notes = Vec::new();
    let eps = scene.contact.regularisation;
    if !(1e-6..=1e-4).contains(&eps) {
        notes.push(format!("contact.regularisation = {eps:e} m/s (map: 1e-5; wear moves ~10 % per decade above 1e-4)"));
    }
    let adapted = scene.contact.model.fixed_grid().is_none();
    if adapted && !(1.3e-4..=3e-4).contains(&scene.step_length) {
        notes.push(format!("passage.step_length = {:e} m (map: 2e-4; the error grows with V dt)", scene.step_length));
    }
    let l = &scene.loads;
    let amplitude = (l.max_normal_force() - l.min_normal_force()) / (2.0 * l.normal_force);
    if amplitude > 0.6 {
        notes.push(format!("normal-force amplitude {amplitude:.2} of the mean (map: 0.45)"));
    }
    let ratio = l.max_longitudinal_force() / (scene.material.friction * l.min_normal_force());
    if ratio > 0.95 {
        notes.push(format!("F_x / (mu N_min) = {ratio:.2} (map: 0.91)"));
    }
    if scene.growth.as_ref().is_some_and(|g| g.dynamics != crate::params::DynamicsKind::Imposed) {
        notes.push(
            "track dynamics: the dynamic normal force is not known before the run; lambda / 2a_max uses the \
             imposed loads only"
                .into(),
        );
    }
    notes
}
