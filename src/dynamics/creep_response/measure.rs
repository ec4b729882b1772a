//! The response of eq. 1 measured on a tangential solver: multi-sine runs,
//! one per input, and a reference run at the mean state.

use super::{CreepResponse, CreepResponseError, Input, Longitudinal, MeanState};
use crate::contact::{Elements, StepInput, TangentialSolver};
use crate::creep_coefficients::creep_coefficients;
use crate::hertz::HertzShape;
use num_complex::Complex64;
use rayon::prelude::*;
use std::f64::consts::PI;

/// How the response is excited and measured (lengths in m, rolled
/// distance of the wheel).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Excitation {
    /// Rolled distance per step, `V dt` (m); on the fixed grid its element
    /// length `dx` is taken instead (the grid moves one element per step).
    pub step: f64,
    /// Length of the measured period `L` (m), rounded to whole steps: the
    /// harmonics are `k_n = 2 pi n / L`, spaced `2 pi a0 / L` in reduced
    /// frequency.
    pub period: f64,
    /// Largest reduced frequency `w a0 / V` excited (1): the harmonics
    /// `n = 1 ..= floor(max_reduced L / (2 pi a0))`.
    pub max_reduced: f64,
    /// Run-in at the mean state before the excitation starts (m).
    pub run_in: f64,
    /// Excitation before the measured period (m): the response to the
    /// switched-on excitation settles over it.
    pub lead: f64,
    /// Amplitude of each harmonic and of the offset, relative to the
    /// input's scale [`input_scale`] (1).
    pub level: f64,
    /// The inputs measured (the others' columns are left zero).
    pub inputs: [bool; 4],
}

/// The scale of each input's excitation: for the creepages and the spin
/// the value at which the linear theory's force reaches the friction limit
/// (`mu N0 / (G a0 b0 C11)`, `mu N0 / (G a0 b0 C22)`, `mu N0 / (G (a0
/// b0)^(3/2) C23)`, Kalker's coefficients of the patch), for the normal
/// force `N0`.
pub fn input_scale(shape: &HertzShape, mean: &MeanState) -> Result<[f64; 4], CreepResponseError> {
    let p = shape.patch(mean.normal_force).map_err(|e| CreepResponseError::Input(format!("mean normal force: {e}")))?;
    let el = shape.elastic();
    let c =
        creep_coefficients(shape.aspect(), el.poisson_ratio).map_err(|e| CreepResponseError::Input(e.to_string()))?;
    let (g, limit, ab) = (el.shear_modulus(), mean.friction * mean.normal_force, p.a * p.b);
    Ok([limit / (g * ab * c.c11), limit / (g * ab * c.c22), limit / (g * ab.powf(1.5) * c.c23), mean.normal_force])
}

/// One run's recorded forces over the measured period, and the mean
/// creepage it ran at.
struct Run {
    fx: Vec<f64>,
    fy: Vec<f64>,
    creepage_x: f64,
}

/// What every run shares.
struct Plan<'a> {
    shape: &'a HertzShape,
    mean: &'a MeanState,
    step: f64,
    run_in: usize,
    lead: usize,
    period: usize,
    /// Wavenumbers (1/m) and Schroeder phases (rad) of the harmonics.
    harmonics: Vec<(f64, f64)>,
    /// Per-harmonic amplitude of each input (units of the input).
    amplitude: [f64; 4],
}

