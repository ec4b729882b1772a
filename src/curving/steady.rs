//! Steady (quasi-static) curving of a wheelset or a bogie: each wheelset's
//! lateral shift, yaw from the radial, rotation speed and two normal forces
//! at which the creep, normal and suspension forces balance the curve's
//! load (Boocock, *Vehicle System Dynamics* 5 (1969) 1-26, for the
//! equations).
//!
//! Each wheel touches its rail at its rigid contact point, read from the
//! wheelset's [`ContactTable`] at its lateral shift (the height and roll
//! follow from the shift); the two normal forces are unknowns that the
//! vertical force and the roll moment balance (Elkins and Gostling, *Proc.
//! 5th IAVSD Symposium*, 1977, for this quasi-static method). Per wheel,
//! in the wheelset's common axes (`x` forward, `Y` left, `Z` up; the curve
//! turns left, so the left rail is the low rail), with the wheelset yawed
//! `psi` from the radial and turning at `(1 + eps) V / r0`:
//!
//! ```text
//! xi_x   = 1 - Y_c / R - (1 + eps) r_c / r0        longitudinal creepage
//! xi_eta = -psi cos(delta)                          lateral, in the contact plane
//! phi    = (1 + eps) n_Y / r0 + cos(delta) / R     spin (1/m), n the contact normal
//! ```
//!
//! The creep forces are FASTSIM's (Kalker 1982, [`crate::contact::fastsim`])
//! on the Hertz ellipse. Each wheelset balances its lateral and vertical
//! forces and its roll, yaw and spin moments; a bogie's frame balances its
//! lateral force and yaw moment through the primary suspension (`2 k_y`
//! laterally, `2 k_x d^2` in yaw per wheelset), the frame carrying the
//! lateral load `Q a_y / g` of each wheelset. The equations are solved by
//! Levenberg-Marquardt's method (Newton's as it converges), by
//! continuation in the curvature, cant and traction where the full step
//! fails. A second contact point whose clearance is below the main
//! patch's Hertz approach is reported as two-point contact; its share of
//! the load is not modelled (the rigid contact carries it all).

use super::geometry::{Geometry, GeometryError, Side};
use super::table::{ContactTable, WheelContact};
use super::vehicle::{Curve, GRAVITY, Loads, Vehicle};
use crate::contact::Creepage;
use crate::contact::fastsim::Fastsim;
use crate::contact::mesh::PressureShape;
use crate::creep_coefficients::creep_coefficients;
use crate::hertz::{Curvatures, Elastic, HertzShape};
use nalgebra::{DMatrix, DVector};

/// Unknowns per wheelset: lateral shift, yaw, spin offset, left and right
/// normal forces (relative to the axle load).
const PER_WHEELSET: usize = 5;
/// Force balance to which the solution converges, relative to the axle load
/// (FASTSIM's 24 x 24 mesh leaves a noise of about 1e-5).
const TOLERANCE: f64 = 1e-4;
/// Iterations per continuation step.
const MAX_ITERATIONS: usize = 60;
/// The forward differences' step of every unknown: 1 um, 1 urad, 1e-6 of
/// the rotation speed and of the axle load.
const DIFFERENCE: f64 = 1e-6;
/// Contact angle above which a contact is on the flange (rad, 45 degrees).
pub const FLANGE_ANGLE: f64 = std::f64::consts::FRAC_PI_4;

/// The contact's materials and friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactModel {
    /// Elastic constants of wheel and rail.
    pub elastic: Elastic,
    /// Coulomb friction coefficient (1).
    pub friction: f64,
    /// The creep forces' law.
    pub creep: CreepLaw,
}

/// How the creep forces follow from the creepages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CreepLaw {
    /// FASTSIM on the Hertz ellipse (24 x 24 elements), saturating at mu N.
    Fastsim,
    /// Kalker's linear theory, unsaturated: `F_x = -G a b C11 xi_x`, `F_y =
    /// -G a b (C22 xi_y + sqrt(a b) C23 phi)` (Kalker, *Three-dimensional
    /// elastic bodies in rolling contact*, 1990): the linear curving
    /// theory's law, for checks at small creepages.
    Linear,
}

