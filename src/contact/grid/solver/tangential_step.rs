//! The tangential problem of one step on the fixed grid: the elements in
//! contact, the earlier-displacement term (the stored fields shifted by
//! whole columns), the step's products, the CG solver with Gauss-Seidel
//! behind it, and the solution expanded back onto the whole grid.

use super::super::cg;
use super::super::coupling::Coupling;
use super::super::spec::{GRID_FORCE_TOLERANCE, GridScheme, GridSolver};
use super::super::tangential::{self, ContactSet, GridStep, Law};
use super::FixedGrid;
use super::on_set::{Layout, OnSet};
use crate::contact::friction::{STICK_SLIP_FACTOR, varying::frozen_jacobian};
use crate::contact::transient::GS_MAX_SWEEPS;
use crate::contact::{ContactError, Creepage, PatchSolution, StepInput};

/// A step's tangential solution.
pub(super) struct Solved {
    /// On the whole grid.
    pub out: PatchSolution,
    /// Slips kept for the next warm start, interleaved (m/s).
    pub s_grid: Vec<f64>,
    /// The displacement field `K p` on the whole grid (x, y) (m).
    pub u: (Vec<f64>, Vec<f64>),
    /// Whether the CG solver handed the step to Gauss-Seidel.
    pub fell_back: bool,
    /// Whether the CG solver tried the step.
    pub tried_cg: bool,
    /// With friction memory: the ratio `mu / mu_0` of every grid element
    /// at the end of the step (1 outside contact).
    pub kept: Option<Vec<f64>>,
}

/// The earlier-displacement term of a step and its warm start.
struct Earlier {
    /// `u~` at the elements in contact, interleaved (m).
    u_prev: Vec<f64>,
    /// Weight of the current displacement (1 or 3/2).
    beta: f64,
    /// Warm-start slips, interleaved (m/s).
    s0: Vec<f64>,
    /// Warm-start tractions, interleaved (Pa).
    p0: Vec<f64>,
    /// Warm-start creepage.
    xi0: f64,
    /// The ratio `mu / mu_0` each element's material kept from the last
    /// step (1 at a virgin start and where it was out of contact).
    kept: Vec<f64>,
}

