//! The linearised profile contact on the patch-adapted mesh: the normal
//! contact over a rail of height `r(X, Y)` (m, positive up) to first order
//! in `r`.
//!
//! The normal problem's linear response on the Hertz ellipse with the force
//! prescribed (the approach change its multiplier),
//!
//! ```text
//! sum_J A_IJ dp_J = r(X_c + x_I, y_I) + d delta  (every element I),   sum_J dp_J area_J = 0,
//! ```
//!
//! (`A` the normal influence coefficients of the two half-spaces for
//! uniform pressure on the mesh's rectangles, Boussinesq-Love,
//! [`crate::contact::influence::normal_influence`]) is singular at the
//! edge, `dp = q / sqrt(1 - rho^2)` with `q` regular, and to first order
//! `p_H + dp = p0 sqrt(1 - rho^2 + 2 q / p0)`: the edge moves (Johnson,
//! *Contact Mechanics*, 1985, sec. 5.2 and 13.2). The wear needs the edge
//! where it is: the rail material enters the contact at the leading edge
//! and its stick traction builds up from there, and the contact point of a
//! wheel on a wavy rail moves by `R dr/dX`, carrying the wear with it (the
//! response on the Hertz area with its edge held, tried first, wore nine
//! 0.2 um harmonics down at -0.67 dB per 1e5 passages at 30 mm where the
//! nonlinear contact wears them at -1.40, -2.14 against -3.02 at 15 mm:
//! book: docs/src/theory/consistent-chain.md). So the mesh moves:
//! [`MeshResponse::linear_patch`] fits the Hertz ellipse to the response's
//! moments (a shift and a stretch, by reciprocity, from the profile
//! directly) and adds the rest of the response on it; on the fixed grid
//! [`MeshResponse::pressure_on_cells`] averages that pressure over the
//! grid's elements. The contact filter
//! of the dynamics is the same linearisation's approach change
//! ([`crate::growth::linear_roughness`]).
//!
//! With the Hertz shape fixed (`b/a` independent of the load) the mesh is
//! the same in normalised coordinates at every step and `A` scales with
//! `a`: `dp = S r / a` with one solution operator `S`, built once by LU
//! (faer), on the tangential mesh or, beyond [`MAX_NORMAL_ELEMENTS`], on a
//! coarser Paul-Hashemi mesh of the same ellipse.

mod cells;

use super::RailContact;
use super::influence::{Rect, normal_influence};
use super::mesh::{EllipseMesh, PressureShape, pressure_on_mesh};
use crate::contact::grid::RailSurface;
use crate::hertz::{Curvatures, Elastic, HertzPatch, HertzShape};
use faer::Mat;
use faer::linalg::solvers::Solve;
use std::f64::consts::PI;

/// Largest number of elements the linear normal problem is solved on; a
/// finer tangential mesh takes the rest of the response (beyond the moved
/// ellipse) from a coarser mesh of at most this many elements (about 0.5 mm
/// at the paper's patch; the profile under the patch is smooth on that
/// scale).
pub const MAX_NORMAL_ELEMENTS: usize = 625;

/// The largest shift (relative to a) or stretch (relative to a semi-axis)
/// of the patch the linear profile contact accepts: beyond, the
/// corrugation is far outside the linear range and the step stops with
/// an error.
pub const MAX_LINEAR_MOVE: f64 = 0.5;

/// Gauss-Legendre points in `phi` (rho = sin phi) of the disc quadrature.
const DISC_RADIAL: usize = 16;
/// Trapezoid points in the angle of the disc quadrature.
const DISC_ANGULAR: usize = 64;

/// The linear normal response on a Paul-Hashemi mesh.
#[derive(Debug, Clone)]
pub struct MeshResponse {
    /// The mesh the normal problem is solved on.
    normal_mesh: EllipseMesh,
    /// Solution operator at a = 1 m, row-major (n x n): dp = S r / a.
    operator: Vec<f64>,
    /// Curvature sums A, B (1/m) of the Hertz contact.
    curvatures: Curvatures,
    /// The Hertz semi-axes' logarithmic derivatives with respect to the
    /// curvature sums at fixed load: `[[dln a/dln A, dln a/dln B],
    /// [dln b/dln A, dln b/dln B]]` (independent of the load).
    log_derivatives: [[f64; 2]; 2],
    /// Quadrature of `int F / sqrt(1 - rho^2)` over the unit disc: points
    /// (xi, eta) and weights.
    disc: Vec<(f64, f64, f64)>,
}

