//! The transient tangential problem of one step on the elements in contact
//! of the fixed grid, with the longitudinal force prescribed (Kalker 1990,
//! ch. 5; Baeza et al. 2008, Eqs. 3-7 on CONTACT's grid):
//!
//! ```text
//! s_I = V w_I(xi) + (beta u_I - u~_I) / dt,    u = K p,
//! ```
//!
//! `w_I = (xi - phi y_I, eta + phi x_I)` the rigid slip per unit speed, `K`
//! the tangential influence coefficients ([`super::convolution`]) and
//! `(beta, u~)` the backward difference of the material derivative: first
//! order `(1, u_o)` or second order `(3/2, 2 u_o - u_oo / 2)` with `u_o`,
//! `u_oo` the displacements the material had one and two steps earlier
//! ([`super::solver`]). The friction law is one of [`Law`]
//! ([`crate::contact::friction`]): the paper's regularised law or exact
//! Coulomb friction.
//!
//! **Solver.** Element-wise nonlinear Gauss-Seidel (Kalker 1990, ch. 5;
//! Vollebregt's ConvexGS), as the adapted model's solver
//! ([`crate::contact::transient::gauss_seidel`]): each element's 2 x 2
//! problem `s = s0 + (beta/dt) K_0 p(s)` solved exactly for its law, rows
//! from the leading edge, the creepage updated after each sweep from the
//! force residual, Anderson acceleration of the whole (the loop shared with
//! the adapted mesh, [`crate::contact::gs_loop`]). On the grid the
//! displacement update of an element is a contiguous run of the
//! coefficient table per row of the contact area (the table, three
//! components of `(2 nx - 1)(2 ny - 1)`, stays in cache where the
//! adapted mesh's 2N x 2N matrix does not).
//! Both laws' element problems are solved to rounding
//! ([`Law::element_solve`]).

use super::coupling::Coupling;
pub use crate::contact::friction::{Characteristic, Law};
use crate::contact::friction::{FrictionMemory, Local};
use crate::contact::gs_loop::{self, Settings, Sweeper};
use multiversion::multiversion;

/// A contiguous run of elements in contact in one grid row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Run {
    /// Grid row.
    pub iy: usize,
    /// First grid column.
    pub ix0: usize,
    /// Number of elements.
    pub len: usize,
    /// Index of its first element in the contact order.
    pub c0: usize,
}

/// The elements in contact, in sweep order (rows, each from the leading
/// edge), and their runs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ContactSet {
    /// Grid index of each element in contact.
    pub element: Vec<usize>,
    /// Column of each.
    pub ix: Vec<usize>,
    /// Row of each.
    pub iy: Vec<usize>,
    /// The runs.
    pub runs: Vec<Run>,
}

impl ContactSet {
    /// The elements of an `nx`-column grid where `inside` holds.
    pub fn new(nx: usize, n: usize, inside: impl Fn(usize) -> bool) -> Self {
        let mut set = ContactSet::default();
        for k in 0..n {
            if inside(k) {
                let (ix, iy) = (k % nx, k / nx);
                let c = set.element.len();
                match set.runs.last_mut() {
                    Some(r) if r.iy == iy && r.ix0 + r.len == ix => r.len += 1,
                    _ => set.runs.push(Run { iy, ix0: ix, len: 1, c0: c }),
                }
                set.element.push(k);
                set.ix.push(ix);
                set.iy.push(iy);
            }
        }
        set
    }

    /// Number of elements in contact.
    pub fn len(&self) -> usize {
        self.element.len()
    }

    /// Whether no element is in contact.
    pub fn is_empty(&self) -> bool {
        self.element.is_empty()
    }
}

/// The data of one step, on the elements in contact (contact order).
pub struct GridStep<'a> {
    /// How a traction change reaches the displacements (the whole contact
    /// area, or the folded lower half of a symmetric problem).
    pub coupling: Coupling<'a>,
    /// How many grid elements each element in contact stands for (1, or 2
    /// for a folded element and its mirror).
    pub weight: &'a [f64],
    /// The elements in contact.
    pub set: &'a ContactSet,
    /// Time step (s).
    pub dt: f64,
    /// Rolling speed V (m/s).
    pub speed: f64,
    /// Weight of the current displacement in the difference (1 or 3/2).
    pub beta: f64,
    /// The friction law.
    pub law: Law,
    /// How its coefficient varies with the slip speed.
    pub characteristic: Characteristic,
    /// Friction memory: the ratio `mu / mu_0` each element's material had
    /// one step earlier (1), and the memory's parameters.
    pub memory: Option<(&'a [f64], FrictionMemory)>,
    /// mu p3 per element (Pa).
    pub mu_p3: &'a [f64],
    /// Element area (m^2).
    pub area: f64,
    /// Rigid slip per unit speed with xi_x = 0, interleaved (1).
    pub w0: &'a [f64],
    /// Earlier displacement term u~ (m), interleaved.
    pub u_prev: &'a [f64],
    /// Prescribed F_x (N).
    pub force_x: f64,
    /// Whether the creepage is prescribed instead (the warm start's is
    /// kept; `force_x` unused).
    pub creepage_prescribed: bool,
    /// mu N (N), the force scale.
    pub mu_n: f64,
    /// dF_x / dxi_x estimate (N), negative.
    pub kappa: f64,
    /// Tolerance on the kinematic residual (m/s).
    pub tol: f64,
    /// Tolerance on the force residual |F - F_x| / (mu N).
    pub force_tol: f64,
    /// Most sweeps before giving up.
    pub max_sweeps: usize,
}

