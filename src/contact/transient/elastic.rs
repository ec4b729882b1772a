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
use crate::contact::influence::{Influence, Rect, Strip, influence, strip_coefficients};
use faer::Mat;
use rayon::prelude::*;

/// Rows of `u = C p` from which the product runs in two parallel blocks.
const PARALLEL_ROWS: usize = 256;

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
    /// Matrix of [`ExactElastic::previous`] for the last (frames, shift).
    previous_cache: Option<([u64; 5], Mat<f64>)>,
    /// (frames, shift) of the last call: the matrix is only built when the
    /// same key comes twice in a row (constant load); a key seen once is
    /// evaluated directly, strip by strip and a point with its mirror image,
    /// which costs about a quarter of the kernel evaluations of the matrix
    /// and no storage.
    last_key: Option<[u64; 5]>,
}

impl ExactElastic {
    /// Assembles the unit influence matrix for `mesh` and semi-axis ratio
    /// `aspect` = a/b; shear modulus `g` (Pa), Poisson's ratio `nu`.
    pub fn new(mesh: &EllipseMesh, aspect: f64, g: f64, nu: f64) -> Self {
        let unit = PatchFrame { a: 1.0, b: 1.0 / aspect };
        let points: Vec<(f64, f64)> = (0..mesh.len()).map(|k| (mesh.xi[k], mesh.eta[k] / aspect)).collect();
        let c_unit = influence_matrix(mesh, unit, &points, g, nu);
        ExactElastic { g, nu, aspect, c_unit, previous_cache: None, last_key: None }
    }

    /// Forgets the earlier-displacement matrix and key, so that what follows
    /// does not depend on what came before.
    pub fn reset(&mut self) {
        self.previous_cache = None;
        self.last_key = None;
    }

    /// Semi-axis ratio a/b the matrix was built for.
    pub fn aspect(&self) -> f64 {
        self.aspect
    }

    /// The unit matrix C_1 (C = a C_1).
    pub fn unit_matrix(&self) -> &Mat<f64> {
        &self.c_unit
    }

    /// `u = C p` for the patch with semi-axis `a` (interleaved vectors). Rows
    /// in two parallel blocks above [`PARALLEL_ROWS`]; each row's sum runs
    /// over the columns in order, so the result does not depend on the split.
    pub fn displacement(&self, a: f64, p: &[f64], u: &mut [f64]) {
        let rows = |first: usize, u: &mut [f64]| {
            u.iter_mut().for_each(|v| *v = 0.0);
            for (c, pc) in p.iter().enumerate() {
                if *pc == 0.0 {
                    continue;
                }
                let f = a * pc;
                let col = &self.c_unit.col_as_slice(c)[first..first + u.len()];
                for (ur, cr) in u.iter_mut().zip(col) {
                    *ur += cr * f;
                }
            }
        };
        if u.len() < PARALLEL_ROWS {
            rows(0, u);
        } else {
            let half = u.len() / 2;
            let (lo, hi) = u.split_at_mut(half);
            rayon::join(|| rows(0, lo), || rows(half, hi));
        }
    }

    /// Displacement at the current element centres of the material that was
    /// at `x + shift` in the previous patch `old` under tractions `p_old`.
    /// The matrix of this map depends only on the two frames and the shift;
    /// it is kept and reused while they do not change (constant load).
    pub fn previous(
        &mut self,
        mesh: &EllipseMesh,
        now: PatchFrame,
        old: PatchFrame,
        shift: f64,
        p_old: &[f64],
        u_o: &mut [f64],
    ) {
        let key = [now.a, now.b, old.a, old.b, shift].map(f64::to_bits);
        let points: Vec<(f64, f64)> =
            (0..mesh.len()).map(|j| (mesh.xi[j] * now.a + shift, mesh.eta[j] * now.b)).collect();
        let cached = self.previous_cache.as_ref().is_some_and(|(k, _)| *k == key);
        if !cached && self.last_key != Some(key) {
            self.last_key = Some(key);
            previous_direct(mesh, old, &points, p_old, self.g, self.nu, u_o);
            return;
        }
        if !cached {
            self.previous_cache = Some((key, influence_matrix(mesh, old, &points, self.g, self.nu)));
        }
        let b = &self.previous_cache.as_ref().expect("just filled").1;
        u_o.iter_mut().for_each(|v| *v = 0.0);
        for (c, pc) in p_old.iter().enumerate() {
            if *pc != 0.0 {
                for (ur, br) in u_o.iter_mut().zip(b.col_as_slice(c)) {
                    *ur += br * pc;
                }
            }
        }
    }
}

