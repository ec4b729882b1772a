//! One wheel passage over the rail stretch: the model chain (book:
//! docs/src/theory/model-chain.md) at every time step.
//!
//! For each patch position `X_c = start + n h` (time `t = n h / V`):
//! imposed loads `N(X_c)`, `F_x(X_c)` -> Hertz patch -> tangential solution
//! with `F_x` prescribed -> Archard rates at the element centres -> wear of
//! the interval since the previous step on the rail grid (linearly
//! interpolated sub-steps). The kernel knows nothing of files or terminals:
//! progress is reported through a callback.

use crate::contact::{ContactError, Elements, PatchSolution, RailContact, StepInput, TangentialSolver};
use crate::dynamics::wheelset::torsion::TorsionFeedback;
use crate::hertz::{HertzError, HertzPatch, HertzShape};
use crate::loads::ImposedLoads;
use crate::rail_grid::RailGrid;
use crate::wear::{PatchWear, WearKernel, WearLaw};
use ndarray::Array2;

/// Kinematics, loads and discretisation of one passage (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct PassageSpec {
    /// Rolling speed V (m/s).
    pub speed: f64,
    /// Friction coefficient (1) at zero slip speed.
    pub friction: f64,
    /// How the friction coefficient varies with the slip speed.
    pub characteristic: crate::contact::friction::Characteristic,
    /// Friction memory.
    pub memory: Option<crate::contact::friction::FrictionMemory>,
    /// Prescribed longitudinal creepage (1) (`load.control = "creepage"`),
    /// or None: the longitudinal force of `loads` prescribed.
    pub creepage_x: Option<f64>,
    /// Prescribed lateral creepage (1).
    pub creepage_y: f64,
    /// Prescribed spin (1/m).
    pub spin: f64,
    /// Imposed loads along the rail.
    pub loads: ImposedLoads,
    /// Each wheel's imposed loads where a growth study's wheels differ
    /// (`[vehicle]` per wheel); empty: every wheel has `loads`.
    pub wheel_loads: Vec<ImposedLoads>,
    /// Patch-centre position at the first step (m).
    pub start: f64,
    /// Patch-centre position at the last step (m).
    pub end: f64,
    /// Nominal rolled distance per step, V dt (m); adjusted so that `end` is a step.
    pub step_length: f64,
    /// The wear law.
    pub wear_law: WearLaw,
    /// Linearly interpolated wear sub-steps per step (>= 1).
    pub substeps: usize,
    /// Patch-centre positions (m) between which wear is deposited; the steps
    /// before (a run-in) only build up the contact history.
    pub wear_window: (f64, f64),
    /// Dynamic normal force added to the imposed loads (growth studies).
    pub dynamic_normal_force: Option<PeriodicSignal>,
    /// The wheelset's torsion, which turns the normal force's variation
    /// into a variation of the prescribed creepage (growth studies with
    /// `[wheelset]`; [`crate::dynamics::wheelset::torsion`]): one per wheel where the
    /// wheels' loads differ (`wheel_loads`), else one for every wheel;
    /// empty without.
    pub torsion: Vec<TorsionFeedback>,
    /// Variation of the prescribed creepage added to `creepage_x` (1).
    pub dynamic_creepage_x: Option<PeriodicSignal>,
    /// Variation of the prescribed longitudinal force added to the imposed
    /// loads' (N; force control).
    pub dynamic_longitudinal_force: Option<PeriodicSignal>,
    /// Variation of the lateral creepage added to `creepage_y` (1).
    pub dynamic_creepage_y: Option<PeriodicSignal>,
    /// Variation of the spin added to `spin` (1/m).
    pub dynamic_spin: Option<PeriodicSignal>,
    /// The rail surface in the normal problem (`contact.normal =
    /// "linear"` or `"profile"`); `None`: the Hertz contact of the
    /// curvatures.
    pub surface: Option<RailContact>,
}

/// A periodic signal sampled at `x0 + i dx`, i = 0..n, period n dx,
/// linearly interpolated.
#[derive(Debug, Clone, PartialEq)]
pub struct PeriodicSignal {
    /// First sample position (m).
    pub x0: f64,
    /// Sample spacing (m).
    pub dx: f64,
    /// Samples (one period).
    pub values: Vec<f64>,
}