/// One contact patch of the solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Patch {
    /// The wheel it is on.
    pub side: Side,
    /// The rigid contact's geometry.
    pub contact: WheelContact,
    /// Normal force (N).
    pub normal_force: f64,
    /// Hertz semi-axes, rolling and lateral (m).
    pub semi_axes: (f64, f64),
    /// Hertz approach (m).
    pub approach: f64,
    /// The Hertz problem's curvature sums `A`, `B` (1/m): the contact's,
    /// `B` raised to `A / 1000` where conformal.
    pub curvatures: (f64, f64),
    /// Whether the profiles are conformal there (the lateral curvature sum
    /// not above `A / 1000`, raised to it): the Hertz patch is then a bound,
    /// not a solution.
    pub conformal: bool,
    /// Creepages: longitudinal, lateral in the contact plane (1), spin (1/m).
    pub creepage: Creepage,
    /// Creep force on the wheel, longitudinal (N).
    pub force_x: f64,
    /// Creep force on the wheel, lateral in the contact plane (N).
    pub force_lateral: f64,
}

impl Patch {
    /// Contact angle (rad).
    pub fn contact_angle(&self) -> f64 {
        self.contact.contact_angle(self.side)
    }

    /// Whether the patch is on the flange (contact angle above 45 degrees).
    pub fn on_flange(&self) -> bool {
        self.contact_angle() > FLANGE_ANGLE
    }

    /// Whether a second point is within the Hertz approach: two-point contact.
    pub fn two_point(&self) -> bool {
        self.contact.second_clearance < self.approach
    }

    /// The lateral creepage, spin (1/m) and lateral creep force (N) in a
    /// study's axes (x forward, y to the right, the spin about the downward
    /// normal) for the curve turning left, or for its mirror image turning
    /// right (`mirror`: how a study of the high rail takes it, as its first
    /// rail).
    pub fn study_axes(&self, mirror: bool) -> (f64, f64, f64) {
        let s = if mirror { 1.0 } else { -1.0 };
        (s * self.creepage.y, s * self.creepage.spin, s * self.force_lateral)
    }

    /// The force on the wheel in the track's cross-section `(F_Y, F_Z)` (N).
    pub fn force_yz(&self) -> (f64, f64) {
        let (ny, nz) = self.contact.normal;
        (self.normal_force * ny + self.force_lateral * nz, self.normal_force * nz - self.force_lateral * ny)
    }
}

/// One wheelset of the solution.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelsetState {
    /// Longitudinal position from the bogie's centre (m, forward positive).
    pub x: f64,
    /// Lateral shift (m), positive to the left (the low rail).
    pub shift: f64,
    /// Roll (rad), positive raising the left wheel.
    pub roll: f64,
    /// Yaw from the radial (rad), positive towards the curve's centre.
    pub yaw: f64,
    /// Rotation speed's offset from `V / r0` (1).
    pub spin_offset: f64,
    /// The contact patches, left and right.
    pub patches: [Patch; 2],
}

impl WheelsetState {
    /// The patch on `side`.
    pub fn on(&self, side: Side) -> &Patch {
        &self.patches[side as usize]
    }

    /// The angle of attack (rad): the yaw from the radial, positive heading
    /// towards the high (outer) rail.
    pub fn angle_of_attack(&self) -> f64 {
        -self.yaw
    }
}

/// The solution.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyState {
    /// Each wheelset, the leading first.
    pub wheelsets: Vec<WheelsetState>,
    /// The bogie frame's lateral shift (m) and yaw from the radial (rad).
    pub frame: Option<(f64, f64)>,
    /// Iterations, all continuation steps together.
    pub iterations: usize,
    /// The largest force residual, relative to the axle load.
    pub residual: f64,
}

impl SteadyState {
    /// Every wheel, the leading wheelset's first, the low rail's before the
    /// high: its name ("leading low"; "low" with a single wheelset), its
    /// wheelset and its patch.
    pub fn wheels(&self) -> Vec<(String, &WheelsetState, &Patch)> {
        let mut out = Vec::new();
        for (i, w) in self.wheelsets.iter().enumerate() {
            for (side, rail) in [(Side::Left, "low"), (Side::Right, "high")] {
                let name = if self.wheelsets.len() > 1 {
                    format!("{} {rail}", ["leading", "trailing"][i])
                } else {
                    rail.to_string()
                };
                out.push((name, w, w.on(side)));
            }
        }
        out
    }
}

