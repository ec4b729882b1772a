//! Elastic models of the transient solver: the displacement difference
//! `u = C p` at the element centres of the current patch, and the
//! displacement `u_o` that the same material points had one step earlier.
//!
//! * [`ExactElastic`]: Kalker's exact theory on the half-space, `C` from the
//!   rectangle influence coefficients ([`crate::contact::influence`]). With the
//!   Hertz curvatures fixed, a/b does not change with N, so the matrix for
//!   semi-axis `a` is `a C_1` with `C_1` assembled once for a = 1 m.
//!   The earlier displacement is the field of the previous step's tractions
//!   evaluated at the point's earlier position `x + dX` in the previous patch
//!   frame (dX the patch displacement), so a changing mesh needs no
//!   interpolation of displacements (Baeza et al. 2008, Eq. 5).
//! * [`WinklerElastic`]: Kalker's simplified theory, `u = L p` element by
//!   element with `L1` along x and `L2` along y (`L1 = 8a/(3 C11 G)`,
//!   `L2 = 8a/(3 C22 G)`); the earlier displacement is `L` times the previous
//!   traction of the element that contained the earlier position (zero
//!   outside the previous patch).

use crate::contact::EllipseMesh;
use crate::contact::influence::{Rect, influence};
use faer::Mat;

/// Geometry of a patch on the normalised mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchFrame {
    /// Semi-axis along x (m).
    pub a: f64,
    /// Semi-axis along y (m).
    pub b: f64,
}

impl PatchFrame {
    /// Physical rectangle of element `k`.
    pub fn rect(&self, mesh: &EllipseMesh, k: usize) -> Rect {
        let j = mesh.strip(k);
        Rect {
            x: mesh.xi[k] * self.a,
            y: mesh.eta[k] * self.b,
            hx: 0.5 * mesh.d_xi[j] * self.a,
            hy: 0.5 * mesh.d_eta * self.b,
        }
    }
}

/// Exact half-space elastic model.
#[derive(Debug, Clone)]
pub struct ExactElastic {
    g: f64,
    nu: f64,
    aspect: f64,
    /// C for a = 1 m (and b = 1/aspect), 2N x 2N, unknowns interleaved
    /// (x of element k at 2k, y at 2k + 1) (m/Pa per m of a).
    c_unit: Mat<f64>,
}

impl ExactElastic {
    /// Assembles the unit influence matrix for `mesh` and semi-axis ratio
    /// `aspect` = a/b; shear modulus `g` (Pa), Poisson's ratio `nu`.
    pub fn new(mesh: &EllipseMesh, aspect: f64, g: f64, nu: f64) -> Self {
        let n = mesh.len();
        let unit = PatchFrame {
            a: 1.0,
            b: 1.0 / aspect,
        };
        let rects: Vec<Rect> = (0..n).map(|k| unit.rect(mesh, k)).collect();
        let c_unit = Mat::from_fn(2 * n, 2 * n, |r, c| {
            let (j, k) = (r / 2, c / 2);
            let inf = influence(&rects[k], rects[j].x, rects[j].y, g, nu);
            match (r % 2, c % 2) {
                (0, 0) => inf.xx,
                (1, 1) => inf.yy,
                _ => inf.xy,
            }
        });
        ExactElastic {
            g,
            nu,
            aspect,
            c_unit,
        }
    }

    /// Semi-axis ratio a/b the matrix was built for.
    pub fn aspect(&self) -> f64 {
        self.aspect
    }

    /// The unit matrix C_1 (C = a C_1).
    pub fn unit_matrix(&self) -> &Mat<f64> {
        &self.c_unit
    }

    /// `u = C p` for the patch with semi-axis `a` (interleaved vectors).
    pub fn displacement(&self, a: f64, p: &[f64], u: &mut [f64]) {
        u.iter_mut().for_each(|v| *v = 0.0);
        for (c, pc) in p.iter().enumerate() {
            if *pc == 0.0 {
                continue;
            }
            let f = a * pc;
            for (ur, cr) in u.iter_mut().zip(self.c_unit.col_as_slice(c)) {
                *ur += cr * f;
            }
        }
    }