impl PeriodicSignal {
    /// Value at `x` (m).
    pub fn at(&self, x: f64) -> f64 {
        let n = self.values.len();
        let u = ((x - self.x0) / self.dx).rem_euclid(n as f64);
        let i = (u.floor() as usize).min(n - 1);
        let w = u - i as f64;
        (1.0 - w) * self.values[i] + w * self.values[(i + 1) % n]
    }
}

impl PassageSpec {
    /// Number of contact steps (positions), at least 2. A stretch that is a
    /// whole number of steps up to rounding (1e-9 of a step) has exactly that
    /// many.
    pub fn n_steps(&self) -> usize {
        ((self.end - self.start) / self.step_length - 1e-9).ceil().max(1.0) as usize + 1
    }

    /// Patch-centre position of step `n` (m).
    pub fn position(&self, n: usize) -> f64 {
        self.start + (self.end - self.start) * n as f64 / (self.n_steps() - 1) as f64
    }

    /// Time step dt (s).
    pub fn dt(&self) -> f64 {
        (self.end - self.start) / (self.n_steps() - 1) as f64 / self.speed
    }
}

/// Per-step resultants and, optionally, the patch fields.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PatchHistory {
    /// Time since the start of the passage (s).
    pub time: Vec<f64>,
    /// Patch centre in rail coordinates (m): the wheel's position, or with
    /// the linear profile contact on the adapted mesh the moved patch's.
    pub x_c: Vec<f64>,
    /// Normal force (N).
    pub normal_force: Vec<f64>,
    /// Longitudinal force on the wheel (N).
    pub longitudinal_force: Vec<f64>,
    /// Longitudinal creepage (1).
    pub creepage_x: Vec<f64>,
    /// Lateral creepage (1).
    pub creepage_y: Vec<f64>,
    /// Spin (1/m).
    pub spin: Vec<f64>,
    /// Semi-axis along the rail (m).
    pub semi_axis_a: Vec<f64>,
    /// Semi-axis across the rail (m).
    pub semi_axis_b: Vec<f64>,
    /// Maximum pressure (Pa): Hertz's p0 on the adapted mesh (with the
    /// linear profile contact the largest element pressure), the largest
    /// element pressure on the fixed grid.
    pub max_pressure: Vec<f64>,
    /// Area in contact (m^2): pi a b of the Hertz patch on the adapted
    /// mesh, the elements with pressure on the fixed grid.
    pub contact_area: Vec<f64>,
    /// Fraction of elements in stick (1).
    pub stick_fraction: Vec<f64>,
    /// 1 when wheel and rail are in contact (N > 0), 0 otherwise.
    pub in_contact: Vec<f64>,
    /// Iterations of the contact solve: Newton-Raphson iterations,
    /// Gauss-Seidel sweeps, or the fixed grid's CG solver's FFT products (0
    /// for FASTSIM).
    pub newton_iterations: Vec<f64>,
    /// Integral over the patch of the interpolated Archard rate (m^3/s): the
    /// volume the rail loses per second.
    pub wear_volume_rate: Vec<f64>,
    /// Fields on (step, element), when recorded.
    pub fields: Option<PatchFields>,
}

/// Contact fields on (step, element).
#[derive(Debug, Clone, PartialEq)]
pub struct PatchFields {
    /// Normal pressure (Pa).
    pub pressure: Array2<f64>,
    /// Traction on the wheel, x (Pa).
    pub traction_x: Array2<f64>,
    /// Traction on the wheel, y (Pa).
    pub traction_y: Array2<f64>,
    /// Slip velocity, x (m/s).
    pub slip_x: Array2<f64>,
    /// Slip velocity, y (m/s).
    pub slip_y: Array2<f64>,
    /// Archard wear rate (m/s).
    pub wear_rate: Array2<f64>,
    /// 1 = stick, 0 = slip.
    pub stick: Array2<i8>,
    /// The wear law's regime (0: no wear; else [`WearLaw::regimes`]'s
    /// index + 1).
    pub wear_regime: Array2<i8>,
}