impl FixedGrid {
    /// The tangential problem of a step on the pressure `p3` (symmetric
    /// about y = 0 where `folded`): the solution on the whole grid, the
    /// slips kept for the next warm start, the displacement field.
    pub(super) fn tangential_step(&self, input: &StepInput, p3: &[f64], folded: bool) -> Result<Solved, ContactError> {
        let force = input.force_x;
        let n_force = input.patch.normal_force;
        let (nx, ny, n) = (self.grid.nx, self.grid.ny, self.grid.len());
        let area = self.grid.area();
        let folded = self.folded.as_ref().filter(|_| folded);
        let mirror = |k: usize| (ny - 1 - k / nx) * nx + k % nx;
        let whole = ContactSet::new(nx, n, |k| p3[k] > 0.0);
        self.check_inside(&whole, input.position, n_force)
            .map_err(|reason| ContactError::NoConvergence { force, reason })?;
        let set = match folded {
            Some(f) => ContactSet::new(nx, f.half_rows() * nx, |k| p3[k] > 0.0),
            None => whole,
        };
        let weight: Vec<f64> =
            set.element.iter().map(|&k| if folded.is_some() && mirror(k) != k { 2.0 } else { 1.0 }).collect();
        let nc = set.len();
        let mu = input.friction;
        let mu_p3: Vec<f64> = set.element.iter().map(|&k| mu * p3[k]).collect();
        let w0: Vec<f64> = set
            .element
            .iter()
            .flat_map(|&k| {
                let (x, y) = (self.grid.x(k % nx), self.grid.y(k / nx));
                [-input.spin * y, input.creepage_y + input.spin * x]
            })
            .collect();
        let Earlier { u_prev, beta, s0, p0, xi0, kept } = self.earlier(&set);
        let xi0 = input.creepage_x.unwrap_or(xi0);
        let law = self.law();
        let coupling = match folded {
            Some(f) => Coupling::Folded(f),
            None => Coupling::Full(&self.kernel),
        };
        let mut step = GridStep {
            coupling,
            weight: &weight,
            set: &set,
            dt: input.dt,
            speed: input.speed,
            beta,
            law,
            characteristic: input.characteristic,
            memory: input.memory.filter(|_| !input.characteristic.is_constant()).map(|m| (kept.as_slice(), m)),
            mu_p3: &mu_p3,
            area,
            w0: &w0,
            u_prev: &u_prev,
            force_x: force,
            creepage_prescribed: input.creepage_x.is_some(),
            mu_n: mu * n_force,
            // Gauss-Seidel's creepage stiffness, set below where it runs.
            kappa: f64::NAN,
            tol: self.tolerance * self.spec.eps,
            max_sweeps: GS_MAX_SWEEPS,
            force_tol: GRID_FORCE_TOLERANCE,
        };
        // Exact products on the whole grid; the last one (the verdict's) is
        // the field the next step shifts.
        let shape = (nx, ny);
        // A folded grid's products by the symmetric transforms.
        let sym = self.symmetric.as_ref().filter(|_| folded.is_some());
        let mut exact =
            OnSet::new(&self.tangential, &set, &weight, shape, Layout::Blocks).symmetric(sym.map(|s| &s.exact));
        let mut fresh = |p: &[f64], u: &mut [f64]| exact.product(p, u);
        // The CG solver's inner products in single precision; its
        // preconditioner, the FFT inverse on the unpadded grid.
        // On the contact block where it is much smaller than the grid (the
        // CG solver's products only).
        // Under a falling friction characteristic CG may be paused after it
        // stalled ([`super::CgPause`]).
        let newton_krylov = self.spec.solver.resolve() == GridSolver::Cg && self.cg_pause.skip == 0;
        let block = sym.filter(|_| newton_krylov).and_then(|_| self.blocks.for_set(&self.kernel, &set, shape));
        let single = OnSet::new(&self.tangential_single, &set, &weight, shape, Layout::Blocks);
        let pre = OnSet::new(&self.inverse_single, &set, &weight, shape, Layout::Interleaved);
        // An unfolded step's block, its products general.
        let full_block = (sym.is_none() && newton_krylov)
            .then(|| self.full_blocks.for_full_set(&self.kernel, &set, shape))
            .flatten();
        let (mut single, mut pre) = match (&block, &full_block) {
            (Some((origin, products)), _) => {
                (single.on_block(&products.0, *origin), pre.on_block(&products.1, *origin))
            }
            (None, Some((origin, products))) => {
                (single.on_full_block(&products.0, *origin), pre.on_full_block(&products.1, *origin))
            }
            (None, None) => (single.symmetric(sym.map(|s| &s.single)), pre.symmetric(sym.map(|s| &s.inverse))),
        };
        let mut inner = |p: &[f64], u: &mut [f64]| single.product(p, u);
        let mut inverse = |r: &[f64], z: &mut [f64]| pre.product(r, z);
        // The CG solver's law: exact Coulomb friction as the regularised
        // law's limit.
        let cg_step = match law {
            Law::Coulomb => GridStep { law: Law::Regularised { eps: cg::COULOMB_LIMIT * self.spec.eps }, ..step },
            Law::Regularised { .. } => GridStep { ..step },
        };
        // A step CG does not converge goes to Gauss-Seidel; its products
        // count in the step's iterations, and its failure in the report.
        let mut cg_failed: Option<(Vec<f64>, usize)> = None;
        let mut solved =
            match newton_krylov.then(|| cg::solve(&cg_step, &s0, &p0, xi0, &mut fresh, (&mut inner, &mut inverse))) {
                Some(Ok(sol)) => Some(Ok(sol)),
                Some(Err(failure)) => {
                    cg_failed = Some(match failure {
                        cg::CgFailure::NoConvergence { history, products } => (history, products),
                        cg::CgFailure::Coulomb => (Vec::new(), 0),
                    });
                    None
                }
                None => None,
            };
        if solved.is_none() {
            step.kappa = self.creepage_stiffness(&mut fresh, &step, &s0, input);
            let before = cg_failed.as_ref().map_or(0, |f| f.1);
            solved = Some(tangential::solve(&step, &s0, xi0, &mut fresh).map(|mut sol| {
                sol.sweeps += before;
                sol
            }));
        }
        let solved = solved.expect("one of the solvers ran");
        let fell_back = cg_failed.is_some();
        let sol = solved.map_err(|history| {
            let last = history.last().copied().unwrap_or(f64::NAN);
            let cg = match &cg_failed {
                Some((h, products)) => format!(
                    "the CG solver did not converge in {} Newton iterations ({products} products, max |R| {:.3e} -> {:.3e} m/s), then ",
                    h.len(),
                    h.first().copied().unwrap_or(f64::NAN),
                    h.last().copied().unwrap_or(f64::NAN)
                ),
                None => String::new(),
            };
            ContactError::NoConvergence {
                force,
                reason: format!(
                    "{cg}Gauss-Seidel on the fixed grid ({nc} elements in contact) did not converge in {} sweeps: max |R| {:.3e} -> {:.3e} m/s (tolerance {:.1e})",
                    history.len(),
                    history.first().copied().unwrap_or(f64::NAN),
                    last,
                    step.tol
                ),
            }
        })?;
        // The stick test of the law that solved the step: CG's limit of
        // exact Coulomb friction leaves stick slips of up to hundreds of its
        // eps (where |p| nears mu p3); below the kinematic tolerance a slip
        // is zero to the solver's precision.
        let solved_law = match (law, newton_krylov && !fell_back) {
            (Law::Coulomb, true) => Law::Regularised { eps: step.tol / STICK_SLIP_FACTOR },
            _ => law,
        };
        // The coefficient each element's material leaves the step with.
        let kept = step.memory.map(|_| {
            let mut grid = vec![1.0; n];
            for (c, &k) in set.element.iter().enumerate() {
                let r = step.local(c).ratio(sol.s[2 * c].hypot(sol.s[2 * c + 1])).0;
                grid[k] = r;
                if folded.is_some() {
                    grid[mirror(k)] = r;
                }
            }
            grid
        });
        let (mut out, s_grid) = self.expand((input, solved_law), &set, &weight, p3, &sol);
        out.fallback = fell_back;
        Ok(Solved { out, s_grid, u: exact.whole(), fell_back, tried_cg: newton_krylov, kept })
    }