/// `u = B p` of [`ExactElastic::previous`] without the matrix: at each point,
/// the strips of the patch `frame` summed with shared corners
/// ([`crate::contact::influence::strip_coefficients`]).
///
/// The mesh is symmetric about y = 0 (strip `j` mirrors strip `ny - 1 - j`,
/// to rounding: its eta is built as `-1 + (j + 1/2) d_eta`) and so are the
/// points (the patch moves along x only): the coefficients of the old strip
/// `j'` at the mirror image of a point are those of strip `j` at the point,
/// with `c_xy` of opposite sign. Each coefficient is evaluated once and
/// serves the point and its image: half the kernel evaluations. The lower
/// half of the points is bit-identical to the point-by-point sum, the upper
/// within about 3e-14 of it. Point pairs in parallel.
fn previous_direct(
    mesh: &EllipseMesh,
    frame: PatchFrame,
    points: &[(f64, f64)],
    p: &[f64],
    g: f64,
    nu: f64,
    u: &mut [f64],
) {
    let (nx, ny) = (mesh.nx, mesh.ny);
    let strips: Vec<Strip> = (0..ny)
        .map(|j| {
            let c = mesh.half_chord[j];
            let eta = mesh.eta[j * nx];
            Strip {
                edges: (0..=nx).map(|e| frame.a * (c - e as f64 * mesh.d_xi[j])).collect(),
                y_lo: frame.b * (eta - 0.5 * mesh.d_eta),
                y_hi: frame.b * (eta + 0.5 * mesh.d_eta),
            }
        })
        .collect();
    // The points of the lower half and the middle row; k' is the image.
    let lower: Vec<usize> = (0..ny.div_ceil(2) * nx).collect();
    let mirror = |k: usize| (ny - 1 - k / nx) * nx + k % nx;
    let s = 1.0 / (std::f64::consts::PI * g);
    let sums: Vec<([f64; 2], [f64; 2])> = lower
        .par_iter()
        .map_init(
            || (Vec::new(), vec![[0.0; 3]; nx]),
            |(buf, c), &k| {
                let (mut own, mut image) = ([0.0; 2], [0.0; 2]);
                for (j, strip) in strips.iter().enumerate() {
                    strip_coefficients(strip, points[k], nu, buf, c);
                    let (jm, mut d, mut e) = (ny - 1 - j, [0.0; 2], [0.0; 2]);
                    for (i, ci) in c.iter().enumerate() {
                        let (px, py) = (p[2 * (j * nx + i)], p[2 * (j * nx + i) + 1]);
                        d[0] += ci[0] * px + ci[1] * py;
                        d[1] += ci[1] * px + ci[2] * py;
                        let (qx, qy) = (p[2 * (jm * nx + i)], p[2 * (jm * nx + i) + 1]);
                        e[0] += ci[0] * qx - ci[1] * qy;
                        e[1] += -ci[1] * qx + ci[2] * qy;
                    }
                    own = [own[0] + s * d[0], own[1] + s * d[1]];
                    image = [image[0] + s * e[0], image[1] + s * e[1]];
                }
                (own, image)
            },
        )
        .collect();
    for (&k, (own, image)) in lower.iter().zip(&sums) {
        u[2 * k..2 * k + 2].copy_from_slice(own);
        let km = mirror(k);
        if km != k {
            u[2 * km..2 * km + 2].copy_from_slice(image);
        }
    }
}

/// Influence matrix (2P x 2N, interleaved) of the elements of `mesh` in
/// patch `frame` at the points `points` (m). Rows are computed in parallel.
fn influence_matrix(mesh: &EllipseMesh, frame: PatchFrame, points: &[(f64, f64)], g: f64, nu: f64) -> Mat<f64> {
    let n = mesh.len();
    let rects: Vec<Rect> = (0..n).map(|k| frame.rect(mesh, k)).collect();
    let rows: Vec<Vec<Influence>> =
        points.par_iter().map(|(x, y)| rects.iter().map(|r| influence(r, *x, *y, g, nu)).collect()).collect();
    Mat::from_fn(2 * points.len(), 2 * n, |r, c| {
        let inf = rows[r / 2][c / 2];
        match (r % 2, c % 2) {
            (0, 0) => inf.xx,
            (1, 1) => inf.yy,
            _ => inf.xy,
        }
    })
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

    /// Earlier displacement: L times the previous traction field at
    /// (x + shift, y), the field being linear between the element centres
    /// along each strip, zero at the leading edge (unstrained material
    /// enters there), constant from the last centre to the trailing edge, and
    /// linear between strip centre lines.
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
            let (px, py) = interpolate(mesh, p_old, x / old.a, y / old.b);
            u_o[2 * j] = l1 * px;
            u_o[2 * j + 1] = l2 * py;
        }
    }
}