impl PatchHistory {
    /// Records a step without contact: zero patch, forces, creepages and
    /// fields (the fields' rows stay zero).
    fn push_no_contact(&mut self, time: f64, x: f64, normal_force: f64) {
        self.in_contact.push(0.0);
        self.time.push(time);
        self.x_c.push(x);
        self.normal_force.push(normal_force);
        for v in [
            &mut self.longitudinal_force,
            &mut self.creepage_x,
            &mut self.creepage_y,
            &mut self.spin,
            &mut self.semi_axis_a,
            &mut self.semi_axis_b,
            &mut self.max_pressure,
            &mut self.contact_area,
            &mut self.stick_fraction,
            &mut self.newton_iterations,
            &mut self.wear_volume_rate,
        ] {
            v.push(0.0);
        }
    }
}

impl PatchFields {
    /// Zero fields for `steps` steps of `elements` elements.
    pub fn new(steps: usize, elements: usize) -> Self {
        let z = || Array2::zeros((steps, elements));
        PatchFields {
            pressure: z(),
            traction_x: z(),
            traction_y: z(),
            slip_x: z(),
            slip_y: z(),
            wear_rate: z(),
            stick: Array2::zeros((steps, elements)),
            wear_regime: Array2::zeros((steps, elements)),
        }
    }

    fn set(&mut self, n: usize, sol: &PatchSolution, rates: &[f64], regimes: &[i8]) {
        let rows: [(&mut Array2<f64>, &[f64]); 6] = [
            (&mut self.pressure, &sol.pressure),
            (&mut self.traction_x, &sol.traction_x),
            (&mut self.traction_y, &sol.traction_y),
            (&mut self.slip_x, &sol.slip_x),
            (&mut self.slip_y, &sol.slip_y),
            (&mut self.wear_rate, rates),
        ];
        for (field, values) in rows {
            field.row_mut(n).iter_mut().zip(values).for_each(|(d, s)| *d = *s);
        }
        self.stick.row_mut(n).iter_mut().zip(&sol.stick).for_each(|(d, s)| *d = i8::from(*s));
        self.wear_regime.row_mut(n).iter_mut().zip(regimes).for_each(|(d, s)| *d = *s);
    }
}

/// Result of one passage.
#[derive(Debug, Clone, PartialEq)]
pub struct PassageResult {
    /// Wear depth on the rail grid, shape (ny, nx) (m, positive = removed).
    pub wear: Array2<f64>,
    /// Per-step history of the patch.
    pub history: PatchHistory,
    /// Steps at which the linear profile contact's pressure vanished well
    /// inside the patch (0 for the other normal contacts).
    pub clipped_steps: usize,
    /// Steps the fast tangential solver did not converge and the reference
    /// solver solved ([`crate::contact::PatchSolution::fallback`]).
    pub fallback_steps: usize,
    /// Volume the passage wore in each of the wear law's regimes within the
    /// wear window (m^3; [`WearLaw::regimes`]' order): each step's rates
    /// integrated over the patch, times the step.
    pub regime_volume: Vec<f64>,
}

/// Why a passage stopped.
#[derive(Debug, thiserror::Error)]
pub enum PassageError {
    /// The normal problem has no solution at this step.
    #[error("step {step} at X = {x:.6e} m: normal force N = {normal_force:.6e} N: {source}")]
    Normal {
        /// Step index.
        step: usize,
        /// Patch position (m).
        x: f64,
        /// Normal force (N).
        normal_force: f64,
        /// Cause.
        source: HertzError,
    },
    /// The normal problem on the rail surface failed (equivalent roughness).
    #[error("normal problem on the rail profile at X = {x:.6e} m (N = {normal_force:.6e} N): {source}")]
    Approach {
        /// Patch position (m).
        x: f64,
        /// Normal force (N).
        normal_force: f64,
        /// Cause.
        source: ContactError,
    },
    /// The contact model cannot take the passage's rail surface.
    #[error("{0}")]
    Surface(ContactError),
    /// The tangential solver failed at this step.
    #[error("step {step} at X = {x:.6e} m (N = {normal_force:.6e} N, F_x = {force_x:.6e} N): {source}")]
    Tangential {
        /// Step index.
        step: usize,
        /// Patch position (m).
        x: f64,
        /// Normal force (N).
        normal_force: f64,
        /// Prescribed longitudinal force (N).
        force_x: f64,
        /// Cause.
        source: ContactError,
    },
    /// The contact area left the rail grid across the rail: its wear would
    /// be lost.
    #[error(
        "step {step} at X = {x:.6e} m: the contact area reaches |y| = {y:.6e} m, beyond the rail grid's cells (to {half_width:.6e} m): its wear would be lost (raise rail.half_width)"
    )]
    OffRail {
        /// Step index.
        step: usize,
        /// Patch position (m).
        x: f64,
        /// Lateral position of the outermost element in contact (m).
        y: f64,
        /// Where the rail grid's outermost cells end (m).
        half_width: f64,
    },
    /// A result is not finite (never written to the output).
    #[error("step {step} at X = {x:.6e} m: non-finite {what} in the contact solution")]
    NonFinite {
        /// Step index.
        step: usize,
        /// Patch position (m).
        x: f64,
        /// Which quantity.
        what: &'static str,
    },
}