    /// The earlier-displacement term `u~` and weight `beta` of the
    /// difference at the elements of `set` (the stored fields shifted by
    /// one and two columns), and the warm start (the last step's slips at
    /// the same elements, its creepage). A virgin start: zeros, beta = 1.
    fn earlier(&self, set: &ContactSet) -> Earlier {
        let (nx, nc) = (self.grid.nx, set.len());
        let mut e = Earlier {
            u_prev: vec![0.0; 2 * nc],
            beta: 1.0,
            s0: vec![0.0; 2 * nc],
            p0: vec![0.0; 2 * nc],
            xi0: 0.0,
            kept: vec![1.0; nc],
        };
        let Some(h) = &self.history else {
            return e;
        };
        let at = |f: &(Vec<f64>, Vec<f64>), k: usize, back: usize| (f.0[k - back], f.1[k - back]);
        let order = match self.spec.scheme {
            GridScheme::FirstOrder => 1,
            GridScheme::SecondOrder => 2,
            GridScheme::ThirdOrder => 3,
        };
        let level = match (&h.older, &h.oldest) {
            (Some(_), Some(_)) => order.min(3),
            (Some(_), None) => order.min(2),
            _ => 1,
        };
        for (c, &k) in set.element.iter().enumerate() {
            debug_assert!(k % nx >= level, "kept off the leading edge by check_inside");
            let (ox, oy) = at(&h.u, k, 1);
            let (ux, uy) = match level {
                3 => {
                    let (qx, qy) = at(h.older.as_ref().expect("level 3"), k, 2);
                    let (rx, ry) = at(h.oldest.as_ref().expect("level 3"), k, 3);
                    (3.0 * ox - 1.5 * qx + rx / 3.0, 3.0 * oy - 1.5 * qy + ry / 3.0)
                }
                2 => {
                    let (qx, qy) = at(h.older.as_ref().expect("level 2"), k, 2);
                    (2.0 * ox - 0.5 * qx, 2.0 * oy - 0.5 * qy)
                }
                _ => (ox, oy),
            };
            e.u_prev[2 * c] = ux;
            e.u_prev[2 * c + 1] = uy;
            e.s0[2 * c] = h.s[2 * k];
            e.s0[2 * c + 1] = h.s[2 * k + 1];
            e.p0[2 * c] = h.p[2 * k];
            e.p0[2 * c + 1] = h.p[2 * k + 1];
            // Carried with the material: one column upstream.
            if let Some(kept) = &h.kept {
                e.kept[c] = kept[k - 1];
            }
        }
        e.beta = [1.0, 1.5, 11.0 / 6.0][level - 1];
        e.xi0 = h.xi;
        e
    }