impl Plan<'_> {
    /// The multi-sine of unit amplitude per harmonic plus a unit offset at
    /// `x` (m) from the start of the measured period.
    fn signal(&self, x: f64) -> f64 {
        1.0 + self.harmonics.iter().map(|(k, phase)| (k * x + phase).cos()).sum::<f64>()
    }

    /// Runs the solver with `input` excited (`None`: the reference run).
    fn run(&self, solver: &mut dyn TangentialSolver, input: Option<Input>) -> Result<Run, CreepResponseError> {
        let name = input.map_or("reference", Input::name);
        let m = self.mean;
        let dt = self.step / m.speed;
        solver.reset();
        solver.set_surface(None).map_err(|source| CreepResponseError::Contact { input: name, step: 0, source })?;
        let total = self.run_in + self.lead + self.period;
        let mut creepage_x = match m.longitudinal {
            Longitudinal::Creepage(xi) => xi,
            Longitudinal::Force(_) => f64::NAN,
        };
        let mut out = Run { fx: Vec::with_capacity(self.period), fy: Vec::with_capacity(self.period), creepage_x };
        let step_input = |n: usize, creepage_x: f64| -> Result<StepInput, CreepResponseError> {
            let excited = n >= self.run_in;
            // Position relative to the start of the measured period.
            let x = (n as f64 - (self.run_in + self.lead) as f64) * self.step;
            let delta = |which: Input| {
                if excited && input == Some(which) { self.amplitude[which.index()] * self.signal(x) } else { 0.0 }
            };
            let normal_force = m.normal_force + delta(Input::NormalForce);
            let patch = self.shape.patch(normal_force).map_err(|source| CreepResponseError::Normal {
                input: name,
                step: n,
                source,
            })?;
            let (force_x, creepage) = match (excited, m.longitudinal) {
                (false, Longitudinal::Force(f)) => (f, None),
                (_, Longitudinal::Force(f)) => (f, Some(creepage_x + delta(Input::CreepageX))),
                (_, Longitudinal::Creepage(xi)) => (0.0, Some(xi + delta(Input::CreepageX))),
            };
            Ok(StepInput {
                patch,
                speed: m.speed,
                dt,
                friction: m.friction,
                force_x,
                creepage_x: creepage,
                creepage_y: m.creepage_y + delta(Input::CreepageY),
                spin: m.spin + delta(Input::Spin),
                position: n as f64 * self.step,
            })
        };
        for n in 0..total {
            let this = step_input(n, creepage_x)?;
            // The next step's input, where it does not depend on this one's
            // answer (the creepage found by the last step of the run-in).
            let next = (n + 1 < total && n + 1 != self.run_in).then(|| step_input(n + 1, creepage_x)).transpose()?;
            let sol = solver.step_ahead(&this, next.as_ref()).map_err(|source| CreepResponseError::Contact {
                input: name,
                step: n,
                source,
            })?;
            if !(sol.force_x.is_finite() && sol.force_y.is_finite() && sol.creepage.x.is_finite()) {
                return Err(CreepResponseError::NonFinite { input: name, step: n });
            }
            if n + 1 == self.run_in {
                creepage_x = sol.creepage.x;
                out.creepage_x = creepage_x;
            }
            if n >= self.run_in + self.lead {
                out.fx.push(sol.force_x);
                out.fy.push(sol.force_y);
            }
        }
        Ok(out)
    }
}