/// A steady state that cannot be found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CurvingError {
    /// The geometry fails.
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    /// A wheelset leaves the contact table: its flange climbs.
    #[error("wheelset {wheelset} runs beyond its flange contact (lateral shift {y_mm:.2} mm): no steady curving there")]
    OffTable {
        /// The wheelset (1 the leading).
        wheelset: usize,
        /// Its lateral shift (mm).
        y_mm: f64,
    },
    /// Levenberg-Marquardt's method did not converge.
    #[error(
        "steady curving did not converge at {fraction:.3} of the curve (curvature, cant, traction): force residual {residual:.2e} of the axle load after {iterations} iterations, largest in {worst}"
    )]
    NoConvergence {
        /// The share of the curve reached by continuation.
        fraction: f64,
        /// The residual, relative to the axle load.
        residual: f64,
        /// Iterations.
        iterations: usize,
        /// The equation with the largest residual.
        worst: String,
    },
}

/// A steady-curving problem.
#[derive(Debug, Clone)]
pub struct Problem<'a> {
    /// The profiles, placed.
    pub geometry: &'a Geometry,
    /// The wheelset's contact table.
    pub table: &'a ContactTable,
    /// The curve.
    pub curve: Curve,
    /// The vehicle.
    pub vehicle: Vehicle,
    /// The loads.
    pub loads: Loads,
    /// The contact.
    pub contact: ContactModel,
}

const EQUATIONS: [&str; PER_WHEELSET] = ["lateral force", "vertical force", "roll moment", "yaw moment", "spin moment"];
/// The table's reach and step (m).
pub const TABLE: (f64, f64) = (14e-3, 2e-5);