/// The previous step's patch, kept for the wear of the interval to the next.
struct PreviousPatch {
    /// The wheel's position (m): what the wear window counts.
    wheel: f64,
    /// The patch centre (m): where its wear goes.
    x_c: f64,
    a: f64,
    b: f64,
    rates: Vec<f64>,
}

/// Runs one passage; `progress(done, total)` is called as each step is
/// recorded (a step later than it is solved; `total` at the end).
///
/// Each step's contact problem is solved beside the recording of the step
/// before (its wear deposit and history, `rayon::join`): the same
/// operations in the same order as one after the other, on the core the
/// solver leaves idle. An error of the step before is reported before one
/// of the step (whose solve is then wasted work, nothing else).
pub fn run_passage(
    spec: &PassageSpec,
    shape: &HertzShape,
    solver: &mut dyn TangentialSolver,
    deposit: &dyn WearKernel,
    grid: &RailGrid,
    record_fields: bool,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<PassageResult, PassageError> {
    let steps = spec.n_steps();
    let dt = spec.dt();
    let elements = solver.elements();
    let mut rec = Recorder {
        spec,
        deposit,
        grid,
        elements: &elements,
        wear: Array2::zeros((grid.ny, grid.nx)),
        h: PatchHistory {
            fields: record_fields.then(|| PatchFields::new(steps, elements.len())),
            ..Default::default()
        },
        previous: None,
        clipped_steps: 0,
        fallback_steps: 0,
        regime_volume: vec![0.0; spec.wear_law.regimes().len()],
    };
    solver.reset();
    solver.set_surface(spec.surface.clone()).map_err(PassageError::Surface)?;
    let normal_force_at =
        |x: f64| spec.loads.normal_force_at(x) + spec.dynamic_normal_force.as_ref().map_or(0.0, |d| d.at(x));
    let step_input = |n: usize, patch| {
        let x = spec.position(n);
        StepInput {
            patch,
            speed: spec.speed,
            dt,
            friction: spec.friction,
            characteristic: spec.characteristic,
            memory: spec.memory,
            force_x: spec
                .dynamic_longitudinal_force
                .as_ref()
                .map_or(spec.loads.longitudinal_force_at(x), |d| spec.loads.longitudinal_force_at(x) + d.at(x)),
            creepage_x: spec.creepage_x.map(|c| c + spec.dynamic_creepage_x.as_ref().map_or(0.0, |d| d.at(x))),
            creepage_y: spec.dynamic_creepage_y.as_ref().map_or(spec.creepage_y, |d| spec.creepage_y + d.at(x)),
            spin: spec.dynamic_spin.as_ref().map_or(spec.spin, |d| spec.spin + d.at(x)),
            position: x,
        }
    };
    // The solved step not yet recorded.
    let mut pending: Option<SolvedStep> = None;
    for n in 0..steps {
        let x = spec.position(n);
        let normal_force = normal_force_at(x);
        if normal_force <= 0.0 {
            // Contact loss: no patch, no traction, no wear; the contact
            // history restarts when contact returns (a virgin Cattaneo step).
            if rec.flush(&mut pending)? {
                progress(n, steps);
            }
            solver.reset();
            rec.previous = None;
            rec.h.push_no_contact(n as f64 * dt, x, normal_force);
            progress(n + 1, steps);
            continue;
        }
        let patch = match shape.patch(normal_force) {
            Ok(patch) => patch,
            Err(source) => {
                if rec.flush(&mut pending)? {
                    progress(n, steps);
                }
                return Err(PassageError::Normal { step: n, x, normal_force, source });
            }
        };
        let input = step_input(n, patch);
        // The next step's input, where it has a patch: a solver may prepare
        // it meanwhile.
        let next = (n + 1 < steps).then(|| normal_force_at(spec.position(n + 1))).and_then(|force| {
            (force > 0.0).then(|| shape.patch(force).ok()).flatten().map(|patch| step_input(n + 1, patch))
        });
        let last = pending.take();
        let recorded = last.is_some();
        let (sol, done) =
            rayon::join(|| solver.step_ahead(&input, next.as_ref()), || last.map_or(Ok(()), |s| rec.record(s)));
        done?;
        if recorded {
            progress(n, steps);
        }
        let force_x = input.force_x;
        let sol = sol.map_err(|source| PassageError::Tangential { step: n, x, normal_force, force_x, source })?;
        pending = Some(SolvedStep { n, x, normal_force, patch, sol });
    }
    if rec.flush(&mut pending)? {
        progress(steps, steps);
    }
    let Recorder { wear, h, clipped_steps, fallback_steps, regime_volume, .. } = rec;
    Ok(PassageResult { wear, history: h, clipped_steps, fallback_steps, regime_volume })
}

/// A step's contact solution, with what its recording needs.
struct SolvedStep {
    n: usize,
    /// The wheel's position (m).
    x: f64,
    /// Normal force (N).
    normal_force: f64,
    /// The Hertz patch of the normal force.
    patch: HertzPatch,
    sol: PatchSolution,
}

/// What a passage gathers step by step: the rail's wear, the per-step
/// history and fields, the previous patch (for the wear of the interval to
/// the next), the counts of clipped and handed-over steps.
struct Recorder<'a> {
    spec: &'a PassageSpec,
    deposit: &'a dyn WearKernel,
    grid: &'a RailGrid,
    elements: &'a Elements,
    /// Wear depth on the rail grid (m).
    wear: Array2<f64>,
    h: PatchHistory,
    previous: Option<PreviousPatch>,
    clipped_steps: usize,
    fallback_steps: usize,
    regime_volume: Vec<f64>,
}

