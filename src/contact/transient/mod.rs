//! The non-stationary (transient) tangential contact model of Baeza, Vila,
//! Roda and Fayos, Wear 265 (2008) 1156-1162, section 2 (Eqs. 1-7), after
//! Kalker's non-stationary theory (Kalker 1990, ch. 5).
//!
//! Kinematics (Eq. 3, 5) for element J of the current Paul-Hashemi mesh:
//!
//! ```text
//! s_J = V w_J(xi) + (u_J - u_o,J) / dt,    w_J = (xi_x - phi y_J, xi_y + phi x_J)
//! ```
//!
//! with `u = C p` the displacement difference of the two bodies (exact or
//! Winkler elastic model, [`elastic`]) and `u_o,J` the displacement the same
//! material point had one step earlier. Regularised Coulomb friction (Eq. 6):
//!
//! ```text
//! p_J = -(2/pi) atan(|s_J| / eps) mu p3_J s_J / |s_J|
//! ```
//!
//! Substituting gives the nonlinear system of Eq. 7 in the local slips; with
//! the longitudinal force prescribed, `sum_K p_x,K A_K = F_x` closes it with
//! the creepage `xi_x` as an extra unknown. Two solvers, one convergence test
//! (largest kinematic residual below [`DEFAULT_TOLERANCE`] eps, force
//! residual below 1e-10 mu N):
//!
//! * [`StepSolver::Newton`], the reference: Newton-Raphson on all slips
//!   (dense LU with faer for the exact model, 2 x 2 blocks for Winkler, the
//!   creepage eliminated by bordering), warm-started from the previous step,
//!   with a backtracking line search. `O(N^3)` per factorisation.
//! * [`StepSolver::GaussSeidel`] (exact model): element-wise nonlinear
//!   Gauss-Seidel with Anderson acceleration ([`gauss_seidel`]), `O(N^2)` per
//!   sweep and no factorisation. Converges to the same solution (within
//!   1e-13 when both are run to 1e-8 eps; see the test in
//!   `tests/transient_passage.rs`); a step it cannot converge goes to Newton.
//!
//! A step that Newton does not converge is retried by continuation in eps
//! (100 eps, 10 eps, eps); if it still fails the error names the residual
//! history. A virgin start (no history) is the Cattaneo shift problem:
//! `u_o = 0` and the rigid shift over the step is `V xi dt`.

pub mod elastic;
pub mod gauss_seidel;

use super::friction::{Local, STICK_SLIP_FACTOR, regularised_with};
use super::linear::LinearContact;
use super::mesh::{EllipseMesh, PressureShape, pressure_on_mesh};
use super::{ContactError, Creepage, Elements, PatchSolution, RailContact, StepInput, TangentialSolver};
use elastic::{ExactElastic, PatchFrame, WinklerElastic};
use faer::Mat;
use faer::linalg::solvers::Solve;

/// Default convergence tolerance on the kinematic residual, in units of eps:
/// with eps = 1e-5 m/s, |R| < 1e-9 m/s, which leaves the tractions within
/// about 1e-8 of their converged values.
pub const DEFAULT_TOLERANCE: f64 = 1e-4;

/// Sweeps after which a Gauss-Seidel step is handed to Newton.
pub const GS_MAX_SWEEPS: usize = 400;

/// Convergence tolerance on the force residual |sum p_x A - F_x| / (mu N).
pub(crate) const FORCE_TOLERANCE: f64 = 1e-10;

/// Largest growth factor of an element's slip in one Newton iteration.
const STEP_GROWTH: f64 = 10.0;

/// Elastic model of the transient solver.
#[derive(Debug, Clone)]
pub enum ElasticModel {
    /// Kalker's exact theory (half-space influence coefficients).
    Exact(Box<ExactElastic>),
    /// Kalker's simplified theory (Winkler, u = L p).
    Winkler(WinklerElastic),
}

