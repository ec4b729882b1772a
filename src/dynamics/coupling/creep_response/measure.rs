//! The response of eq. 1 measured on a tangential solver: a pair of
//! multi-sine runs of opposite sign per input.

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
    /// `n = 1 ..= M = floor(max_reduced L / (2 pi a0))`.
    pub max_reduced: f64,
    /// Run-in at the mean state before the excitation starts (m).
    pub run_in: f64,
    /// Excitation before the measured period (m): the response to the
    /// switched-on excitation settles over it.
    pub lead: f64,
    /// Root mean square of each input's multi-sine relative to the input's
    /// scale [`input_scale`] (1), per [`Input`]: each harmonic's amplitude
    /// is `level scale sqrt(2 / M)`, the offset `level scale`.
    pub level: [f64; 4],
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
    /// Forces at the end of the run-in (N).
    mean_force: [f64; 2],
}

/// One run: which input is excited with which sign (`None`: every input
/// offset by its `offset`, no harmonics, for [`steady_forces`]).
#[derive(Debug, Clone, Copy)]
struct Drive {
    input: Option<Input>,
    sign: f64,
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
    /// Offset of each input (units of the input).
    offset: [f64; 4],
}

impl Plan<'_> {
    /// The input `which`'s variation at `x` (m from the start of the
    /// measured period) in the run `drive`.
    fn delta(&self, drive: Drive, which: Input, x: f64) -> f64 {
        let i = which.index();
        match drive.input {
            None => self.offset[i],
            Some(input) if input == which => {
                let sines: f64 = self.harmonics.iter().map(|(k, phase)| (k * x + phase).cos()).sum();
                drive.sign * (self.offset[i] + self.amplitude[i] * sines)
            }
            Some(_) => 0.0,
        }
    }

    /// Runs the solver as `drive` says.
    fn run(&self, solver: &mut dyn TangentialSolver, drive: Drive) -> Result<Run, CreepResponseError> {
        let name = drive.input.map_or("steady", Input::name);
        let m = self.mean;
        let dt = self.step / m.speed;
        solver.reset();
        solver.set_surface(None).map_err(|source| CreepResponseError::Contact { input: name, step: 0, source })?;
        let total = self.run_in + self.lead + self.period;
        let mut creepage_x = match m.longitudinal {
            Longitudinal::Creepage(xi) => xi,
            Longitudinal::Force(_) => f64::NAN,
        };
        let mut out = Run {
            fx: Vec::with_capacity(self.period),
            fy: Vec::with_capacity(self.period),
            creepage_x,
            mean_force: [f64::NAN; 2],
        };
        let step_input = |n: usize, creepage_x: f64| -> Result<StepInput, CreepResponseError> {
            let excited = n >= self.run_in;
            let x = (n as f64 - (self.run_in + self.lead) as f64) * self.step;
            let delta = |which: Input| if excited { self.delta(drive, which, x) } else { 0.0 };
            let patch = self
                .shape
                .patch(m.normal_force + delta(Input::NormalForce))
                .map_err(|source| CreepResponseError::Normal { input: name, step: n, source })?;
            let (force_x, creepage) = match (excited, m.longitudinal) {
                (false, Longitudinal::Force(f)) => (f, None),
                (true, Longitudinal::Force(f)) => (f, Some(creepage_x + delta(Input::CreepageX))),
                (_, Longitudinal::Creepage(xi)) => (0.0, Some(xi + delta(Input::CreepageX))),
            };
            Ok(StepInput {
                patch,
                speed: m.speed,
                dt,
                friction: m.friction,
                characteristic: m.characteristic,
                memory: m.memory,
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
                out.mean_force = [sol.force_x, sol.force_y];
            }
            if n >= self.run_in + self.lead {
                out.fx.push(sol.force_x);
                out.fy.push(sol.force_y);
            }
        }
        Ok(out)
    }
}