/// Measures the response of eq. 1 on the solvers `make_solver` builds
/// (one per run; the runs go in parallel), for the Hertz contact `shape`
/// about `mean`, excited as `excitation` says.
///
/// Each measured input's run: `run_in` at the mean state (the mean
/// longitudinal force prescribed where it is given, the creepage found by
/// its last step then held), then the input's multi-sine, per harmonic and
/// offset `level` times [`input_scale`], for `lead` and one measured period
/// `L`. The reference run is the same without the multi-sine. With `dF_j`
/// the forces of a run less the reference's over the measured period
/// (steps `x_j = j h`, `j < P`, `L = P h`):
///
/// ```text
/// H_i,input(w_n) = (2/P) sum_j dF_i,j exp(-i k_n x_j) / (A exp(i phi_n)),   w_n = k_n V,
/// H_i,input(0)   = (1/P) sum_j dF_i,j / A,
/// ```
///
/// `A` the amplitude, `phi_n = -pi n (n - 1) / M` Schroeder's phases of the
/// `M` harmonics.
pub fn measure(
    make_solver: &(dyn Fn() -> Box<dyn TangentialSolver> + Sync),
    shape: &HertzShape,
    mean: &MeanState,
    excitation: &Excitation,
) -> Result<CreepResponse, CreepResponseError> {
    let e = excitation;
    let m = mean;
    let positive = |v: f64| v.is_finite() && v > 0.0;
    for (what, v) in [
        ("mean normal force", m.normal_force),
        ("speed", m.speed),
        ("friction", m.friction),
        ("step", e.step),
        ("period", e.period),
        ("max_reduced", e.max_reduced),
        ("level", e.level),
    ] {
        if !positive(v) {
            return Err(CreepResponseError::Input(format!("{what} = {v} must be finite and > 0")));
        }
    }
    for (what, v) in [("run_in", e.run_in), ("lead", e.lead), ("creepage_y", m.creepage_y), ("spin", m.spin)] {
        if !v.is_finite() || (what != "creepage_y" && what != "spin" && v < 0.0) {
            return Err(CreepResponseError::Input(format!(
                "{what} = {v} must be finite{}",
                if v < 0.0 { " and >= 0" } else { "" }
            )));
        }
    }
    match m.longitudinal {
        Longitudinal::Force(f) if !(f.is_finite() && f.abs() < m.friction * m.normal_force) => {
            return Err(CreepResponseError::Input(format!(
                "mean longitudinal force {f} N must be finite and below mu N0 = {} N",
                m.friction * m.normal_force
            )));
        }
        Longitudinal::Creepage(xi) if !xi.is_finite() => {
            return Err(CreepResponseError::Input(format!("mean creepage {xi} must be finite")));
        }
        _ => {}
    }
    let a0 = shape.patch(m.normal_force).map_err(|e| CreepResponseError::Input(e.to_string()))?.a;
    let runs: Vec<Option<Input>> =
        std::iter::once(None).chain(Input::ALL.into_iter().filter(|i| e.inputs[i.index()]).map(Some)).collect();
    let mut solvers: Vec<Box<dyn TangentialSolver>> = runs.iter().map(|_| make_solver()).collect();
    let step = match solvers[0].elements() {
        Elements::Grid(g) => g.dx,
        Elements::Adapted(_) => e.step,
    };
    let period = (e.period / step).round().max(4.0) as usize;
    let length = period as f64 * step;
    let spacing = 2.0 * PI * a0 / length;
    let count = (e.max_reduced / spacing + 1e-9).floor() as usize;
    if count == 0 || 2 * count >= period {
        return Err(CreepResponseError::Input(format!(
            "{count} harmonics up to w a0 / V = {} on a period of {period} steps: need at least one and fewer than half the steps (lengthen the period or shorten the step)",
            e.max_reduced
        )));
    }
    let harmonics =
        (1..=count).map(|n| (2.0 * PI * n as f64 / length, -PI * (n * (n - 1)) as f64 / count as f64)).collect();
    let scale = input_scale(shape, m)?;
    let plan = Plan {
        shape,
        mean: m,
        step,
        run_in: (e.run_in / step).ceil() as usize,
        lead: (e.lead / step).ceil() as usize,
        period,
        harmonics,
        amplitude: scale.map(|s| s * e.level),
    };
    let results: Vec<Run> = runs
        .par_iter()
        .zip(solvers.par_iter_mut())
        .map(|(&input, solver)| plan.run(solver.as_mut(), input))
        .collect::<Result<_, _>>()?;
    let reference = &results[0];
    let mut table = vec![[[Complex64::new(0.0, 0.0); 4]; 2]; count + 1];
    for (input, run) in runs.iter().zip(&results).skip(1) {
        let input = input.expect("measured runs have an input");
        let a = plan.amplitude[input.index()];
        let rows = [
            run.fx.iter().zip(&reference.fx).map(|(f, r)| f - r).collect::<Vec<f64>>(),
            run.fy.iter().zip(&reference.fy).map(|(f, r)| f - r).collect::<Vec<f64>>(),
        ];
        for (r, d) in rows.iter().enumerate() {
            table[0][r][input.index()] = Complex64::new(d.iter().sum::<f64>() / (period as f64 * a), 0.0);
            for (n, (k, phase)) in plan.harmonics.iter().enumerate() {
                let c: Complex64 = d
                    .iter()
                    .enumerate()
                    .map(|(j, v)| v * Complex64::from_polar(1.0, -k * j as f64 * step))
                    .sum::<Complex64>()
                    * (2.0 / period as f64);
                table[n + 1][r][input.index()] = c / Complex64::from_polar(a, *phase);
            }
        }
    }
    let last = |v: &[f64]| *v.last().expect("a measured period has steps");
    Ok(CreepResponse {
        speed: m.speed,
        semi_axis: a0,
        creepage_x: reference.creepage_x,
        force: [last(&reference.fx), last(&reference.fy)],
        reduced: (0..=count).map(|n| n as f64 * spacing).collect(),
        table,
        measured: e.inputs,
    })
}