impl ElasticModel {
    /// Displacement difference `u` at the element centres of a patch with
    /// semi-axis `a` (m) under tractions `p` (interleaved).
    fn displacement(&self, a: f64, p: &[f64], u: &mut [f64]) {
        match self {
            ElasticModel::Exact(e) => e.displacement(a, p, u),
            ElasticModel::Winkler(w) => {
                let (l1, l2) = w.flexibility(a);
                for (uk, pk) in u.chunks_exact_mut(2).zip(p.chunks_exact(2)) {
                    uk[0] = l1 * pk[0];
                    uk[1] = l2 * pk[1];
                }
            }
        }
    }

    /// Displacement of the material now at the centres of patch `now`, one
    /// step earlier (at `x + shift` in patch `old` under tractions `p_old`).
    fn previous(
        &mut self,
        mesh: &EllipseMesh,
        now: PatchFrame,
        old: PatchFrame,
        shift: f64,
        p_old: &[f64],
        u_o: &mut [f64],
    ) {
        match self {
            ElasticModel::Exact(e) => e.previous(mesh, now, old, shift, p_old, u_o),
            ElasticModel::Winkler(w) => w.previous(mesh, now, old, shift, p_old, u_o),
        }
    }
}

/// State carried from one step to the next.
#[derive(Debug, Clone)]
struct History {
    frame: PatchFrame,
    /// Offset of the patch centre from the wheel's X_c (m): the linear
    /// profile contact moves the patch with the contact point.
    offset: f64,
    /// Tractions, interleaved (Pa).
    p: Vec<f64>,
    /// Slips, interleaved (m/s).
    s: Vec<f64>,
    /// Creepage xi_x.
    xi: f64,
    /// With friction memory: the ratio `mu / mu_0` each element's material
    /// had at the end of the step (1).
    kept: Option<Vec<f64>>,
}

/// How the nonlinear system of a step is solved. [`Transient::new`] starts
/// with the reference, Newton; configs default to Gauss-Seidel
/// (`contact.solver`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, strum::EnumString, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "kebab-case")]
pub enum StepSolver {
    /// Newton-Raphson on all slips with a dense LU (the reference).
    #[default]
    Newton,
    /// Element-wise nonlinear Gauss-Seidel with Anderson acceleration
    /// ([`gauss_seidel`]); exact model only, Newton being already
    /// element-wise for Winkler. A step it cannot converge in
    /// [`GS_MAX_SWEEPS`] sweeps goes to Newton (counted by
    /// [`Transient::gauss_seidel_fallbacks`]).
    GaussSeidel,
}

/// Transient tangential solver.
#[derive(Debug, Clone)]
pub struct Transient {
    mesh: EllipseMesh,
    model: ElasticModel,
    shape: PressureShape,
    eps: f64,
    max_iterations: usize,
    history: Option<History>,
    solver: StepSolver,
    /// Convergence tolerance on the kinematic residual, in units of eps.
    tolerance: f64,
    /// Steps that Gauss-Seidel handed to Newton since the last reset.
    fallbacks: usize,
    /// Factorised Jacobian of the last Newton iteration, reused as the
    /// initial chord matrix of the next step.
    factor: Option<Factor>,
    /// The linear profile contact (empty unless built with one).
    linear: LinearContact,
    /// Elements of the current step whose linear pressure was set to zero.
    clipped: usize,
    /// The current step's patch offset (m) and whether the linear profile
    /// contact moved it.
    moved: Option<f64>,
}

/// A factorised Newton matrix.
#[derive(Debug, Clone)]
enum Factor {
    /// Dense LU (exact model).
    Lu(faer::linalg::solvers::PartialPivLu<f64>),
    /// Inverted 2 x 2 blocks, row-major (Winkler model).
    Blocks(Vec<[f64; 4]>),
}

