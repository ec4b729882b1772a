//! FASTSIM: Kalker's fast algorithm for the simplified theory of steady
//! rolling contact (J.J. Kalker, *A fast algorithm for the simplified theory
//! of rolling contact*, Vehicle System Dynamics 11 (1982) 1-13).
//!
//! Simplified (Winkler) elastic model: the displacement difference is `L p`.
//! In steady rolling the slip of the wheel relative to the rail is
//! `s = V (w - L dp/dx)` with rigid slip `w = (xi_x - phi y, xi_y + phi x)`.
//! Marching along each strip from the leading edge (p = 0) towards the trailing
//! edge, the adhesion trial traction is `p_tr(x - dx) = p(x) - (w / L) dx`;
//! where `|p_tr|` exceeds the traction bound `g = mu p3` the traction is
//! `g p_tr / |p_tr|` and the slip is `s = V L (p - p_tr) / dx` (opposite to p).
//!
//! Flexibility (Kalker 1982, weighted over the creepage components):
//! `L = (|xi_x| L1 + |xi_y| L2 + c |phi| L3) / sqrt(xi_x^2 + xi_y^2 + c^2 phi^2)`,
//! `c = sqrt(a b)`, with `L1 = 8a / (3 C11 G)`, `L2 = 8a / (3 C22 G)`,
//! `L3 = pi a sqrt(a/b) / (4 C23 G)` (so that FASTSIM reproduces Kalker's
//! linear theory at vanishing creepage). Tractions are evaluated at element
//! centres: the first step from the leading edge is half an element, the
//! others one element.
//!
//! Traction bound: Kalker's original parabolic pressure (default) or the
//! Hertzian (elliptic) one; the pressure reported and used for wear is the
//! one the bound is built on.
//!
//! Force control: the creepage xi_x that gives the prescribed F_x is found by
//! Brent's method on a bracket grown from the linear-theory estimate
//! `xi = -F_x / (G a b C11)`.

use super::friction::{Characteristic, FrictionMemory, Local, coulomb_local_with};
use super::linear::{LinearContact, LinearPatch};
use super::mesh::{EllipseMesh, PressureShape, pressure_on_mesh};
use super::{ContactError, Creepage, Elements, PatchSolution, RailContact, StepInput, TangentialSolver};
use crate::creep_coefficients::CreepCoefficients;
use crate::hertz::HertzPatch;
use crate::numerics::{Tolerance, brent};
use std::f64::consts::PI;

/// FASTSIM with a fixed mesh and creep coefficients.
#[derive(Debug, Clone)]
pub struct Fastsim {
    mesh: EllipseMesh,
    shape: PressureShape,
    coefficients: CreepCoefficients,
    shear_modulus: f64,
    /// The linear profile contact (empty unless built with one).
    linear: LinearContact,
}

/// The three flexibilities (m/Pa).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flexibilities {
    /// L1 (longitudinal).
    pub l1: f64,
    /// L2 (lateral).
    pub l2: f64,
    /// L3 (spin).
    pub l3: f64,
}

impl Fastsim {
    /// The mesh the fields are given on.
    pub fn mesh(&self) -> &EllipseMesh {
        &self.mesh
    }

    /// FASTSIM on an `nx` x `ny` Paul-Hashemi mesh. `coefficients` come from
    /// Kalker's table for the patch's a/b and nu; `shear_modulus` G in Pa.
    pub fn new(
        nx: usize,
        ny: usize,
        shape: PressureShape,
        coefficients: CreepCoefficients,
        shear_modulus: f64,
    ) -> Self {
        Fastsim { mesh: EllipseMesh::new(nx, ny), shape, coefficients, shear_modulus, linear: LinearContact::default() }
    }

    /// Lets the model take the rail surface into its traction bound by the
    /// linear profile contact ([`super::linear`]): the patch moved and
    /// stretched with the surface, the bound `mu p` with `p` the model's
    /// pressure shape on it plus the rest of the exact elastic response. `shape` is the Hertz contact's.
    pub fn with_linear_contact(mut self, shape: &crate::hertz::HertzShape) -> Self {
        self.linear = LinearContact::new(&self.mesh, shape);
        self
    }