/// The steady forces `(F_x, F_y)` on the wheel (N) with the inputs held
/// at `mean + offset` (`offset` in the units of [`Input`]'s columns):
/// `run_in` (m) at the mean state as in [`measure`], then `settle` (m) at
/// the offset state; the last step's forces. Central differences of these
/// are the steady Jacobian that `H(0)` must equal.
pub fn steady_forces(
    solver: &mut dyn TangentialSolver,
    shape: &HertzShape,
    mean: &MeanState,
    (step, run_in, settle): (f64, f64, f64),
    offset: [f64; 4],
) -> Result<[f64; 2], CreepResponseError> {
    let step = match solver.elements() {
        Elements::Grid(g) => g.dx,
        Elements::Adapted(_) => step,
    };
    let plan = Plan {
        shape,
        mean,
        step,
        run_in: (run_in / step).ceil().max(1.0) as usize,
        lead: (settle / step).ceil() as usize,
        period: 1,
        harmonics: Vec::new(),
        amplitude: [0.0; 4],
        offset,
    };
    let run = plan.run(solver, Drive { input: None, sign: 1.0 })?;
    Ok([run.fx[0], run.fy[0]])
}

/// Measures the response of eq. 1 on the solvers `make_solver` builds
/// (one per run; the runs go in parallel), for the Hertz contact `shape`
/// about `mean`, excited as `excitation` says.
///
/// Each measured input has two runs, of opposite sign `s = +-1`: `run_in`
/// at the mean state (the mean longitudinal force prescribed where it is
/// given; the creepage found by its last step is then held), then
///
/// ```text
/// dq(x) = s (A0 + A sum_{n=1}^{M} cos(k_n x + phi_n)),   phi_n = -pi n (n - 1) / M,
/// ```
///
/// (Schroeder's phases, offset `A0 = level scale`, `A = A0 sqrt(2/M)`)
/// for `lead` and one measured period `L = P h` (steps `x_j = j h`, `j <
/// P`). With `dF_j` half the difference of the two runs' forces, which
/// holds the odd part of the response only (the mean, what the start-up
/// leaves and the even-order nonlinearity cancel):
///
/// ```text
/// H_i,input(w_n) = (2/P) sum_j dF_i,j exp(-i k_n x_j) / (A exp(i phi_n)),   w_n = k_n V,
/// H_i,input(0)   = (1/P) sum_j dF_i,j / A0.
/// ```
pub fn measure(
    make_solver: &(dyn Fn() -> Box<dyn TangentialSolver> + Sync),
    shape: &HertzShape,
    mean: &MeanState,
    excitation: &Excitation,
) -> Result<CreepResponse, CreepResponseError> {
    let (e, m) = (excitation, mean);
    check(e, m)?;
    let a0 = shape.patch(m.normal_force).map_err(|e| CreepResponseError::Input(e.to_string()))?.a;
    let drives: Vec<Drive> = Input::ALL
        .into_iter()
        .filter(|i| e.inputs[i.index()])
        .flat_map(|i| [1.0, -1.0].map(|sign| Drive { input: Some(i), sign }))
        .collect();
    if drives.is_empty() {
        return Err(CreepResponseError::Input("no input to measure".into()));
    }
    let mut solvers: Vec<Box<dyn TangentialSolver>> = drives.iter().map(|_| make_solver()).collect();
    let step = match solvers[0].elements() {
        Elements::Grid(g) => g.dx,
        Elements::Adapted(_) => e.step,
    };
    let period = (e.period / step).round().max(4.0) as usize;
    let length = period as f64 * step;
    let spacing = 2.0 * PI * a0 / length;
    let count = (e.max_reduced / spacing + 1e-9).floor() as usize;
    if count < 2 || 2 * count >= period {
        return Err(CreepResponseError::Input(format!(
            "{count} harmonics up to w a0 / V = {} on a period of {period} steps: need at least two and fewer than half the steps (lengthen the period or shorten the step)",
            e.max_reduced
        )));
    }
    let scale = input_scale(shape, m)?;
    let offset: [f64; 4] = std::array::from_fn(|i| e.level[i] * scale[i]);
    let plan = Plan {
        shape,
        mean: m,
        step,
        run_in: (e.run_in / step).ceil().max(1.0) as usize,
        lead: (e.lead / step).ceil() as usize,
        period,
        harmonics: (1..=count)
            .map(|n| (2.0 * PI * n as f64 / length, -PI * (n * (n - 1)) as f64 / count as f64))
            .collect(),
        amplitude: offset.map(|a| a * (2.0 / count as f64).sqrt()),
        offset,
    };
    let runs: Vec<Run> = drives
        .par_iter()
        .zip(solvers.par_iter_mut())
        .map(|(&drive, solver)| plan.run(solver.as_mut(), drive))
        .collect::<Result<_, _>>()?;
    let mut table = vec![[[Complex64::new(0.0, 0.0); 4]; 2]; count + 1];
    for (pair, runs) in drives.chunks(2).zip(runs.chunks(2)) {
        let input = pair[0].input.expect("measured runs have an input").index();
        let half = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| 0.5 * (p - q)).collect::<Vec<f64>>();
        for (r, d) in [half(&runs[0].fx, &runs[1].fx), half(&runs[0].fy, &runs[1].fy)].iter().enumerate() {
            table[0][r][input] = Complex64::new(d.iter().sum::<f64>() / (period as f64 * plan.offset[input]), 0.0);
            for (n, (k, phase)) in plan.harmonics.iter().enumerate() {
                let c: Complex64 =
                    d.iter().enumerate().map(|(j, v)| v * Complex64::from_polar(1.0, -k * j as f64 * step)).sum();
                table[n + 1][r][input] =
                    c * (2.0 / period as f64) / Complex64::from_polar(plan.amplitude[input], *phase);
            }
        }
    }
    Ok(CreepResponse {
        speed: m.speed,
        semi_axis: a0,
        creepage_x: runs[0].creepage_x,
        force: runs[0].mean_force,
        reduced: (0..=count).map(|n| n as f64 * spacing).collect(),
        table,
        measured: e.inputs,
    })
}