impl GridStep<'_> {
    /// The friction characteristic of element `c` (contact order) in this
    /// step: the steady one, with the element's memory.
    pub fn local(&self, c: usize) -> Local {
        match self.memory {
            Some((kept, m)) => Local::new(self.characteristic, Some(m), kept[c], self.dt),
            None => self.characteristic.into(),
        }
    }
}

/// Converged state of one step, on the elements in contact.
#[derive(Debug, Clone)]
pub struct GridSolution {
    /// Tractions (Pa), interleaved.
    pub p: Vec<f64>,
    /// Slips (m/s), interleaved.
    pub s: Vec<f64>,
    /// Creepage xi_x.
    pub xi: f64,
    /// Displacements `K p` at the elements (m), x then y blocks.
    pub u: Vec<f64>,
    /// Sweeps done (Gauss-Seidel), or FFT products used ([`super::cg`]).
    pub sweeps: usize,
}

/// Solves the step from the warm start (slips `s`, creepage `xi`).
/// `fresh(p, u)` computes `u = K p` at the elements in contact exactly
/// (x block then y block); the verdict is always taken on it. Err holds the
/// largest kinematic residual (m/s) of every sweep.
pub fn solve(
    st: &GridStep,
    s: &[f64],
    xi: f64,
    fresh: &mut dyn FnMut(&[f64], &mut [f64]),
) -> Result<GridSolution, Vec<f64>> {
    let n = st.set.len();
    let p: Vec<f64> =
        (0..n).flat_map(|c| st.law.traction([s[2 * c], s[2 * c + 1]], st.mu_p3[c], st.local(c))).collect();
    let p_scale = st.mu_p3.iter().fold(0.0f64, |m, v| m.max(*v)).max(f64::MIN_POSITIVE);
    let settings = Settings {
        depth: GRID_DEPTH,
        max_sweeps: st.max_sweeps,
        tol: st.tol,
        force_tol: st.force_tol,
        force_x: st.force_x,
        creepage_prescribed: st.creepage_prescribed,
        mu_n: st.mu_n,
        kappa: st.kappa,
        p_scale,
        xi_scale: (st.kappa.abs() / (n as f64 * st.area * p_scale)).max(f64::MIN_POSITIVE),
    };
    let solved = gs_loop::solve(st, &settings, p, s.to_vec(), xi, fresh)?;
    Ok(GridSolution { p: solved.p, s: solved.s, xi: solved.xi, u: solved.u, sweeps: solved.sweeps })
}

impl Sweeper for GridStep<'_> {
    fn sweep(&self, p: &mut [f64], s: &mut [f64], u: &mut [f64], xi: f64) {
        sweep(self, p, s, u, xi);
    }

    fn residual(&self, s: &[f64], u: &[f64], xi: f64) -> f64 {
        residual(self, s, u, xi)
    }

    fn force(&self, p: &[f64]) -> f64 {
        (0..self.set.len()).map(|c| self.weight[c] * p[2 * c]).sum::<f64>() * self.area
    }
}

/// Anderson depth of the grid solver: deeper than the adapted mesh's (6),
/// whose mixing cost weighs more there; on paper_normal_30mm at the default
/// grid 6, 10, 15, 20 and 30 pairs need 42, 35, 32, 31 and 30 sweeps per
/// step, and 16 takes a fifth off the passage's time.
pub const GRID_DEPTH: usize = 16;

/// Elements (solved: half the contact area of a folded problem) from which a
/// sweep runs in two parallel halves. Below, a sweep is too short for the
/// threads' wake-ups (about a fifth of the time at 0.4 mm elements with 128:
/// growth_exact 7.0 -> 5.3 s for 5 passages, paper_normal_30mm 1.48 -> 1.20 s).
const PARALLEL_MIN: usize = 400;

/// One Gauss-Seidel sweep over the elements in contact at creepage `xi`.
/// From [`PARALLEL_MIN`] elements the two halves of the rows sweep in
/// parallel, each against its own copy of the displacements (Jacobi between
/// the halves, Gauss-Seidel within), then `u = u_a + u_b - u_0`: a fixed
/// split and a fixed order of the sums, so the result does not depend on
/// the threads.
fn sweep(st: &GridStep, p: &mut [f64], s: &mut [f64], u: &mut [f64], xi: f64) {
    let n = st.set.len();
    if n < PARALLEL_MIN {
        sweep_block(st, 0, p, s, u, xi);
        return;
    }
    // Split at the run boundary nearest the middle.
    let m = st.set.runs.iter().map(|r| r.c0).min_by_key(|c| c.abs_diff(n / 2)).unwrap_or(0);
    let (pa, pb) = p.split_at_mut(2 * m);
    let (sa, sb) = s.split_at_mut(2 * m);
    let (mut ua, mut ub) = (u.to_vec(), u.to_vec());
    rayon::join(|| sweep_block(st, 0, pa, sa, &mut ua, xi), || sweep_block(st, m, pb, sb, &mut ub, xi));
    for ((u0, a), b) in u.iter_mut().zip(&ua).zip(&ub) {
        *u0 = a + b - *u0;
    }
}