    /// Flexibilities for the patch semi-axes (m).
    pub fn flexibilities(&self, a: f64, b: f64) -> Flexibilities {
        let g = self.shear_modulus;
        let c = &self.coefficients;
        Flexibilities {
            l1: 8.0 * a / (3.0 * c.c11 * g),
            l2: 8.0 * a / (3.0 * c.c22 * g),
            l3: PI * a * (a / b).sqrt() / (4.0 * c.c23 * g),
        }
    }

    /// Solves the steady problem with all creepages prescribed (the
    /// model's pressure shape on the Hertz patch).
    pub fn solve_creepage(&self, patch: &HertzPatch, creepage: Creepage, friction: f64, speed: f64) -> PatchSolution {
        self.solve_creepage_with(patch, creepage, (friction, Characteristic::Constant, None), speed)
    }

    /// [`solve_creepage`](Fastsim::solve_creepage) with the friction
    /// coefficient at zero slip varying with the slip speed as `ch` does,
    /// with or without memory (each cell remembers its upstream
    /// neighbour's coefficient, `dt` = the cell's length / V).
    pub fn solve_creepage_with(
        &self,
        patch: &HertzPatch,
        creepage: Creepage,
        (friction, ch, memory): (f64, Characteristic, Option<FrictionMemory>),
        speed: f64,
    ) -> PatchSolution {
        let pressure = pressure_on_mesh(&self.mesh, self.shape, patch.normal_force, patch.a, patch.b);
        self.solve_with_pressure(patch, pressure, creepage, (friction, ch, memory), speed)
    }

    /// The patch and pressure of a step: the Hertz patch and the shape's
    /// pressure, or with the rail surface in the linear profile contact the
    /// patch moved with it and its first-order pressure
    /// ([`MeshResponse::linear_patch`]).
    fn step_patch(&self, input: &StepInput) -> Result<(HertzPatch, Vec<f64>, Option<LinearPatch>), ContactError> {
        let patch = input.patch;
        Ok(match self.linear.patch(input.position, &patch, self.shape, &self.mesh, false)? {
            Some(mut lp) => (HertzPatch { a: lp.a, b: lp.b, ..patch }, std::mem::take(&mut lp.pressure), Some(lp)),
            None => (patch, pressure_on_mesh(&self.mesh, self.shape, patch.normal_force, patch.a, patch.b), None),
        })
    }

    /// Solves the steady problem with all creepages prescribed and the
    /// pressure `pressure` (Pa, at the element centres) as the traction
    /// bound's.
    fn solve_with_pressure(
        &self,
        patch: &HertzPatch,
        pressure: Vec<f64>,
        creepage: Creepage,
        (friction, ch, memory): (f64, Characteristic, Option<FrictionMemory>),
        speed: f64,
    ) -> PatchSolution {
        let m = &self.mesh;
        let (a, b) = (patch.a, patch.b);
        let flex = self.flexibilities(a, b);
        let c = (a * b).sqrt();
        let norm = (creepage.x.powi(2) + creepage.y.powi(2) + (c * creepage.spin).powi(2)).sqrt();
        let l = if norm > 0.0 {
            (creepage.x.abs() * flex.l1 + creepage.y.abs() * flex.l2 + c * creepage.spin.abs() * flex.l3) / norm
        } else {
            flex.l1
        };
        let n = m.len();
        let mut sol = PatchSolution {
            creepage,
            pressure,
            traction_x: vec![0.0; n],
            traction_y: vec![0.0; n],
            slip_x: vec![0.0; n],
            slip_y: vec![0.0; n],
            stick: vec![true; n],
            ..Default::default()
        };
        for j in 0..m.ny {
            let y = m.eta[j * m.nx] * b;
            let mut x_prev = m.half_chord[j] * a;
            let (mut px, mut py) = (0.0, 0.0);
            // Fresh material enters at the leading edge with the static
            // coefficient.
            let mut kept = 1.0;
            for i in 0..m.nx {
                let k = j * m.nx + i;
                let x = m.xi[k] * a;
                let step = x_prev - x;
                let x_mid = 0.5 * (x_prev + x);
                let wx = creepage.x - creepage.spin * y;
                let wy = creepage.y + creepage.spin * x_mid;
                let tx = px - wx / l * step;
                let ty = py - wy / l * step;
                let bound = friction * sol.pressure[k];
                let mag = tx.hypot(ty);
                if !ch.is_constant() {
                    // The cell's slip s = K (p - t), K = V L / dx: the
                    // element problem under Coulomb friction (Giménez,
                    // Alonso & Gómez, Veh. Syst. Dyn. 43 (2005) 233-244:
                    // the coefficient of the cell's own slip speed).
                    let kk = speed * l / step;
                    let local = Local::new(ch, memory, kept, step / speed);
                    let (s, p) = coulomb_local_with([-kk * tx, -kk * ty], [kk, 0.0, kk], bound, local);
                    kept = local.ratio(s[0].hypot(s[1])).0;
                    (px, py) = (p[0], p[1]);
                    (sol.slip_x[k], sol.slip_y[k]) = (s[0], s[1]);
                    sol.stick[k] = s == [0.0; 2];
                } else if mag > bound {
                    px = bound * tx / mag;
                    py = bound * ty / mag;
                    sol.slip_x[k] = speed * l * (px - tx) / step;
                    sol.slip_y[k] = speed * l * (py - ty) / step;
                    sol.stick[k] = false;
                } else {
                    px = tx;
                    py = ty;
                }
                sol.traction_x[k] = px;
                sol.traction_y[k] = py;
                x_prev = x;
            }
        }
        sol.force_x = m.integrate(&sol.traction_x, a, b);
        sol.force_y = m.integrate(&sol.traction_y, a, b);
        sol
    }