impl Factor {
    /// Solves in place for every column of `rhs`.
    fn solve(&self, rhs: &mut Mat<f64>) {
        match self {
            Factor::Lu(lu) => lu.solve_in_place(rhs.as_mut()),
            Factor::Blocks(inv) => {
                for (k, m) in inv.iter().enumerate() {
                    for col in 0..rhs.ncols() {
                        let (b0, b1) = (rhs[(2 * k, col)], rhs[(2 * k + 1, col)]);
                        rhs[(2 * k, col)] = m[0] * b0 + m[1] * b1;
                        rhs[(2 * k + 1, col)] = m[2] * b0 + m[3] * b1;
                    }
                }
            }
        }
    }
}

/// The data of one step's nonlinear system.
struct Problem<'a> {
    input: &'a StepInput,
    frame: PatchFrame,
    /// Pressure at the element centres (Pa).
    p3: &'a [f64],
    /// Element areas (m^2).
    area: &'a [f64],
    /// Earlier displacements of the material at the centres (m).
    u_o: &'a [f64],
    /// The friction characteristic at each element.
    local: &'a [Local],
}

/// Residuals of one Newton evaluation.
struct Eval {
    p: Vec<f64>,
    /// D blocks (xx, xy, yy) per element.
    d: Vec<[f64; 3]>,
    r: Vec<f64>,
    r_force: f64,
}

impl Transient {
    /// The mesh the fields are given on.
    pub fn mesh(&self) -> &EllipseMesh {
        &self.mesh
    }

    /// A transient solver on an `nx` x `ny` mesh with regularisation `eps`
    /// (m/s) and the pressure shape `shape`.
    pub fn new(mesh: EllipseMesh, model: ElasticModel, shape: PressureShape, eps: f64) -> Self {
        Transient {
            mesh,
            model,
            shape,
            eps,
            max_iterations: 60,
            history: None,
            solver: StepSolver::Newton,
            tolerance: DEFAULT_TOLERANCE,
            fallbacks: 0,
            factor: None,
            linear: LinearContact::default(),
            clipped: 0,
            moved: None,
        }
    }

    /// Lets the model take the rail surface into its normal pressure by the
    /// linear profile contact ([`super::linear`]) of the Hertz contact
    /// `shape`: the patch moved and stretched with the surface (uniformly
    /// for the exact elastic model, whose coefficients hold one aspect
    /// ratio), the model's pressure shape on it plus the rest of the exact
    /// elastic response.
    pub fn with_linear_contact(mut self, shape: &crate::hertz::HertzShape) -> Self {
        self.linear = LinearContact::new(&self.mesh, shape);
        self
    }

    /// Caps the Newton-Raphson iterations per attempt (default 60).
    pub fn with_max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// Chooses how each step's system is solved (default Newton).
    pub fn with_solver(mut self, solver: StepSolver) -> Self {
        self.solver = solver;
        self
    }

    /// Steps that the Gauss-Seidel solver did not converge in
    /// [`GS_MAX_SWEEPS`] sweeps and handed to Newton, since the last reset.
    pub fn gauss_seidel_fallbacks(&self) -> usize {
        self.fallbacks
    }

    /// Sets the convergence tolerance on the kinematic residual |R| (m/s) to
    /// `relative` eps (default [`DEFAULT_TOLERANCE`]).
    pub fn with_tolerance(mut self, relative: f64) -> Self {
        self.tolerance = relative;
        self
    }

    /// Rigid slip per unit speed at element k.
    fn rigid(&self, k: usize, frame: PatchFrame, cr: Creepage) -> [f64; 2] {
        let (x, y) = (self.mesh.xi[k] * frame.a, self.mesh.eta[k] * frame.b);
        [cr.x - cr.spin * y, cr.y + cr.spin * x]
    }