/// The quadrature `int_disc F(xi, eta) / sqrt(1 - rho^2) dxi deta = sum w F`:
/// with `rho = sin phi` the weight is `sin phi dphi dtheta`, smooth;
/// Gauss-Legendre in `phi` on `[0, pi/2]`, the trapezoid rule (spectral for
/// a periodic integrand) in `theta`.
fn disc_quadrature() -> Vec<(f64, f64, f64)> {
    use gauss_quad::legendre::GaussLegendre;
    let rule = GaussLegendre::new(DISC_RADIAL.try_into().expect("nonzero"));
    let mut out = Vec::with_capacity(DISC_RADIAL * DISC_ANGULAR);
    for &(u, w) in rule.as_node_weight_pairs() {
        let phi = 0.25 * PI * (u + 1.0);
        let (rho, weight) = (phi.sin(), 0.25 * PI * w * phi.sin() * 2.0 * PI / DISC_ANGULAR as f64);
        for k in 0..DISC_ANGULAR {
            let theta = 2.0 * PI * k as f64 / DISC_ANGULAR as f64;
            out.push((rho * theta.cos(), rho * theta.sin(), weight));
        }
    }
    out
}

/// The patch of a step on the adapted mesh with the linear profile
/// contact: the ellipse moved and stretched to first order, the pressure
/// on it.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearPatch {
    /// Offset of the patch centre from the wheel's `X_c` along x (m).
    pub offset: f64,
    /// Semi-axis along x (m).
    pub a: f64,
    /// Semi-axis across (m).
    pub b: f64,
    /// Pressure at the element centres of the moved patch (Pa).
    pub pressure: Vec<f64>,
    /// Elements well inside the patch (`1 - rho^2 > 1/4`) where the
    /// first-order pressure vanished: the patch splits there, beyond the
    /// linearisation's range.
    pub clipped: usize,
}

/// Bilinear sample (linear extrapolation beyond the ends) of `q` on a
/// Paul-Hashemi mesh's tensor coordinates: `t = xi / sqrt(1 - eta^2)` at
/// `1 - (i + 1/2) 2 / nx` along the strips, `eta` at `-1 + (j + 1/2) 2 / ny`.
fn sample(q: &[f64], nx: usize, ny: usize, t: f64, eta: f64) -> f64 {
    let at = |u: f64, n: usize| -> (usize, f64) {
        if n == 1 {
            return (0, 0.0);
        }
        let i = (u.floor().max(0.0) as usize).min(n - 2);
        (i, u - i as f64)
    };
    let (i, wi) = at((1.0 - t) * nx as f64 / 2.0 - 0.5, nx);
    let (j, wj) = at((eta + 1.0) * ny as f64 / 2.0 - 0.5, ny);
    let v = |j: usize, i: usize| q[j * nx + i];
    let row = |j: usize| if nx == 1 { v(j, 0) } else { (1.0 - wi) * v(j, i) + wi * v(j, i + 1) };
    if ny == 1 { row(j) } else { (1.0 - wj) * row(j) + wj * row(j + 1) }
}