    /// The step's solution on the whole grid (zero outside contact; a
    /// folded element and its mirror image, y components negated; stick by
    /// `law`, the law that solved it) and the slips kept for the next warm
    /// start.
    fn expand(
        &self,
        (input, law): (&StepInput, Law),
        set: &ContactSet,
        weight: &[f64],
        p3: &[f64],
        sol: &tangential::GridSolution,
    ) -> (PatchSolution, Vec<f64>) {
        let (nx, ny, n) = (self.grid.nx, self.grid.ny, self.grid.len());
        let mut out = PatchSolution {
            creepage: Creepage { x: sol.xi, y: input.creepage_y, spin: input.spin },
            pressure: p3.to_vec(),
            traction_x: vec![0.0; n],
            traction_y: vec![0.0; n],
            slip_x: vec![0.0; n],
            slip_y: vec![0.0; n],
            stick: vec![false; n],
            iterations: sol.sweeps,
            ..Default::default()
        };
        let mut s_grid = vec![0.0; 2 * n];
        for (c, &k) in set.element.iter().enumerate() {
            let (sx, sy) = (sol.s[2 * c], sol.s[2 * c + 1]);
            let stick = law.is_stick([sx, sy]);
            let mirror = (ny - 1 - k / nx) * nx + k % nx;
            let images: &[(usize, f64)] = if weight[c] == 2.0 { &[(k, 1.0), (mirror, -1.0)] } else { &[(k, 1.0)] };
            for &(e, sign) in images {
                out.traction_x[e] = sol.p[2 * c];
                out.traction_y[e] = sign * sol.p[2 * c + 1];
                out.slip_x[e] = sx;
                out.slip_y[e] = sign * sy;
                out.stick[e] = stick;
                s_grid[2 * e] = sx;
                s_grid[2 * e + 1] = sign * sy;
            }
        }
        let area = self.grid.area();
        out.force_x = out.traction_x.iter().sum::<f64>() * area;
        out.force_y = out.traction_y.iter().sum::<f64>() * area;
        (out, s_grid)
    }

    /// dF_x/dxi_x estimate (N), as the adapted solver's: the stick area
    /// (|s| < 10 eps at the warm start) answers a uniform slip change with
    /// the uniform traction change that cancels it through its mean row sum
    /// of `(beta/dt) K_xx` (one product, `product(p, u)` as the step's:
    /// interleaved tractions on `set`, displacements x block then y block);
    /// slip elements answer through their own law's derivative.
    fn creepage_stiffness(
        &self,
        product: &mut dyn FnMut(&[f64], &mut [f64]),
        step: &GridStep,
        s: &[f64],
        input: &StepInput,
    ) -> f64 {
        let (set, weight, mu_p3, beta) = (step.set, step.weight, step.mu_p3, step.beta);
        let nc = set.len();
        let eps = self.spec.eps;
        let scale = beta / input.dt;
        let stick: Vec<bool> = (0..nc).map(|c| s[2 * c].hypot(s[2 * c + 1]) < STICK_SLIP_FACTOR * eps).collect();
        let unit: Vec<f64> = stick.iter().flat_map(|&st| [if st { 1.0 } else { 0.0 }, 0.0]).collect();
        let mut u = vec![0.0; 2 * nc];
        product(&unit, &mut u);
        let count: f64 = (0..nc).filter(|&c| stick[c]).map(|c| weight[c]).sum();
        let mut kappa = 0.0;
        let area = self.grid.area();
        if count > 0.0 {
            let rows: f64 = (0..nc).filter(|&c| stick[c]).map(|c| weight[c] * scale * u[c]).sum();
            kappa += count * area / (rows / count);
        }
        let k0 = scale * self.kernel.at(0, 0, 0);
        for c in 0..nc {
            if !stick[c] {
                let d = frozen_jacobian([s[2 * c], s[2 * c + 1]], mu_p3[c], eps, step.local(c));
                kappa += weight[c] * area * d[0] / (1.0 + k0 * d[0]);
            }
        }
        -input.speed * kappa.max(1e-30)
    }
}