impl Problem<'_> {
    /// The wheelsets' nominal rolling radius `r0` (m): the mean of the tape
    /// circles' radii.
    fn r0(&self) -> f64 {
        let r = self.geometry.wheelset().radius;
        0.5 * (r[0] + r[1])
    }

    /// Solves the steady state.
    pub fn solve(&self) -> Result<SteadyState, CurvingError> {
        let axles = self.vehicle.axles();
        let mut u = self.initial(&axles);
        let (mut done, mut step, mut iterations) = (0.0, 1.0f64, 0);
        loop {
            let fraction = (done + step).min(1.0);
            match self.levenberg_marquardt(&u, fraction, &axles) {
                Ok((next, its)) => {
                    iterations += its;
                    u = next;
                    done = fraction;
                    if done >= 1.0 {
                        break;
                    }
                    step = (step * 1.5).min(1.0);
                }
                Err(e) => {
                    step *= 0.5;
                    if step < 1.0 / 64.0 {
                        // A fold: the wheelsets snap to another contact (the
                        // gauge corner, the flange). Start afresh at the
                        // next share of the curve with one wheelset moved
                        // towards the high rail.
                        let target = (done + 1.0 / 16.0).min(1.0);
                        let jumped = self.jump(&u, target, &axles);
                        let Some((next, its)) = jumped else { return Err(e) };
                        iterations += its;
                        (u, done, step) = (next, target, 1.0 / 16.0);
                        if done >= 1.0 {
                            break;
                        }
                    }
                }
            }
        }
        let (r, states) = self.residual(&u, 1.0, &axles)?;
        let frame = matches!(self.vehicle, Vehicle::Bogie { .. })
            .then(|| (u[PER_WHEELSET * axles.len()], u[PER_WHEELSET * axles.len() + 1]));
        Ok(SteadyState { wheelsets: states, frame, iterations, residual: r.amax() })
    }

    /// Levenberg-Marquardt's method at `fraction` from starting points that move one
    /// wheelset (the leading first) 1, 2, 4 or 6 mm towards the high rail.
    fn jump(&self, u: &[f64], fraction: f64, axles: &[f64]) -> Option<(Vec<f64>, usize)> {
        let mut its = 0;
        for i in 0..axles.len() {
            for shift in [1e-3, 2e-3, 4e-3, 6e-3] {
                let mut v = u.to_vec();
                v[PER_WHEELSET * i] -= shift;
                match self.levenberg_marquardt(&v, fraction, axles) {
                    Ok((next, k)) => return Some((next, its + k)),
                    Err(_) => its += MAX_ITERATIONS,
                }
            }
        }
        None
    }

    /// The starting point: each wheelset centred, half its load on each
    /// wheel, parallel to the frame.
    fn initial(&self, axles: &[f64]) -> Vec<f64> {
        let bogie = matches!(self.vehicle, Vehicle::Bogie { .. });
        let mut u = Vec::new();
        for &x in axles {
            u.extend([0.0, if bogie { -x / self.curve.radius } else { 0.0 }, 0.0, 0.5, 0.5]);
        }
        if bogie {
            u.extend([0.0, 0.0]);
        }
        u
    }

    /// The Hertz shape of a contact and whether it is conformal.
    fn hertz(&self, c: &WheelContact) -> (HertzShape, bool) {
        let (a, b) = c.curvatures;
        let conformal = b <= a * 1e-3;
        let curv = Curvatures { a, b: if conformal { a * 1e-3 } else { b } };
        (HertzShape::new(curv, self.contact.elastic).expect("curvatures kept positive and within 1e3"), conformal)
    }

    /// The patch of a wheel with contact `c`, normal force `normal_force`,
    /// the wheelset yawed `yaw` turning at `(1 + eps) V / r0` on a curve of
    /// curvature `kappa`.
    pub fn patch(&self, side: Side, c: &WheelContact, normal_force: f64, yaw: f64, eps: f64, kappa: f64) -> Patch {
        let r0 = self.r0();
        let (ny, nz) = c.normal;
        let (shape, conformal) = self.hertz(c);
        let creepage = Creepage {
            x: 1.0 - c.lateral * kappa - (1.0 + eps) * c.rolling_radius / r0,
            y: -yaw * nz,
            spin: (1.0 + eps) * ny / r0 + nz * kappa,
        };
        let curvatures = shape.curvatures();
        let curvatures = (curvatures.a, curvatures.b);
        let (mut semi_axes, mut approach, mut force_x, mut force_lateral) = ((0.0, 0.0), 0.0, 0.0, 0.0);
        if let Ok(patch) = shape.patch(normal_force) {
            let nu = self.contact.elastic.poisson_ratio;
            let coefficients = creep_coefficients(patch.aspect().clamp(0.1, 10.0), nu).expect("aspect clamped");
            let g = self.contact.elastic.shear_modulus();
            let (fx, fy) = match self.contact.creep {
                CreepLaw::Fastsim => {
                    let fastsim = Fastsim::new(24, 24, PressureShape::Hertz, coefficients, g);
                    let solution = fastsim.solve_creepage(&patch, creepage, self.contact.friction, self.curve.speed);
                    (solution.force_x, solution.force_y)
                }
                CreepLaw::Linear => {
                    let gab = g * patch.a * patch.b;
                    let c = coefficients;
                    (
                        -gab * c.c11 * creepage.x,
                        -gab * (c.c22 * creepage.y + (patch.a * patch.b).sqrt() * c.c23 * creepage.spin),
                    )
                }
            };
            (semi_axes, approach, force_x, force_lateral) = ((patch.a, patch.b), patch.approach, fx, fy);
        }
        Patch {
            side,
            contact: *c,
            normal_force,
            semi_axes,
            approach,
            curvatures,
            conformal,
            creepage,
            force_x,
            force_lateral,
        }
    }

    /// The equations' residuals at unknowns `u`, at `fraction` of the curve.
    fn residual(
        &self,
        u: &[f64],
        fraction: f64,
        axles: &[f64],
    ) -> Result<(DVector<f64>, Vec<WheelsetState>), CurvingError> {
        let curve = Curve { radius: self.curve.radius / fraction, cant: self.curve.cant * fraction, ..self.curve };
        let kappa = curve.curvature();
        let mass = self.loads.axle_load / GRAVITY;
        let (lateral, normal) = (mass * curve.lateral_acceleration(), mass * curve.normal_acceleration());
        let traction = self.loads.traction * fraction;
        let q = self.loads.axle_load;
        let b = self.geometry.tape_half_spacing();
        let r0 = self.r0();
        let n = axles.len();
        let bogie = match self.vehicle {
            Vehicle::Bogie { primary, .. } => Some((primary, u[PER_WHEELSET * n], u[PER_WHEELSET * n + 1])),
            Vehicle::Wheelset => None,
        };
        let mut r = DVector::zeros(u.len());
        let mut states = Vec::with_capacity(n);
        for (i, &x) in axles.iter().enumerate() {
            let w = &u[PER_WHEELSET * i..PER_WHEELSET * (i + 1)];
            let (y, yaw, eps) = (w[0], w[1], w[2]);
            let Some(row) = self.table.at(y) else {
                return Err(CurvingError::OffTable { wheelset: i + 1, y_mm: y * 1e3 });
            };
            let patches = [Side::Left, Side::Right]
                .map(|s| self.patch(s, &row.wheel[s as usize], (w[3 + s as usize] * q).max(0.0), yaw, eps, kappa));
            let (mut fy, mut fz, mut mx, mut mz, mut my) = (0.0, 0.0, 0.0, 0.0, 0.0);
            for p in &patches {
                let (py, pz) = p.force_yz();
                let (dy, dz) = (p.contact.lateral - y, p.contact.height - row.z);
                fy += py;
                fz += pz;
                mx += dy * pz - dz * py;
                mz -= dy * p.force_x;
                my += p.force_x * p.contact.rolling_radius / r0;
            }
            // The carried mass's lateral force, at its centre's height.
            mx += (self.loads.centre_height - r0) * lateral;
            let (mut ext_y, mut ext_mz) = (-lateral, 0.0);
            if let Some((primary, yb, psib)) = bogie {
                let dy = y + x * x * kappa / 2.0 - yb - psib * x;
                let dpsi = yaw + x * kappa - psib;
                ext_y = -primary.lateral_stiffness() * dy;
                ext_mz = -primary.yaw_stiffness() * dpsi;
                let k = PER_WHEELSET * n;
                r[k] += (primary.lateral_stiffness() * dy - lateral) / q;
                r[k + 1] += (primary.lateral_stiffness() * dy * x + primary.yaw_stiffness() * dpsi) / (q * b);
            }
            let k = PER_WHEELSET * i;
            r[k] = (fy + ext_y) / q;
            r[k + 1] = (fz - normal) / q;
            r[k + 2] = mx / (q * b);
            r[k + 3] = (mz + ext_mz) / (q * b);
            r[k + 4] = (my - traction) / q;
            // A wheel whose normal force would be negative lifts off: its
            // force is held at zero, the vertical balance pushed back.
            for s in Side::BOTH {
                if w[3 + s as usize] < 0.0 {
                    r[k + 1] += w[3 + s as usize];
                }
            }
            states.push(WheelsetState { x, shift: y, roll: row.roll, yaw, spin_offset: eps, patches });
        }
        Ok((r, states))
    }

    /// Levenberg-Marquardt's method from `u0` (forward-difference
    /// Jacobian), each step within the unknowns' limits.
    fn levenberg_marquardt(&self, u0: &[f64], fraction: f64, axles: &[f64]) -> Result<(Vec<f64>, usize), CurvingError> {
        let n = u0.len();
        let limits: Vec<f64> = (0..n)
            .map(
                |j| if j >= PER_WHEELSET * axles.len() { 2e-3 } else { [1e-3, 2e-3, 2e-3, 0.5, 0.5][j % PER_WHEELSET] },
            )
            .collect();
        let mut u = u0.to_vec();
        let mut r = self.residual(&u, fraction, axles)?.0;
        let mut lambda = 1e-6;
        for iteration in 0..MAX_ITERATIONS {
            if r.amax() < TOLERANCE {
                return Ok((u, iteration));
            }
            let mut jac = DMatrix::zeros(n, n);
            for j in 0..n {
                let mut v = u.clone();
                v[j] += DIFFERENCE;
                let rj = self.residual(&v, fraction, axles)?.0;
                jac.set_column(j, &((rj - &r) / DIFFERENCE));
            }
            // Levenberg-Marquardt with Marquardt's scaling (Newton's step as
            // the damping vanishes), each step within the unknowns' limits.
            let jtj = jac.transpose() * &jac;
            let jtr = jac.transpose() * &r;
            let norm = r.norm();
            let mut accepted = false;
            for _ in 0..16 {
                let mut a = jtj.clone();
                for j in 0..n {
                    a[(j, j)] += lambda * jtj[(j, j)].max(1e-300);
                }
                let Some(mut du) = a.lu().solve(&(-&jtr)) else { break };
                let scale = (0..n).map(|j| du[j].abs() / limits[j]).fold(1.0, f64::max);
                du /= scale;
                let v: Vec<f64> = (0..n).map(|j| u[j] + du[j]).collect();
                if let Ok((rv, _)) = self.residual(&v, fraction, axles)
                    && rv.norm() < norm
                {
                    (u, r) = (v, rv);
                    lambda = (lambda / 3.0).max(1e-12);
                    accepted = true;
                    break;
                }
                lambda *= 4.0;
            }
            if !accepted {
                break;
            }
        }
        if r.amax() < TOLERANCE {
            return Ok((u, MAX_ITERATIONS));
        }
        let worst = r.iamax();
        let name = if worst >= PER_WHEELSET * axles.len() {
            format!("the bogie frame's {}", ["lateral force", "yaw moment"][worst - PER_WHEELSET * axles.len()])
        } else {
            format!("wheelset {}'s {}", worst / PER_WHEELSET + 1, EQUATIONS[worst % PER_WHEELSET])
        };
        Err(CurvingError::NoConvergence { fraction, residual: r.amax(), iterations: MAX_ITERATIONS, worst: name })
    }
}