impl MeshResponse {
    /// The response for the tangential `mesh` of the Hertz contact `shape`.
    pub fn new(mesh: &EllipseMesh, shape: &HertzShape) -> Self {
        let (elastic, curvatures) = (shape.elastic(), shape.curvatures());
        let b_over_a = 1.0 / shape.aspect();
        // Scale-free: the log-derivatives at any load, by central
        // differences of the Hertz solution.
        let h = 1e-5;
        let axes = |ca: f64, cb: f64| {
            let p = HertzShape::new(Curvatures { a: ca, b: cb }, elastic)
                .and_then(|s| s.patch(1e5))
                .expect("a valid shape stays valid under a small change");
            (p.a.ln(), p.b.ln())
        };
        let (ca, cb) = (curvatures.a, curvatures.b);
        let (ap, am) = (axes(ca * (1.0 + h), cb), axes(ca * (1.0 - h), cb));
        let (bp, bm) = (axes(ca, cb * (1.0 + h)), axes(ca, cb * (1.0 - h)));
        let d = |p: f64, m: f64| (p - m) / ((1.0 + h).ln() - (1.0 - h).ln());
        let log_derivatives = [[d(ap.0, am.0), d(bp.0, bm.0)], [d(ap.1, am.1), d(bp.1, bm.1)]];
        let (nx, ny) = (mesh.nx, mesh.ny);
        let factor = ((mesh.len() as f64 / MAX_NORMAL_ELEMENTS as f64).sqrt().ceil() as usize).max(1);
        let normal_mesh =
            if factor == 1 { mesh.clone() } else { EllipseMesh::new(nx.div_ceil(factor), ny.div_ceil(factor)) };
        let operator = solution_operator(&normal_mesh, b_over_a, elastic);
        MeshResponse { normal_mesh, operator, curvatures, log_derivatives, disc: disc_quadrature() }
    }

    /// The shortest wavelength (m) along the rail that the response
    /// resolves on a patch of semi-axis `a` (m): eight elements of the
    /// normal mesh (the profile's shorter harmonics alias on it, and on the
    /// moments' quadrature).
    pub fn resolution(&self, a: f64) -> f64 {
        8.0 * 2.0 * a / self.normal_mesh.nx as f64
    }

    /// Elements of the mesh the normal problem is solved on.
    pub fn normal_elements(&self) -> usize {
        self.normal_mesh.len()
    }

    /// The step's patch over `surface` to first order in the surface.
    ///
    /// The linear response `dp = q / sqrt(1 - rho^2)` (rho the Hertz
    /// ellipse's normalised radius, `q` regular) is singular at the edge:
    /// the edge moves. To first order `p_H + dp = p0 sqrt(1 - rho^2 + 2 q /
    /// p0)`, which vanishes where `1 - rho^2 + 2 q / p0 = 0`. The
    /// tangential problem needs the edges where they are (the material
    /// enters the contact at the leading edge, and its stick traction builds
    /// up from there), so the mesh moves with them: its ellipse is the one
    /// whose Hertz pressure has the first-order response's moments,
    ///
    /// ```text
    /// s = int x dp dA / N,   da = 5 int x^2 dp dA / (2 a N),   db = 5 int y^2 dp dA / (2 b N)
    /// ```
    ///
    /// (a Hertz pressure has `int x^2 p dA = N a^2 / 5`; exact for a tilted
    /// or curved rail, whose contact is Hertz's, shifted by `s = R dr/dX`
    /// or with the curvature changed). With `uniform` b stretches with a
    /// (the exact elastic model's coefficients hold one aspect ratio). On the
    /// moved ellipse (radius `rho'`, peak `p0'`) the rest of the response,
    /// `q_r = q -` the moved ellipse's own first-order change, is added in
    /// the same first-order form,
    ///
    /// ```text
    /// p = p_shape + p0' sqrt(max(0, 1 - rho'^2 + 2 q_r / p0')) - p0' sqrt(1 - rho'^2),
    /// ```
    ///
    /// `p_shape` the model's pressure on the moved ellipse (for the Hertz
    /// shape `p` is the first-order pressure itself), rescaled to hold the
    /// force. A flat surface leaves the patch and the shape's pressure bit
    /// for bit.
    pub fn linear_patch(
        &self,
        surface: &RailSurface,
        position: f64,
        patch: &HertzPatch,
        shape: PressureShape,
        mesh: &EllipseMesh,
        uniform: bool,
    ) -> Result<LinearPatch, super::ContactError> {
        let Some(fit) = self.fit(surface, position, patch, uniform, false)? else {
            let (a, b) = (patch.a, patch.b);
            let pressure = pressure_on_mesh(mesh, shape, patch.normal_force, a, b);
            return Ok(LinearPatch { offset: 0.0, a, b, pressure, clipped: 0 });
        };
        let mut pressure = pressure_on_mesh(mesh, shape, patch.normal_force, fit.a, fit.b);
        let mut clipped = 0;
        for (p, (&xm, &em)) in pressure.iter_mut().zip(mesh.xi.iter().zip(&mesh.eta)) {
            let moved = (1.0 - xm * xm - em * em).max(0.0);
            *p += fit.p0 * (fit.first_order(xm, em).max(0.0).sqrt() - moved.sqrt());
            if *p <= 0.0 {
                // Well inside the patch the contact opens: beyond the
                // linearisation's range (at the edge it is the first-order
                // edge itself).
                clipped += usize::from(moved > 0.25);
                *p = 0.0;
            }
        }
        let total = mesh.integrate(&pressure, fit.a, fit.b);
        if total.is_nan() || total <= 0.0 {
            return Err(fit.out_of_range());
        }
        pressure.iter_mut().for_each(|p| *p *= patch.normal_force / total);
        Ok(LinearPatch { offset: fit.shift, a: fit.a, b: fit.b, pressure, clipped })
    }