    fn evaluate(&self, pb: &Problem, s: &[f64], xi: f64, eps: f64) -> Eval {
        let (input, frame, p3, area, u_o) = (pb.input, pb.frame, pb.p3, pb.area, pb.u_o);
        let n = self.mesh.len();
        let mu = input.friction;
        let mut p = vec![0.0; 2 * n];
        let mut d = vec![[0.0; 3]; n];
        for k in 0..n {
            let (pk, dk) = regularised_with([s[2 * k], s[2 * k + 1]], mu * p3[k], eps, pb.local[k]);
            p[2 * k] = pk[0];
            p[2 * k + 1] = pk[1];
            d[k] = dk;
        }
        let mut u = vec![0.0; 2 * n];
        self.model.displacement(frame.a, &p, &mut u);
        let cr = Creepage { x: xi, y: input.creepage_y, spin: input.spin };
        let mut r = vec![0.0; 2 * n];
        for k in 0..n {
            let w = self.rigid(k, frame, cr);
            for (c, wc) in w.iter().enumerate() {
                let i = 2 * k + c;
                r[i] = s[i] - input.speed * wc - (u[i] - u_o[i]) / input.dt;
            }
        }
        let force: f64 = (0..n).map(|k| p[2 * k] * area[k]).sum();
        // A prescribed creepage leaves no force equation.
        let r_force = match input.creepage_x {
            Some(_) => 0.0,
            None => (force - input.force_x) / (mu * input.patch.normal_force),
        };
        Eval { p, d, r, r_force }
    }

    /// Factorises the Newton matrix `J = I + (1/dt) C D` of the slips.
    fn factor(&self, frame: PatchFrame, dt: f64, d: &[[f64; 3]]) -> Factor {
        let n = self.mesh.len();
        match &self.model {
            ElasticModel::Exact(e) => {
                let c = e.unit_matrix();
                let scale = frame.a / dt;
                let j = Mat::from_fn(2 * n, 2 * n, |r, col| {
                    let k = col / 2;
                    let dk = d[k];
                    let (c0, c1) = (c[(r, 2 * k)], c[(r, 2 * k + 1)]);
                    let v = if col % 2 == 0 { c0 * dk[0] + c1 * dk[1] } else { c0 * dk[1] + c1 * dk[2] };
                    scale * v + if r == col { 1.0 } else { 0.0 }
                });
                Factor::Lu(j.partial_piv_lu())
            }
            ElasticModel::Winkler(w) => {
                let (l1, l2) = w.flexibility(frame.a);
                Factor::Blocks(
                    d.iter()
                        .map(|dk| {
                            // J_k = I + (1/dt) diag(l1, l2) D_k, stored inverted.
                            let (j00, j01) = (1.0 + l1 * dk[0] / dt, l1 * dk[1] / dt);
                            let (j10, j11) = (l2 * dk[1] / dt, 1.0 + l2 * dk[2] / dt);
                            let det = j00 * j11 - j01 * j10;
                            [j11 / det, -j01 / det, -j10 / det, j00 / det]
                        })
                        .collect(),
                )
            }
        }
    }