    /// Solves with the longitudinal force prescribed (lateral creepage and
    /// spin prescribed), finding xi_x; or, with the longitudinal creepage
    /// prescribed too, at that creepage.
    pub fn solve_force(&self, input: &StepInput) -> Result<PatchSolution, ContactError> {
        input.check_friction_limit()?;
        let (moved, pressure, moved_by) = self.step_patch(input)?;
        let patch = &moved;
        let limit = input.friction * patch.normal_force;
        let force = input.force_x;
        let at = |xi: f64| {
            let cr = Creepage { x: xi, y: input.creepage_y, spin: input.spin };
            let mut s = self.solve_with_pressure(
                patch,
                pressure.clone(),
                cr,
                (input.friction, input.characteristic, input.memory),
                input.speed,
            );
            if let Some(lp) = &moved_by {
                s.clipped = lp.clipped;
                s.offset = lp.offset;
                s.semi_axes = Some((lp.a, lp.b));
            }
            s
        };
        if let Some(xi) = input.creepage_x {
            return Ok(at(xi));
        }
        let residual = |xi: f64| (at(xi).force_x - force) / limit;
        let g = self.shear_modulus;
        let linear = (force.abs().max(1e-6 * limit)) / (g * patch.a * patch.b * self.coefficients.c11);
        let r0 = residual(0.0);
        if r0 == 0.0 {
            return Ok(at(0.0));
        }
        // F_x decreases with xi: a positive residual needs a larger xi.
        let dir = r0.signum();
        let mut hi = dir * linear;
        let mut grown = 0;
        while residual(hi).signum() == dir {
            hi *= 2.0;
            grown += 1;
            if grown > 60 {
                return Err(ContactError::NoConvergence { force, reason: format!("no bracket up to xi = {hi:.3e}") });
            }
        }
        let lo = if grown == 0 { 0.0 } else { hi / 2.0 };
        let tol = Tolerance { residual: 1e-12, x_rel: 1e-13, x_abs: 1e-18, max_iter: 200 };
        let xi = brent(lo, hi, residual, tol)
            .map_err(|e| ContactError::NoConvergence { force, reason: format!("Brent: {e}") })?;
        Ok(at(xi))
    }
}

impl TangentialSolver for Fastsim {
    fn step(&mut self, input: &StepInput) -> Result<PatchSolution, ContactError> {
        self.solve_force(input)
    }

    fn reset(&mut self) {}

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