/// The excitation's and the mean state's ranges.
fn check(e: &Excitation, m: &MeanState) -> Result<(), CreepResponseError> {
    let positive = |v: f64| v.is_finite() && v > 0.0;
    let mut values: Vec<(String, f64)> = [
        ("mean normal force (N)", m.normal_force),
        ("speed (m/s)", m.speed),
        ("friction", m.friction),
        ("step (m)", e.step),
        ("period (m)", e.period),
        ("max_reduced", e.max_reduced),
    ]
    .map(|(w, v)| (w.to_string(), v))
    .into();
    values.extend(Input::ALL.iter().zip(e.level).map(|(i, l)| (format!("level of {}", i.name()), l)));
    for (what, v) in values {
        if !positive(v) {
            return Err(CreepResponseError::Input(format!("{what} = {v} must be finite and > 0")));
        }
    }
    for (what, v) in [("run_in", e.run_in), ("lead", e.lead)] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(CreepResponseError::Input(format!("{what} = {v} m must be finite and >= 0")));
        }
    }
    for (what, v) in [("mean lateral creepage", m.creepage_y), ("mean spin", m.spin)] {
        if !v.is_finite() {
            return Err(CreepResponseError::Input(format!("{what} = {v} must be finite")));
        }
    }
    match m.longitudinal {
        Longitudinal::Force(f) if !(f.is_finite() && f.abs() < m.friction * m.normal_force) => {
            Err(CreepResponseError::Input(format!(
                "mean longitudinal force {f} N must be finite and below mu N0 = {} N",
                m.friction * m.normal_force
            )))
        }
        Longitudinal::Creepage(xi) if !xi.is_finite() => {
            Err(CreepResponseError::Input(format!("mean creepage {xi} must be finite")))
        }
        _ => Ok(()),
    }
}