    /// The largest half-extents (m) of the patch over `surface` under
    /// `patch` with the patch centre at any of `positions` (m): along x
    /// `|shift| + a'`, across `b'` of the moved and stretched ellipse (the
    /// moments alone, without the remainder: cheap enough for every rail
    /// cell of a passage), each move and stretch taken up to the largest
    /// the linearisation accepts (a step beyond stops with its error). At
    /// least Hertz's.
    pub fn extent(
        &self,
        surface: &RailSurface,
        positions: impl Iterator<Item = f64>,
        patch: &HertzPatch,
    ) -> (f64, f64) {
        let (a, b) = (patch.a, patch.b);
        let (mut ax, mut by) = (a, b);
        let clamp =
            |v: f64, of: f64| if v.is_finite() { v.clamp(-MAX_LINEAR_MOVE * of, MAX_LINEAR_MOVE * of) } else { 0.0 };
        for x in positions {
            let (shift, da, db) = self.moments(surface, x, patch);
            ax = ax.max(clamp(shift, a).abs() + a + clamp(da, a));
            by = by.max(b + clamp(db, b));
        }
        (ax, by)
    }

    /// The moved ellipse's shift and semi-axis changes (m) over `surface`
    /// with the patch centre at `position` (see [`MeshResponse::fit`]):
    ///
    /// ```text
    /// s = int x dp dA / N,   da = 5 int x^2 dp dA / (2 a N),   db = 5 int y^2 dp dA / (2 b N)
    /// ```
    ///
    /// from the profile by reciprocity.
    fn moments(&self, surface: &RailSurface, position: f64, patch: &HertzPatch) -> (f64, f64, f64) {
        let (a, b, n_force) = (patch.a, patch.b, patch.normal_force);
        let p0 = 3.0 * n_force / (2.0 * PI * a * b);
        let (mut ix, mut ixx, mut iyy) = (0.0, 0.0, 0.0);
        for &(xi, eta, w) in &self.disc {
            let v = w * surface.height(position + xi * a, eta * b);
            let cos2 = 1.0 - xi * xi - eta * eta;
            ix += v * xi;
            ixx += v * (xi * xi - cos2);
            iyy += v * (eta * eta - cos2);
        }
        let (ix, ixx, iyy) = (ix * a * a * b, ixx * a * b, iyy * a * b);
        let (ca, cb) = (self.curvatures.a, self.curvatures.b);
        let l = &self.log_derivatives;
        let m1 = p0 * ix / (2.0 * ca * a * a);
        let mx = -p0 * (l[0][0] * ixx + l[1][0] * iyy) / ca;
        let my = -p0 * (l[0][1] * ixx + l[1][1] * iyy) / cb;
        (m1 / n_force, 2.5 * mx / (a * n_force), 2.5 * my / (b * n_force))
    }

    /// The normal mesh's response `dp_k` (Pa) at element `k` to the heights
    /// `r` (m) at its elements, on a patch of semi-axis `a` (m).
    fn response_at(&self, k: usize, r: &[f64], a: f64) -> f64 {
        let n = r.len();
        self.operator[k * n..(k + 1) * n].iter().zip(r).map(|(s, v)| s * v).sum::<f64>() / a
    }