    /// Newton-Raphson at regularisation `eps` from (s, xi); Ok(iterations,
    /// final evaluation) or Err(residual history). The factorised Jacobian is reused while it
    /// keeps reducing the residual fast (chord steps) and refreshed when the
    /// reduction slows or a step fails; the converged solution satisfies the
    /// same tolerance either way.
    fn newton(
        &self,
        pb: &Problem,
        s: &mut [f64],
        xi: &mut f64,
        eps: f64,
        factor: &mut Option<Factor>,
    ) -> Result<(usize, Eval), Vec<f64>> {
        let (input, frame, area) = (pb.input, pb.frame, pb.area);
        let n = self.mesh.len();
        let v = input.speed;
        let tol = self.tolerance * eps;
        let merit = |e: &Eval| e.r.iter().map(|r| (r / v).powi(2)).sum::<f64>() + e.r_force.powi(2);
        let scale = input.friction * input.patch.normal_force;
        let mut history = Vec::new();
        let mut ev = self.evaluate(pb, s, *xi, eps);
        for _ in 0..self.max_iterations {
            let r_max = ev.r.iter().fold(0.0f64, |m, r| m.max(r.abs()));
            history.push(r_max);
            if r_max < tol && ev.r_force.abs() < FORCE_TOLERANCE {
                return Ok((history.len() - 1, ev));
            }
            let fresh = factor.is_none();
            let f = factor.get_or_insert_with(|| self.factor(frame, input.dt, &ev.d));
            let mut rhs = Mat::from_fn(2 * n, 2, |i, c| {
                if c == 0 {
                    -ev.r[i]
                } else if i % 2 == 0 {
                    v
                } else {
                    0.0
                }
            });
            f.solve(&mut rhs);
            // Force row: h = d(R_F)/ds = -(A_k/(mu N)) (D_xx, D_xy) per element.
            let (mut h1, mut h2) = (0.0, 0.0);
            for k in 0..n {
                let (hx, hy) = (-area[k] * ev.d[k][0] / scale, -area[k] * ev.d[k][1] / scale);
                h1 += hx * rhs[(2 * k, 0)] + hy * rhs[(2 * k + 1, 0)];
                h2 += hx * rhs[(2 * k, 1)] + hy * rhs[(2 * k + 1, 1)];
            }
            let dxi = if input.creepage_x.is_some() { 0.0 } else { -(ev.r_force + h1) / h2 };
            let finite = dxi.is_finite() && (0..2 * n).all(|i| rhs[(i, 0)].is_finite() && rhs[(i, 1)].is_finite());
            if !finite {
                if fresh {
                    return Err(history);
                }
                *factor = None;
                continue;
            }
            let m0 = merit(&ev);
            let mut t = 1.0;
            let s0 = s.to_vec();
            let xi0 = *xi;
            // Element-wise limit: an element's slip may grow at most
            // STEP_GROWTH times its size (or eps) per iteration, so that one
            // element crossing from stick to slip does not force the whole
            // step to be cut by the line search.
            let step: Vec<f64> = (0..n)
                .flat_map(|k| {
                    let (dx, dy) =
                        (rhs[(2 * k, 0)] + dxi * rhs[(2 * k, 1)], rhs[(2 * k + 1, 0)] + dxi * rhs[(2 * k + 1, 1)]);
                    let limit = STEP_GROWTH * s0[2 * k].hypot(s0[2 * k + 1]).max(eps);
                    let f = (limit / dx.hypot(dy)).min(1.0);
                    [f * dx, f * dy]
                })
                .collect();
            let accepted = loop {
                for i in 0..2 * n {
                    s[i] = s0[i] + t * step[i];
                }
                *xi = xi0 + t * dxi;
                let trial = self.evaluate(pb, s, *xi, eps);
                let m = merit(&trial);
                if m < (1.0 - 1e-4 * t) * m0 {
                    let slow = m > 0.25 * m0;
                    ev = trial;
                    break Some(slow);
                }
                if t < 1e-3 {
                    break None;
                }
                t *= 0.5;
            };
            match accepted {
                Some(slow) => {
                    if slow {
                        *factor = None;
                    }
                }
                None => {
                    s.copy_from_slice(&s0);
                    *xi = xi0;
                    if fresh {
                        return Err(history);
                    }
                    *factor = None;
                }
            }
        }
        Err(history)
    }