/// Traction field of `p` (interleaved) at normalised point (xi, eta),
/// interpolated as described in [`WinklerElastic::previous`].
pub(super) fn interpolate(mesh: &EllipseMesh, p: &[f64], xi: f64, eta: f64) -> (f64, f64) {
    if eta.abs() >= 1.0 {
        return (0.0, 0.0);
    }
    // Strip centre lines eta_j = -1 + (j + 1/2) d_eta.
    let t = (eta + 1.0) / mesh.d_eta - 0.5;
    let j0 = t.floor().clamp(0.0, (mesh.ny - 1) as f64) as usize;
    let j1 = (j0 + 1).min(mesh.ny - 1);
    let w1 = if j1 == j0 { 0.0 } else { (t - j0 as f64).clamp(0.0, 1.0) };
    let a = along_strip(mesh, p, j0, xi);
    let b = along_strip(mesh, p, j1, xi);
    ((1.0 - w1) * a.0 + w1 * b.0, (1.0 - w1) * a.1 + w1 * b.1)
}

fn along_strip(mesh: &EllipseMesh, p: &[f64], j: usize, xi: f64) -> (f64, f64) {
    let c = mesh.half_chord[j];
    let d = mesh.d_xi[j];
    let at = |i: usize| (p[2 * (j * mesh.nx + i)], p[2 * (j * mesh.nx + i) + 1]);
    if xi >= c || xi <= -c {
        return (0.0, 0.0);
    }
    // Position in element-centre units from the leading edge: centre i at u = i + 1/2.
    let u = (c - xi) / d;
    if u <= 0.5 {
        let (px, py) = at(0);
        return (px * u / 0.5, py * u / 0.5);
    }
    let last = mesh.nx - 1;
    if u >= last as f64 + 0.5 {
        return at(last);
    }
    let i0 = (u - 0.5).floor() as usize;
    let w = u - 0.5 - i0 as f64;
    let (a, b) = (at(i0), at((i0 + 1).min(last)));
    ((1.0 - w) * a.0 + w * b.0, (1.0 - w) * a.1 + w * b.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaling_and_previous_agree_with_direct_assembly() {
        let mesh = EllipseMesh::new(6, 5);
        let mut e = ExactElastic::new(&mesh, 0.6, 8e10, 0.3);
        let frame = PatchFrame { a: 6e-3, b: 1e-2 };
        let p: Vec<f64> = (0..2 * mesh.len()).map(|i| (i as f64 * 0.37).sin() * 1e8).collect();
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
    fn previous_direct_equals_the_matrix_path() {
        // A varying load (new frame each call) takes the direct strip sum; the
        // same key twice builds and uses the matrix. Both within 1e-12.
        let mesh = EllipseMesh::new(9, 7);
        let mut e = ExactElastic::new(&mesh, 0.6, 8e10, 0.3);
        let (old, now) = (PatchFrame { a: 6e-3, b: 1e-2 }, PatchFrame { a: 6.1e-3, b: 6.1e-3 / 0.6 });
        let p: Vec<f64> = (0..2 * mesh.len()).map(|i| (i as f64 * 0.37).sin() * 1e8).collect();
        let (mut direct, mut matrix) = (vec![0.0; p.len()], vec![0.0; p.len()]);
        e.previous(&mesh, now, old, 2e-4, &p, &mut direct);
        assert!(e.previous_cache.is_none(), "one call: no matrix");
        e.previous(&mesh, now, old, 2e-4, &p, &mut matrix);
        assert!(e.previous_cache.is_some(), "the same key twice: matrix");
        let scale = matrix.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (k, (d, m)) in direct.iter().zip(&matrix).enumerate() {
            assert!((d - m).abs() < 1e-12 * scale, "{k}: {d} vs {m}");
        }
    }

    #[test]
    fn winkler_interpolation_is_linear_between_centres_and_zero_at_the_leading_edge() {
        let mesh = EllipseMesh::new(8, 4);
        // p_x = 1 + xi (linear along x), p_y = 0.
        let p: Vec<f64> = (0..mesh.len()).flat_map(|k| [1.0 + mesh.xi[k], 0.0]).collect();
        let j = 1;
        let k = j * mesh.nx + 3;
        let mid = 0.5 * (mesh.xi[k] + mesh.xi[k + 1]);
        let (px, _) = interpolate(&mesh, &p, mid, mesh.eta[k]);
        assert!((px - (1.0 + mid)).abs() < 1e-12);
        let (px, _) = interpolate(&mesh, &p, mesh.half_chord[j] - 1e-12, mesh.eta[k]);
        assert!(px.abs() < 1e-9, "zero at the leading edge");
        assert_eq!(interpolate(&mesh, &p, 0.0, 1.2), (0.0, 0.0));
    }
}