    /// The first-order patch of a step over `surface` (`None` for a flat
    /// surface under the patch: Hertz's patch).
    ///
    /// The moments of the response by reciprocity: with `w = sqrt(1 -
    /// rho^2)`, `int x dp = p0 / (2 A a^2) int x r / w`, and `int x^2 dp`,
    /// `int y^2 dp` from the Hertz pressure changes that a change of A or B
    /// makes, `p0 ((da/a)(xi^2 - w^2) + (db/b)(eta^2 - w^2)) / w`, whose
    /// displacement is `-dA x^2 - dB y^2 + const`.
    fn fit(
        &self,
        surface: &RailSurface,
        position: f64,
        patch: &HertzPatch,
        uniform: bool,
        residual: bool,
    ) -> Result<Option<LinearFit>, super::ContactError> {
        let (a, b, n_force) = (patch.a, patch.b, patch.normal_force);
        let nm = &self.normal_mesh;
        let r: Vec<f64> = nm.xi.iter().zip(&nm.eta).map(|(x, e)| surface.height(position + x * a, e * b)).collect();
        if r.iter().all(|v| *v == 0.0) {
            return Ok(None);
        }
        let n = r.len();
        let p0 = 3.0 * n_force / (2.0 * PI * a * b);
        let (shift, da_fit, db_fit) = self.moments(surface, position, patch);
        let (mut da, mut db) = (da_fit, db_fit);
        if uniform {
            // One stretch for both axes: the mean of the two.
            let e = (da / a + db / b) / 2.0;
            (da, db) = (e * a, e * b);
        }
        // A move or stretch of half the patch is no first-order change.
        let stretch = (da / a).abs().max((db / b).abs());
        if stretch > MAX_LINEAR_MOVE || shift.abs() > MAX_LINEAR_MOVE * a || !(stretch.is_finite() && shift.is_finite())
        {
            return Err(super::ContactError::LinearRange { shift, stretch: 100.0 * stretch, a });
        }
        let (ca, cb) = (self.curvatures.a, self.curvatures.b);
        let l = &self.log_derivatives;
        // The remainder's regular part. On the adapted mesh (`residual`
        // false) the response to the whole profile less the moved
        // ellipse's own first-order change of p_H, on the mesh it was
        // solved on (the formulation the adapted mesh's growth rates were
        // validated with). On the fixed grid (`residual`) the response to
        // the profile less the one the moved ellipse answers exactly (the
        // tilt 2 A s and the curvature changes dA, dB of its stretch,
        // [da/a, db/b] = L [dA/A, dB/B]), so that the discretised response
        // carries only what the ellipse does not: sampled on the grid's
        // elements, the first form left the discretisation's error of the
        // tilt and curvature in the remainder, most at the edge (a tilted
        // rail's patch moved 18 % too far, growth rates 15-35 % off);
        // the second form on the adapted mesh took the 28 x 28 mesh's
        // growth rates 16-19 % away from the nonlinear contact's at 15-30
        // mm, where the first is within 1-8 %.
        let q_r: Vec<f64> = if residual {
            let det = l[0][0] * l[1][1] - l[0][1] * l[1][0];
            let (ea, eb) = (da_fit / a, db_fit / b);
            let d_a = ca * (l[1][1] * ea - l[0][1] * eb) / det;
            let d_b = cb * (-l[1][0] * ea + l[0][0] * eb) / det;
            let alpha = 2.0 * ca * shift;
            let rest: Vec<f64> = (0..n)
                .map(|k| {
                    let (x, y) = (nm.xi[k] * a, nm.eta[k] * b);
                    r[k] - (alpha * x - d_a * x * x - d_b * y * y)
                })
                .collect();
            (0..n)
                .map(|k| {
                    let (x, y) = (nm.xi[k], nm.eta[k]);
                    let w = (1.0 - x * x - y * y).max(0.0);
                    let left_out = p0 * (((da_fit - da) / a) * (x * x - w) + ((db_fit - db) / b) * (y * y - w));
                    self.response_at(k, &rest, a) * w.sqrt() + left_out
                })
                .collect()
        } else {
            (0..n)
                .map(|k| {
                    let (x, y) = (nm.xi[k], nm.eta[k]);
                    let w = (1.0 - x * x - y * y).max(0.0);
                    let own = p0 * (shift * x / a + (da / a) * (x * x - w) + (db / b) * (y * y - w));
                    self.response_at(k, &r, a) * w.sqrt() - own
                })
                .collect()
        };
        let (a2, b2) = (a + da, b + db);
        Ok(Some(LinearFit {
            shift,
            a: a2,
            b: b2,
            hertz_a: a,
            hertz_b: b,
            p0: 3.0 * n_force / (2.0 * PI * a2 * b2),
            q_r,
            normal_nx: nm.nx,
            normal_ny: nm.ny,
            stretch,
        }))
    }
}