    fn solve_step(&mut self, input: &StepInput) -> Result<PatchSolution, ContactError> {
        input.check_friction_limit()?;
        let n = self.mesh.len();
        let patch = &input.patch;
        let force = input.force_x;
        if input.dt.is_nan() || input.dt <= 0.0 {
            return Err(ContactError::NoConvergence {
                force,
                reason: format!("transient models need a time step > 0, got {}", input.dt),
            });
        }
        // The patch: Hertz's, or moved with the contact point by the linear
        // profile contact (uniformly stretched for the exact elastic model,
        // whose coefficients hold one aspect ratio).
        let uniform = matches!(self.model, ElasticModel::Exact(_));
        let (frame, p3) = match self.linear.patch(input.position, patch, self.shape, &self.mesh, uniform)? {
            Some(lp) => {
                self.clipped = lp.clipped;
                self.moved = Some(lp.offset);
                (PatchFrame { a: lp.a, b: lp.b }, lp.pressure)
            }
            None => {
                self.clipped = 0;
                self.moved = None;
                (
                    PatchFrame { a: patch.a, b: patch.b },
                    pressure_on_mesh(&self.mesh, self.shape, patch.normal_force, patch.a, patch.b),
                )
            }
        };
        let offset = self.moved.unwrap_or(0.0);
        let area: Vec<f64> = (0..n).map(|k| self.mesh.area(k) * frame.a * frame.b).collect();
        let mut u_o = vec![0.0; 2 * n];
        let memory = input.memory.filter(|_| !input.characteristic.is_constant());
        let mut kept = vec![1.0; n];
        let (mut s, mut xi) = match &self.history {
            Some(h) => {
                // The material now at x was at x + V dt + (offset now -
                // offset then) in the previous patch's frame.
                let shift = input.speed * input.dt + offset - h.offset;
                self.model.previous(&self.mesh, frame, h.frame, shift, &h.p, &mut u_o);
                if let (Some(_), Some(old)) = (memory, &h.kept) {
                    kept_upstream(&self.mesh, (frame, h.frame), shift, old, &mut kept);
                }
                (h.s.clone(), h.xi)
            }
            None => (vec![0.0; 2 * n], 0.0),
        };
        let local: Vec<Local> = kept.iter().map(|&r| Local::new(input.characteristic, memory, r, input.dt)).collect();
        if let Some(prescribed) = input.creepage_x {
            xi = prescribed;
        }
        if let (StepSolver::GaussSeidel, ElasticModel::Exact(e)) = (self.solver, &self.model) {
            let cr0 = Creepage { x: 0.0, y: input.creepage_y, spin: input.spin };
            let w0: Vec<f64> = (0..n).flat_map(|k| self.rigid(k, frame, cr0)).collect();
            let mu_p3: Vec<f64> = p3.iter().map(|v| input.friction * v).collect();
            let step = gauss_seidel::GsStep {
                elastic: e,
                a: frame.a,
                dt: input.dt,
                speed: input.speed,
                eps: self.eps,
                local: &local,
                mu_p3: &mu_p3,
                area: &area,
                w0: &w0,
                u_o: &u_o,
                force_x: force,
                creepage_prescribed: input.creepage_x.is_some(),
                mu_n: input.friction * patch.normal_force,
                tol: self.tolerance * self.eps,
                max_sweeps: GS_MAX_SWEEPS,
                split: (self.mesh.ny / 2) * self.mesh.nx,
            };
            match gauss_seidel::solve(&step, &s, xi) {
                Ok(gs) => return Ok(self.finish(input, (frame, &local), p3, gs.p, gs.s, gs.xi, gs.sweeps)),
                Err(_) => self.fallbacks += 1,
            }
        }
        let pb = Problem { input, frame, p3: &p3, area: &area, u_o: &u_o, local: &local };
        let mut log = Vec::new();
        let (s_start, xi_start) = (s.clone(), xi);
        let mut iterations = 0;
        let mut solved: Option<Eval> = None;
        // The last factorised Jacobian is a good chord matrix for the next
        // step (the patch and the stick/slip pattern change little).
        let mut factor = self.factor.take();
        // A direct attempt at eps; if it fails, continuation from the warm
        // start through 100 eps and 10 eps down to eps.
        let attempts = [vec![self.eps], vec![100.0 * self.eps, 10.0 * self.eps, self.eps]];
        for (attempt, sequence) in attempts.iter().enumerate() {
            if attempt > 0 {
                s.clone_from(&s_start);
                xi = xi_start;
            }
            solved = None;
            for &eps in sequence {
                match self.newton(&pb, &mut s, &mut xi, eps, &mut factor) {
                    Ok((it, ev)) => {
                        iterations += it;
                        solved = Some(ev);
                    }
                    Err(h) => {
                        iterations += h.len();
                        log.push(format!(
                            "eps {eps:.1e}: max |R| {:.3e} -> {:.3e} m/s in {} iterations",
                            h[0],
                            h[h.len() - 1],
                            h.len()
                        ));
                        solved = None;
                        break;
                    }
                }
            }
            if solved.is_some() {
                break;
            }
        }
        // The last eps of every sequence is self.eps: `ev` is the converged
        // evaluation at the model's regularisation.
        let Some(ev) = solved else {
            return Err(ContactError::NoConvergence {
                force,
                reason: format!("Newton-Raphson on the local slips failed: {}", log.join("; ")),
            });
        };
        Ok(self.finish(input, (frame, &local), p3, ev.p, s, xi, iterations))
    }