    /// Displacement at the current element centres of the material that was
    /// at `x + shift` in the previous patch `old` under tractions `p_old`.
    pub fn previous(
        &self,
        mesh: &EllipseMesh,
        now: PatchFrame,
        old: PatchFrame,
        shift: f64,
        p_old: &[f64],
        u_o: &mut [f64],
    ) {
        let n = mesh.len();
        let rects: Vec<Rect> = (0..n).map(|k| old.rect(mesh, k)).collect();
        for j in 0..n {
            let (x, y) = (mesh.xi[j] * now.a + shift, mesh.eta[j] * now.b);
            let (mut ux, mut uy) = (0.0, 0.0);
            for (k, rect) in rects.iter().enumerate() {
                let (px, py) = (p_old[2 * k], p_old[2 * k + 1]);
                if px == 0.0 && py == 0.0 {
                    continue;
                }
                let c = influence(rect, x, y, self.g, self.nu);
                ux += c.xx * px + c.xy * py;
                uy += c.xy * px + c.yy * py;
            }
            u_o[2 * j] = ux;
            u_o[2 * j + 1] = uy;
        }
    }
}

/// Simplified (Winkler) elastic model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WinklerElastic {
    /// L1 per metre of a (m/Pa / m).
    pub l1_unit: f64,
    /// L2 per metre of a.
    pub l2_unit: f64,
}

impl WinklerElastic {
    /// Flexibilities (L1, L2) for semi-axis `a` (m/Pa).
    pub fn flexibility(&self, a: f64) -> (f64, f64) {
        (self.l1_unit * a, self.l2_unit * a)
    }

    /// Earlier displacement: L times the previous traction of the element
    /// of the previous patch that contains (x + shift, y).
    pub fn previous(
        &self,
        mesh: &EllipseMesh,
        now: PatchFrame,
        old: PatchFrame,
        shift: f64,
        p_old: &[f64],
        u_o: &mut [f64],
    ) {
        let (l1, l2) = self.flexibility(old.a);
        for j in 0..mesh.len() {
            let (x, y) = (mesh.xi[j] * now.a + shift, mesh.eta[j] * now.b);
            let (ux, uy) = match locate(mesh, old, x, y) {
                Some(k) => (l1 * p_old[2 * k], l2 * p_old[2 * k + 1]),
                None => (0.0, 0.0),
            };
            u_o[2 * j] = ux;
            u_o[2 * j + 1] = uy;
        }
    }
}

/// The element of `mesh` in patch `frame` that contains (x, y), if any.
pub fn locate(mesh: &EllipseMesh, frame: PatchFrame, x: f64, y: f64) -> Option<usize> {
    let eta = y / frame.b;
    let j = ((eta + 1.0) / mesh.d_eta).floor();
    if !(0.0..mesh.ny as f64).contains(&j) {
        return None;
    }
    let j = j as usize;
    let c = mesh.half_chord[j];
    let xi = x / frame.a;
    // Elements run from the leading edge xi = c towards -c.
    let i = ((c - xi) / mesh.d_xi[j]).floor();
    if !(0.0..mesh.nx as f64).contains(&i) {
        return None;
    }
    Some(j * mesh.nx + i as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaling_and_previous_agree_with_direct_assembly() {
        let mesh = EllipseMesh::new(6, 5);
        let e = ExactElastic::new(&mesh, 0.6, 8e10, 0.3);
        let frame = PatchFrame { a: 6e-3, b: 1e-2 };
        let p: Vec<f64> = (0..2 * mesh.len())
            .map(|i| (i as f64 * 0.37).sin() * 1e8)
            .collect();
        let mut u = vec![0.0; p.len()];
        e.displacement(frame.a, &p, &mut u);
        let mut u_o = vec![0.0; p.len()];
        // Zero shift and the same patch: the earlier displacement is C p.
        e.previous(&mesh, frame, frame, 0.0, &p, &mut u_o);
        for (x, y) in u.iter().zip(&u_o) {
            assert!((x - y).abs() < 1e-12 * u.iter().map(|v| v.abs()).fold(0.0, f64::max));
        }
    }

    #[test]
    fn locate_finds_the_containing_element() {
        let mesh = EllipseMesh::new(8, 4);
        let f = PatchFrame { a: 2.0, b: 1.0 };
        for k in 0..mesh.len() {
            assert_eq!(locate(&mesh, f, mesh.xi[k] * 2.0, mesh.eta[k]), Some(k));
        }
        assert_eq!(locate(&mesh, f, 2.5, 0.0), None);
    }
}