/// The first-order patch of a step: the Hertz ellipse moved and stretched
/// to the response's moments, and the regular part of the rest of the
/// response on the normal mesh.
#[derive(Debug, Clone)]
struct LinearFit {
    /// Offset of the moved centre from `X_c` (m).
    shift: f64,
    /// Moved semi-axes (m).
    a: f64,
    b: f64,
    /// The step's Hertz semi-axes (m).
    hertz_a: f64,
    hertz_b: f64,
    /// Hertz peak pressure of the moved ellipse (Pa).
    p0: f64,
    /// Regular part of the rest of the response on the normal mesh (Pa).
    q_r: Vec<f64>,
    normal_nx: usize,
    normal_ny: usize,
    /// Largest relative stretch of a semi-axis.
    stretch: f64,
}

impl LinearFit {
    /// `(p / p0')^2` to first order at the moved ellipse's normalised
    /// point (`xm`, `em`): `1 - rho'^2 + 2 q_r / p0'`, the rest of the
    /// response taken at the Hertz ellipse's edge beyond it.
    fn first_order(&self, xm: f64, em: f64) -> f64 {
        (1.0 - xm * xm - em * em).max(0.0) + self.rest(xm, em)
    }

    /// `2 q_r / p0'` at the moved ellipse's normalised point (the
    /// remainder taken at the Hertz ellipse's edge beyond it).
    fn rest(&self, xm: f64, em: f64) -> f64 {
        if self.q_r.is_empty() {
            return 0.0;
        }
        let (xo, eo) = ((self.shift + xm * self.a) / self.hertz_a, (em * self.b / self.hertz_b).clamp(-1.0, 1.0));
        let t = (xo / (1.0 - eo * eo).max(1e-12).sqrt()).clamp(-1.0, 1.0);
        2.0 * sample(&self.q_r, self.normal_nx, self.normal_ny, t, eo) / self.p0
    }

    /// The error of a patch the linearisation does not hold.
    fn out_of_range(&self) -> super::ContactError {
        super::ContactError::LinearRange { shift: self.shift, stretch: 100.0 * self.stretch, a: self.hertz_a }
    }
}

/// A model's linear profile contact: its response on the model's mesh, if
/// the model was built with one, and the rail surface set for the passage.
#[derive(Debug, Clone, Default)]
pub struct LinearContact {
    response: Option<MeshResponse>,
    rail: Option<RailContact>,
}

impl LinearContact {
    /// The linear contact of the tangential `mesh` of the Hertz contact
    /// `shape`.
    pub fn new(mesh: &EllipseMesh, shape: &HertzShape) -> Self {
        LinearContact { response: Some(MeshResponse::new(mesh, shape)), rail: None }
    }

    /// The shortest wavelength it resolves on a patch of semi-axis `a` (m)
    /// ([`MeshResponse::resolution`]); `None` without a response.
    pub fn resolution(&self, a: f64) -> Option<f64> {
        self.response.as_ref().map(|r| r.resolution(a))
    }

    /// Takes the surface of the following steps: a linear one needs the
    /// response; the nonlinear profile contact is the fixed grid's.
    pub fn set_surface(&mut self, surface: Option<RailContact>) -> Result<(), super::ContactError> {
        match surface {
            Some(RailContact::Linear(_)) if self.response.is_none() => Err(super::ContactError::NoSurface),
            Some(RailContact::Profile(_)) => Err(super::ContactError::NoSurface),
            s => {
                self.rail = s;
                Ok(())
            }
        }
    }

    /// The step's patch moved with the linear surface set
    /// ([`MeshResponse::linear_patch`]); `None` without one (the Hertz
    /// patch and the shape's pressure).
    pub fn patch(
        &self,
        position: f64,
        patch: &HertzPatch,
        shape: PressureShape,
        mesh: &EllipseMesh,
        uniform: bool,
    ) -> Result<Option<LinearPatch>, super::ContactError> {
        match (&self.response, &self.rail) {
            (Some(response), Some(RailContact::Linear(surface))) => {
                response.linear_patch(surface, position, patch, shape, mesh, uniform).map(Some)
            }
            _ => Ok(None),
        }
    }
}