    /// The solution of a converged step; keeps it as the next step's history.
    #[allow(clippy::too_many_arguments)]
    fn finish(
        &mut self,
        input: &StepInput,
        (frame, local): (PatchFrame, &[Local]),
        p3: Vec<f64>,
        p: Vec<f64>,
        s: Vec<f64>,
        xi: f64,
        iterations: usize,
    ) -> PatchSolution {
        let n = self.mesh.len();
        let mut sol = PatchSolution {
            creepage: Creepage { x: xi, y: input.creepage_y, spin: input.spin },
            pressure: p3,
            traction_x: (0..n).map(|k| p[2 * k]).collect(),
            traction_y: (0..n).map(|k| p[2 * k + 1]).collect(),
            slip_x: (0..n).map(|k| s[2 * k]).collect(),
            slip_y: (0..n).map(|k| s[2 * k + 1]).collect(),
            stick: (0..n).map(|k| s[2 * k].hypot(s[2 * k + 1]) < STICK_SLIP_FACTOR * self.eps).collect(),
            iterations,
            clipped: self.clipped,
            offset: self.moved.unwrap_or(0.0),
            semi_axes: self.moved.map(|_| (frame.a, frame.b)),
            ..Default::default()
        };
        sol.force_x = self.mesh.integrate(&sol.traction_x, frame.a, frame.b);
        sol.force_y = self.mesh.integrate(&sol.traction_y, frame.a, frame.b);
        // The coefficient each element's material leaves the step with.
        let kept = local
            .first()
            .is_some_and(|l| l.memory.is_some())
            .then(|| (0..n).map(|k| local[k].ratio(s[2 * k].hypot(s[2 * k + 1])).0).collect());
        self.history = Some(History { frame, offset: self.moved.unwrap_or(0.0), p, s, xi, kept });
        sol
    }
}

impl TangentialSolver for Transient {
    fn step(&mut self, input: &StepInput) -> Result<PatchSolution, ContactError> {
        self.solve_step(input)
    }

    fn reset(&mut self) {
        self.history = None;
        self.fallbacks = 0;
        self.factor = None;
        // The earlier-displacement cache too: a passage must not depend on
        // the ones before it (a resumed run starts with a fresh solver).
        if let ElasticModel::Exact(e) = &mut self.model {
            e.reset();
        }
    }

    fn elements(&self) -> Elements {
        Elements::Adapted(self.mesh.clone())
    }

    fn linear_resolution(&self, a: f64) -> Option<f64> {
        self.linear.resolution(a)
    }

    fn set_surface(&mut self, surface: Option<RailContact>) -> Result<(), ContactError> {
        self.linear.set_surface(surface)
    }
}

/// The ratio `mu / mu_0` the material at each element centre had one step
/// earlier: the field `old` of the previous patch (`frames` = (now, then))
/// at `(x + shift, y)`, linear between the centres along each strip and
/// between strips, 1 at the leading edge (fresh material) and outside.
fn kept_upstream(mesh: &EllipseMesh, (now, old): (PatchFrame, PatchFrame), shift: f64, kept: &[f64], out: &mut [f64]) {
    // The deviation from 1, interpolated as a traction field (zero at the
    // leading edge and outside).
    let deviation: Vec<f64> = kept.iter().flat_map(|r| [r - 1.0, 0.0]).collect();
    for (j, o) in out.iter_mut().enumerate() {
        let (x, y) = (mesh.xi[j] * now.a + shift, mesh.eta[j] * now.b);
        *o = 1.0 + elastic::interpolate(mesh, &deviation, x / old.a, y / old.b).0;
    }
}