/// Gauss-Seidel over the elements `first ..` (contact order) whose tractions
/// and slips are `p` and `s`, updating the displacements `u` of the whole
/// contact area (x block, y block).
fn sweep_block(st: &GridStep, first: usize, p: &mut [f64], s: &mut [f64], u: &mut [f64], xi: f64) {
    let n = st.set.len();
    let k = st.coupling;
    let nx = k.nx() as isize;
    let scale = st.beta / st.dt;
    for local in 0..p.len() / 2 {
        let c = first + local;
        let (i, j) = (2 * c, 2 * c + 1);
        let (li, lj) = (2 * local, 2 * local + 1);
        let (ixj, iyj) = (st.set.ix[c] as isize, st.set.iy[c]);
        let kk = k.own(iyj).map(|v| scale * v);
        let own = [kk[0] * p[li] + kk[1] * p[lj], kk[1] * p[li] + kk[2] * p[lj]];
        let s0 = [
            st.speed * (st.w0[i] + xi) + (st.beta * u[c] - st.u_prev[i]) / st.dt - own[0],
            st.speed * st.w0[j] + (st.beta * u[n + c] - st.u_prev[j]) / st.dt - own[1],
        ];
        let (sk, pk) = st.law.element_solve(s0, kk, st.mu_p3[c], [s[li], s[lj]], st.local(c));
        s[li] = sk[0];
        s[lj] = sk[1];
        let (dx, dy) = (pk[0] - p[li], pk[1] - p[lj]);
        p[li] = pk[0];
        p[lj] = pk[1];
        if dx == 0.0 && dy == 0.0 {
            continue;
        }
        let (ux, uy) = u.split_at_mut(n);
        for r in &st.set.runs {
            let rows = k.rows(r.iy, iyj);
            let o = (r.ix0 as isize - ixj + nx - 1) as usize;
            let range = r.c0..r.c0 + r.len;
            let seg = |c: usize| &rows[c][o..o + r.len];
            add_run((&mut ux[range.clone()], &mut uy[range]), [seg(0), seg(1), seg(2), seg(3)], dx, dy);
        }
    }
}

/// `u_x += F_xx dx + F_x<-y dy`, `u_y += F_y<-x dx + F_yy dy` along one run:
/// the inner loop of a sweep. Compiled also for AVX2 and picked at run time
/// (`multiversion`), without fused multiply-adds, so that every target
/// gives the same bits.
#[multiversion(targets("x86_64+avx2"))]
fn add_run((ux, uy): (&mut [f64], &mut [f64]), [fxx, fxy, fyx, fyy]: [&[f64]; 4], dx: f64, dy: f64) {
    let coupling = fxx.iter().zip(fxy).zip(fyx.iter().zip(fyy));
    for ((a, b), ((xx, xy), (yx, yy))) in ux.iter_mut().zip(uy.iter_mut()).zip(coupling) {
        *a += xx * dx + xy * dy;
        *b += yx * dx + yy * dy;
    }
}

/// Largest kinematic residual (m/s) of slips `s` and displacements `u`.
pub fn residual(st: &GridStep, s: &[f64], u: &[f64], xi: f64) -> f64 {
    (0..st.set.len())
        .map(|c| {
            let [rx, ry] = kinematic_residual(st, s, u, xi, c);
            rx.abs().max(ry.abs())
        })
        .fold(0.0, f64::max)
}

/// The kinematic residual `s - V w(xi) - (beta u - u~) / dt` (m/s) of
/// element `c` (contact order), `u` in blocks (x then y).
pub fn kinematic_residual(st: &GridStep, s: &[f64], u: &[f64], xi: f64, c: usize) -> [f64; 2] {
    let (n, i, j) = (st.set.len(), 2 * c, 2 * c + 1);
    [
        s[i] - st.speed * (st.w0[i] + xi) - (st.beta * u[c] - st.u_prev[i]) / st.dt,
        s[j] - st.speed * st.w0[j] - (st.beta * u[n + c] - st.u_prev[j]) / st.dt,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contact_set_runs() {
        // 4 columns; elements 1, 2, 5, 7 (row 1: 5 and 7 are separate runs).
        let set = ContactSet::new(4, 8, |k| [1, 2, 5, 7].contains(&k));
        assert_eq!(set.element, vec![1, 2, 5, 7]);
        assert_eq!(
            set.runs,
            vec![
                Run { iy: 0, ix0: 1, len: 2, c0: 0 },
                Run { iy: 1, ix0: 1, len: 1, c0: 2 },
                Run { iy: 1, ix0: 3, len: 1, c0: 3 }
            ]
        );
    }
}