impl Recorder<'_> {
    /// Records the pending step, if any (whether there was one).
    fn flush(&mut self, pending: &mut Option<SolvedStep>) -> Result<bool, PassageError> {
        pending.take().map_or(Ok(false), |s| self.record(s).map(|()| true))
    }

    /// Checks a solved step (finite, on the rail), deposits the wear of the
    /// interval from the previous step and appends its history.
    fn record(&mut self, step: SolvedStep) -> Result<(), PassageError> {
        let SolvedStep { n, x, normal_force, patch, sol } = step;
        let (spec, grid, h) = (self.spec, self.grid, &mut self.h);
        let dt = spec.dt();
        check_finite(&sol, n, x)?;
        self.clipped_steps += usize::from(sol.clipped > 0);
        self.fallback_steps += usize::from(sol.fallback);
        // The patch the solver used (moved with the contact point by the
        // linear profile contact on the adapted mesh).
        let (patch_a, patch_b) = sol.semi_axes.unwrap_or((patch.a, patch.b));
        // How far across the contact area reaches: the fixed grid's
        // elements in contact; the adapted mesh's patch where the linear
        // contact widened it (the Hertz patch is checked by the config).
        let reach = match self.elements {
            Elements::Grid(g) => (0..g.len())
                .filter(|&k| sol.pressure[k] > 0.0)
                .map(|k| (g.y(k / g.nx) - 0.5 * g.dy).abs().max((g.y(k / g.nx) + 0.5 * g.dy).abs()))
                .fold(0.0f64, f64::max),
            Elements::Adapted(_) if sol.semi_axes.is_some() => patch_b,
            Elements::Adapted(_) => 0.0,
        };
        // The outermost rail cells reach half a cell beyond the nodes.
        let edge = grid.half_width + 0.5 * grid.dy;
        if reach > edge * (1.0 + 1e-9) {
            return Err(PassageError::OffRail { step: n, x, y: reach, half_width: edge });
        }
        let (rates, regimes) = spec.wear_law.rates(&sol, spec.speed);
        let (w0, w1) = spec.wear_window;
        // The interval from the previous step belongs to the window when its
        // midpoint does: [w0, w1) then holds exactly (w1 - w0) / step of them
        // whatever the steps' offset (a periodic stretch receives one whole
        // passage).
        if let Some(p) = self.previous.as_ref().filter(|p| (w0..w1).contains(&(0.5 * (p.wheel + x)))) {
            let from = PatchWear { x_c: p.x_c, a: p.a, b: p.b, rates: &p.rates };
            let to = PatchWear { x_c: x + sol.offset, a: patch_a, b: patch_b, rates: &rates };
            self.deposit.accumulate(grid, &mut self.wear, &from, &to, dt, spec.substeps);
            if let [volume] = self.regime_volume.as_mut_slice() {
                // One regime (Archard's): every wearing element is in it.
                *volume += self.deposit.integral(&rates, patch_a, patch_b) * dt;
            } else {
                let mut masked = vec![0.0; rates.len()];
                for (r, volume) in self.regime_volume.iter_mut().enumerate() {
                    let regime = (r + 1) as i8;
                    masked.iter_mut().zip(rates.iter().zip(&regimes)).for_each(|(m, (v, g))| {
                        *m = if *g == regime { *v } else { 0.0 };
                    });
                    *volume += self.deposit.integral(&masked, patch_a, patch_b) * dt;
                }
            }
        }
        h.in_contact.push(1.0);
        h.time.push(n as f64 * dt);
        // The patch centre: moved with the contact point by the linear
        // profile contact on the adapted mesh (the elements' xi, eta are
        // relative to it).
        h.x_c.push(x + sol.offset);
        h.normal_force.push(normal_force);
        h.longitudinal_force.push(sol.force_x);
        h.creepage_x.push(sol.creepage.x);
        h.creepage_y.push(sol.creepage.y);
        h.spin.push(sol.creepage.spin);
        h.semi_axis_a.push(patch_a);
        h.semi_axis_b.push(patch_b);
        let (max_pressure, contact_area) = match self.elements {
            Elements::Grid(g) => (
                sol.pressure.iter().fold(0.0f64, |m, p| m.max(*p)),
                sol.pressure.iter().filter(|p| **p > 0.0).count() as f64 * g.area(),
            ),
            Elements::Adapted(_) => (
                match sol.semi_axes {
                    // The linear profile contact's pressure is not Hertz's.
                    Some(_) => sol.pressure.iter().fold(0.0f64, |m, p| m.max(*p)),
                    None => patch.p0,
                },
                std::f64::consts::PI * patch_a * patch_b,
            ),
        };
        h.max_pressure.push(max_pressure);
        h.contact_area.push(contact_area);
        h.stick_fraction.push(sol.stick_fraction());
        h.newton_iterations.push(sol.iterations as f64);
        h.wear_volume_rate.push(self.deposit.integral(&rates, patch_a, patch_b));
        if let Some(f) = h.fields.as_mut() {
            f.set(n, &sol, &rates, &regimes);
        }
        self.previous = Some(PreviousPatch { wheel: x, x_c: x + sol.offset, a: patch_a, b: patch_b, rates });
        Ok(())
    }
}

fn check_finite(sol: &PatchSolution, step: usize, x: f64) -> Result<(), PassageError> {
    let fields: [(&'static str, &[f64]); 5] = [
        ("pressure", &sol.pressure),
        ("traction_x", &sol.traction_x),
        ("traction_y", &sol.traction_y),
        ("slip_x", &sol.slip_x),
        ("slip_y", &sol.slip_y),
    ];
    for (what, v) in fields {
        if v.iter().any(|x| !x.is_finite()) {
            return Err(PassageError::NonFinite { step, x, what });
        }
    }
    if !sol.creepage.x.is_finite() {
        return Err(PassageError::NonFinite { step, x, what: "creepage" });
    }
    Ok(())
}