/// The solution operator of the bordered system at a = 1 m:
/// `[A, -1; area^T, 0] [dp; d delta] = [r; 0]`, the rows giving `dp`.
fn solution_operator(mesh: &EllipseMesh, b_over_a: f64, elastic: Elastic) -> Vec<f64> {
    let n = mesh.len();
    let (g, nu) = (elastic.shear_modulus(), elastic.poisson_ratio);
    let rect = |k: usize| Rect {
        x: mesh.xi[k],
        y: mesh.eta[k] * b_over_a,
        hx: 0.5 * mesh.d_xi[mesh.strip(k)],
        hy: 0.5 * mesh.d_eta * b_over_a,
    };
    // Scaled to order one: influence coefficients are ~ 1/G.
    let mut m = Mat::<f64>::zeros(n + 1, n + 1);
    for j in 0..n {
        let rj = rect(j);
        for i in 0..n {
            m[(i, j)] = g * normal_influence(&rj, mesh.xi[i], mesh.eta[i] * b_over_a, g, nu);
        }
        m[(j, n)] = -1.0;
        m[(n, j)] = mesh.area(j);
    }
    let lu = m.partial_piv_lu();
    let mut rhs = Mat::<f64>::zeros(n + 1, n);
    for i in 0..n {
        rhs[(i, i)] = 1.0;
    }
    lu.solve_in_place(rhs.as_mut());
    // dp = (G S') r: undo the scaling.
    let mut op = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            op[i * n + j] = g * rhs[(i, j)];
        }
    }
    op
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper_shape() -> HertzShape {
        let el = Elastic { young_modulus: 2.1e11, poisson_ratio: 0.3 };
        HertzShape::new(Curvatures::wheel_on_rail(0.5, -0.409, 0.3), el).unwrap()
    }

    /// The paper's contact at `n_force` (N) on an `nx x ny` mesh and its
    /// linear response.
    fn setup(n_force: f64, nx: usize, ny: usize) -> (HertzShape, HertzPatch, EllipseMesh, MeshResponse) {
        let shape = paper_shape();
        let mesh = EllipseMesh::new(nx, ny);
        let resp = MeshResponse::new(&mesh, &shape);
        (shape, shape.patch(n_force).unwrap(), mesh, resp)
    }

    /// A line `f(X)` along the rail, uniform across, sampled every 10 um.
    fn line(f: impl Fn(f64) -> f64) -> RailSurface {
        let (x0, dx, n) = (-0.02, 1e-5, 4001);
        let v: Vec<f64> = (0..n).map(|i| f(x0 + i as f64 * dx)).collect();
        RailSurface::line(x0, dx, &v, false)
    }

    #[test]
    fn a_tilted_rail_shifts_the_hertz_patch_by_r_times_the_slope() {
        // r = alpha X: the gap A x^2 - alpha x is Hertz's about x = alpha /
        // (2 A): the contact point of a wheel of radius R = 1 / (2 A) moves
        // by R alpha, the patch unchanged.
        let (shape, patch, mesh, resp) = setup(1e5, 16, 12);
        let alpha = 1e-4;
        let lp = resp.linear_patch(&line(|x| alpha * x), 0.0, &patch, PressureShape::Hertz, &mesh, false).unwrap();
        let expected = alpha / (2.0 * shape.curvatures().a);
        assert!((lp.offset - expected).abs() < 1e-9 * expected, "{} vs {expected}", lp.offset);
        assert!((lp.a - patch.a).abs() < 1e-12 * patch.a && (lp.b - patch.b).abs() < 1e-12 * patch.b);
        // The pressure is the Hertz pressure on the moved patch (the rest of
        // the response, discretised, within 1 % of p0).
        let hertz = pressure_on_mesh(&mesh, PressureShape::Hertz, 1e5, lp.a, lp.b);
        for (p, h) in lp.pressure.iter().zip(&hertz) {
            assert!((p - h).abs() < 1e-2 * patch.p0, "{p} vs {h}");
        }
    }

    #[test]
    fn a_curved_rail_gives_the_hertz_patch_of_the_changed_curvature() {
        // r = kappa X^2 / 2 changes A to A - kappa / 2: the semi-axes of
        // that Hertz patch, to first order (kappa = 0.2 % of A: second
        // order 1e-3 of the change).
        let (shape, patch, mesh, resp) = setup(1e5, 16, 12);
        let c = shape.curvatures();
        let kappa = 2e-3 * c.a;
        let lp =
            resp.linear_patch(&line(|x| 0.5 * kappa * x * x), 0.0, &patch, PressureShape::Hertz, &mesh, false).unwrap();
        let bent = HertzShape::new(Curvatures { a: c.a - 0.5 * kappa, b: c.b }, shape.elastic()).unwrap();
        let exact = bent.patch(1e5).unwrap();
        assert!(lp.offset.abs() < 1e-12 * patch.a);
        let (da, db) = (lp.a - patch.a, lp.b - patch.b);
        assert!((da - (exact.a - patch.a)).abs() < 2e-3 * (exact.a - patch.a).abs(), "{da} vs {}", exact.a - patch.a);
        assert!((db - (exact.b - patch.b)).abs() < 2e-3 * (exact.b - patch.b).abs(), "{db} vs {}", exact.b - patch.b);
    }

    #[test]
    fn flat_rail_is_hertz_bit_for_bit_and_every_step_holds_the_force() {
        let (_, patch, mesh, resp) = setup(1.2e5, 12, 10);
        for bound in [PressureShape::Hertz, PressureShape::Parabolic] {
            let flat = resp.linear_patch(&line(|_| 0.0), 0.003, &patch, bound, &mesh, false).unwrap();
            assert_eq!(flat.pressure, pressure_on_mesh(&mesh, bound, 1.2e5, patch.a, patch.b));
            assert_eq!((flat.offset, flat.a, flat.b), (0.0, patch.a, patch.b));
            let k = 2.0 * PI / 0.02;
            let wavy = resp.linear_patch(&line(|x| 2e-6 * (k * x).cos()), 0.003, &patch, bound, &mesh, true).unwrap();
            let total = mesh.integrate(&wavy.pressure, wavy.a, wavy.b);
            assert!((total - 1.2e5).abs() < 1e-10 * 1.2e5);
            // Uniform: b stretched as a.
            assert!((wavy.a / patch.a - wavy.b / patch.b).abs() < 1e-12);
        }
    }

    #[test]
    fn the_patch_moves_linearly_with_the_profile() {
        let (shape, patch, mesh, resp) = setup(1e5, 40, 40);
        assert_eq!(resp.normal_elements(), 20 * 20);
        let k = 2.0 * PI / 0.015;
        let at = |amp: f64| {
            resp.linear_patch(&line(|x| amp * (k * x).sin()), 0.001, &patch, PressureShape::Parabolic, &mesh, false)
                .unwrap()
        };
        let (one, three) = (at(1e-7), at(3e-7));
        assert!((3.0 * one.offset - three.offset).abs() < 1e-12 * three.offset.abs());
        assert!((3.0 * (one.a - patch.a) - (three.a - patch.a)).abs() < 1e-9 * (three.a - patch.a).abs());
        // The wave's slope at X_c = 1 mm moves the contact point by about
        // R r' (the patch averages the slope: sin(ka)/ka-like).
        let slope = 1e-7 * k * (k * 0.001).cos();
        let r_slope = slope / (2.0 * shape.curvatures().a);
        assert!(one.offset * slope > 0.0 && one.offset.abs() < r_slope.abs(), "{} vs {r_slope}", one.offset);
    }

    #[test]
    fn a_corrugation_far_beyond_the_linear_range_is_refused() {
        // 50 um at 15 mm: R r'' = 4.4, the patch would move by more than
        // half its length.
        let (_, patch, mesh, resp) = setup(1e5, 12, 10);
        let k = 2.0 * PI / 0.015;
        let e = resp.linear_patch(&line(|x| 5e-5 * (k * x).sin()), 0.0, &patch, PressureShape::Hertz, &mesh, false);
        assert!(matches!(e, Err(crate::contact::ContactError::LinearRange { .. })), "{e:?}");
    }
}
