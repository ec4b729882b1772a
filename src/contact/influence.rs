//! Tangential influence coefficients of the elastic half-space for uniform
//! traction on a rectangle.
//!
//! Cerruti's solution (Johnson, *Contact Mechanics*, 1985, eq. 3.86 at z = 0):
//! a tangential point force Q_x at the origin displaces the surface point
//! (x, y), r = sqrt(x^2 + y^2), by
//!
//! ```text
//! u_x = Q_x / (2 pi G) [(1 - nu)/r + nu x^2/r^3],   u_y = Q_x / (2 pi G) nu x y / r^3
//! ```
//!
//! (and symmetrically for Q_y). For quasi-identical bodies the normal and
//! tangential problems decouple, and the displacement *difference* of the two
//! bodies under opposite tractions is twice this. Integrating over a rectangle
//! of uniform traction (Kalker, *Three-dimensional elastic bodies in rolling
//! contact*, 1990, ch. 5; the same primitives as Love's rectangle solution),
//! with `X = x - x'`, `Y = y - y'` and the corner rule
//! `[[F]] = F(Xb, Yb) - F(Xa, Yb) - F(Xb, Ya) + F(Xa, Ya)`:
//!
//! ```text
//! int int 1/r     = X asinh(Y/|X|) + Y asinh(X/|Y|)
//! int int X^2/r^3 = Y asinh(X/|Y|)
//! int int Y^2/r^3 = X asinh(Y/|X|)
//! int int X Y/r^3 = -r
//! ```
//!
//! (the `ln|X|` parts of `ln(Y + r)` cancel between corners, which makes the
//! asinh form exact and finite on element edges and at the centre).

use std::f64::consts::PI;
use wide::f64x4;

/// An axis-aligned rectangle (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Centre x (m).
    pub x: f64,
    /// Centre y (m).
    pub y: f64,
    /// Half-length along x (m).
    pub hx: f64,
    /// Half-width along y (m).
    pub hy: f64,
}

/// Displacement difference (m) per unit uniform traction (Pa) on a
/// rectangle, at a point: `[[c_xx, c_xy], [c_yx, c_yy]]` with `c_yx = c_xy`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Influence {
    /// u_x per unit p_x (m/Pa).
    pub xx: f64,
    /// u_x per unit p_y = u_y per unit p_x (m/Pa).
    pub xy: f64,
    /// u_y per unit p_y (m/Pa).
    pub yy: f64,
}

/// X asinh(Y/|X|), zero on X = 0.
fn xa(x: f64, y: f64) -> f64 {
    if x == 0.0 { 0.0 } else { x * (y / x.abs()).asinh() }
}

/// The primitives (1/r, X^2/r^3, Y^2/r^3, XY/r^3) at one corner.
fn corner(x: f64, y: f64) -> [f64; 4] {
    let a = xa(x, y); // X asinh(Y/|X|)
    let b = xa(y, x); // Y asinh(X/|Y|)
    [a + b, b, a, -(x * x + y * y).sqrt()]
}

/// Influence of uniform traction on `rect` at point (`x`, `y`) for shear
/// modulus `g` (Pa) and Poisson's ratio `nu`: displacement difference of two
/// identical half-spaces (m per Pa).
pub fn influence(rect: &Rect, x: f64, y: f64, g: f64, nu: f64) -> Influence {
    let (xa_, xb) = (x - rect.x - rect.hx, x - rect.x + rect.hx);
    let (ya, yb) = (y - rect.y - rect.hy, y - rect.y + rect.hy);
    let c_bb = corner(xb, yb);
    let c_ab = corner(xa_, yb);
    let c_ba = corner(xb, ya);
    let c_aa = corner(xa_, ya);
    let i = |k: usize| c_bb[k] - c_ab[k] - c_ba[k] + c_aa[k];
    // Two bodies: 2 / (2 pi G) = 1 / (pi G).
    let s = 1.0 / (PI * g);
    Influence { xx: s * ((1.0 - nu) * i(0) + nu * i(1)), xy: s * nu * i(3), yy: s * ((1.0 - nu) * i(0) + nu * i(2)) }
}

/// Normal influence of uniform pressure on `rect` at point (`x`, `y`):
/// the approach of the surfaces of two identical half-spaces (m per Pa).
/// Boussinesq's point load displaces the surface by `(1 - nu) P / (2 pi G
/// r)`; integrated over the rectangle (Love 1929; Johnson 1985, sec. 3.2)
/// with the same primitive `int int 1/r` as the tangential coefficients, and
/// doubled for the two bodies.
pub fn normal_influence(rect: &Rect, x: f64, y: f64, g: f64, nu: f64) -> f64 {
    let (xa_, xb) = (x - rect.x - rect.hx, x - rect.x + rect.hx);
    let (ya, yb) = (y - rect.y - rect.hy, y - rect.y + rect.hy);
    let i0 = corner(xb, yb)[0] - corner(xa_, yb)[0] - corner(xb, ya)[0] + corner(xa_, ya)[0];
    (1.0 - nu) * i0 / (PI * g)
}

/// The corner primitives of [`corner`] at (x, y1) and (x, y2) from one
/// square root and two logarithms each: `X asinh(Y/|X|) = X sign(Y)
/// ln((|Y| + r)/|X|)` (same value to rounding; the far field loses nothing
/// that matters, see the test). The four logarithms in one SIMD evaluation
/// (`wide`'s vectorised ln, within a few ulp of libm's).
#[inline]
fn corner_pair(x: f64, y1: f64, y2: f64) -> ([f64; 4], [f64; 4]) {
    let (r1, r2) = ((x * x + y1 * y1).sqrt(), (x * x + y2 * y2).sqrt());
    let (ax, ay1, ay2) = (x.abs(), y1.abs(), y2.abs());
    // ln(1) = 0 where the prefactor (x or y) vanishes and the ratio would not
    // be finite.
    let ratio = |num: f64, den: f64| if den == 0.0 { 1.0 } else { num / den };
    let logs = f64x4::new([ratio(ay1 + r1, ax), ratio(ax + r1, ay1), ratio(ay2 + r2, ax), ratio(ax + r2, ay2)])
        .ln()
        .to_array();
    let corner = |y: f64, r: f64, la: f64, lb: f64| {
        let a = x * y.signum() * la;
        let b = y * x.signum() * lb;
        [a + b, b, a, -r]
    };
    (corner(y1, r1, logs[0], logs[1]), corner(y2, r2, logs[2], logs[3]))
}

/// A strip of contiguous rectangles: element `i` spans `edges[i + 1] ..
/// edges[i]` along x (m, decreasing) and `y_lo .. y_hi` along y (m).
#[derive(Debug, Clone, PartialEq)]
pub struct Strip {
    /// x-edges (m), decreasing, one more than the elements.
    pub edges: Vec<f64>,
    /// Lower y-edge (m).
    pub y_lo: f64,
    /// Upper y-edge (m).
    pub y_hi: f64,
}

/// Displacement difference at the point (`x`, `y`) (m) under uniform
/// tractions `(px[i], py[i])` (Pa) on the elements of `strip`. The same
/// corner rule as [`influence`], with the corners shared by neighbouring
/// elements evaluated once: `2 (n + 1)` corners instead of `4 n`.
pub fn strip_displacement(strip: &Strip, (px, py): (&[f64], &[f64]), (x, y): (f64, f64), g: f64, nu: f64) -> [f64; 2] {
    let edges = &strip.edges;
    let (ya, yb) = (y - strip.y_hi, y - strip.y_lo);
    let edge = |e: f64| {
        let (hi, lo) = corner_pair(x - e, yb, ya);
        [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], hi[3] - lo[3]]
    };
    let s = 1.0 / (PI * g);
    let mut g_right = edge(edges[0]);
    let (mut ux, mut uy) = (0.0, 0.0);
    for i in 0..px.len() {
        let g_left = edge(edges[i + 1]);
        let d = |k: usize| g_left[k] - g_right[k];
        let (xx, xy, yy) = ((1.0 - nu) * d(0) + nu * d(1), nu * d(3), (1.0 - nu) * d(0) + nu * d(2));
        ux += xx * px[i] + xy * py[i];
        uy += xy * px[i] + yy * py[i];
        g_right = g_left;
    }
    [s * ux, s * uy]
}

/// The y-differenced corner primitives `corner(X, Yb) - corner(X, Ya)` of
/// [`corner_pair`] at every x-edge of `strip`, `X = x - edge`, four edges at
/// a time: every lane does the arithmetic of [`corner_pair`] in the same
/// order, so the values are those of the scalar form to the bit.
fn edge_values(strip: &Strip, x: f64, (yb, ya): (f64, f64), out: &mut Vec<[f64; 4]>) {
    let edges = &strip.edges;
    out.clear();
    let (ay1, ay2) = (yb.abs(), ya.abs());
    let (sy1, sy2) = (f64x4::splat(yb.signum()), f64x4::splat(ya.signum()));
    let (one, zero) = (f64x4::ONE, f64x4::ZERO);
    for chunk in edges.chunks(4) {
        let mut xs = [chunk[chunk.len() - 1]; 4];
        xs[..chunk.len()].copy_from_slice(chunk);
        let xv = f64x4::splat(x) - f64x4::new(xs);
        let (vy1, vy2) = (f64x4::splat(yb), f64x4::splat(ya));
        let r1 = (xv * xv + vy1 * vy1).sqrt();
        let r2 = (xv * xv + vy2 * vy2).sqrt();
        let ax = xv.abs();
        let x_zero = ax.simd_eq(zero);
        let over_ax = |num: f64x4| x_zero.select(one, num / ax);
        let over_ay = |num: f64x4, ay: f64| if ay == 0.0 { one } else { num / f64x4::splat(ay) };
        let la1 = over_ax(f64x4::splat(ay1) + r1).ln();
        let lb1 = over_ay(ax + r1, ay1).ln();
        let la2 = over_ax(f64x4::splat(ay2) + r2).ln();
        let lb2 = over_ay(ax + r2, ay2).ln();
        let sx = xv.is_sign_negative().select(-one, one);
        let (a1, b1) = (xv * sy1 * la1, vy1 * sx * lb1);
        let (a2, b2) = (xv * sy2 * la2, vy2 * sx * lb2);
        let g = [(a1 + b1) - (a2 + b2), b1 - b2, a1 - a2, r2 - r1].map(|v| v.to_array());
        out.extend((0..chunk.len()).map(|lane| [g[0][lane], g[1][lane], g[2][lane], g[3][lane]]));
    }
}

/// Influence coefficients `(c_xx, c_xy, c_yy)` of the elements of `strip`
/// at the point (`x`, `y`) (m), in units of `1 / (pi G)` (multiply by
/// `1 / (pi G)` for m/Pa): the corner rule of [`influence`] with shared
/// corners, as [`strip_displacement`], but four edges at a time and the
/// coefficients kept, so that a caller can apply them to more than one
/// traction field (the mirror image of a symmetric mesh, for instance).
/// `edge_buf` is scratch space.
pub fn strip_coefficients(
    strip: &Strip,
    (x, y): (f64, f64),
    nu: f64,
    edge_buf: &mut Vec<[f64; 4]>,
    out: &mut [[f64; 3]],
) {
    edge_values(strip, x, (y - strip.y_lo, y - strip.y_hi), edge_buf);
    for (i, c) in out.iter_mut().enumerate() {
        let (right, left) = (edge_buf[i], edge_buf[i + 1]);
        let d = |k: usize| left[k] - right[k];
        *c = [(1.0 - nu) * d(0) + nu * d(1), nu * d(3), (1.0 - nu) * d(0) + nu * d(2)];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strip_sum_equals_the_element_sum() {
        // Near field, on edges and at centres: within 1e-12 of the
        // element-by-element corner rule. Far away (25 and 250 element
        // lengths) both forms lose digits to cancellation between corners;
        // they agree within 1e-9 there.
        let (g, nu) = (8.0e10, 0.28);
        let edges: Vec<f64> = (0..=7).map(|e| 3e-3 - e as f64 * 0.8e-3).collect();
        let (y_lo, y_hi) = (-0.4e-3, 0.3e-3);
        let px: Vec<f64> = (0..7).map(|i| 1e8 * (1.0 + 0.3 * i as f64)).collect();
        let py: Vec<f64> = (0..7).map(|i| -2e7 * (i as f64 - 2.5)).collect();
        for (x, y) in [(0.0, 0.0), (3e-3, 0.3e-3), (-2.6e-3, -0.4e-3), (1.234e-3, 5e-3), (0.02, -0.005), (-0.2, 0.0)] {
            let strip = Strip { edges: edges.clone(), y_lo, y_hi };
            let fast = strip_displacement(&strip, (&px, &py), (x, y), g, nu);
            let (mut ux, mut uy) = (0.0, 0.0);
            for i in 0..7 {
                let r = Rect {
                    x: 0.5 * (edges[i] + edges[i + 1]),
                    y: 0.5 * (y_lo + y_hi),
                    hx: 0.5 * (edges[i] - edges[i + 1]),
                    hy: 0.5 * (y_hi - y_lo),
                };
                let c = influence(&r, x, y, g, nu);
                ux += c.xx * px[i] + c.xy * py[i];
                uy += c.xy * px[i] + c.yy * py[i];
            }
            let scale = ux.abs().max(uy.abs());
            let tol = if x.abs() > 0.01 { 1e-9 } else { 1e-12 };
            assert!(
                (fast[0] - ux).abs() < tol * scale && (fast[1] - uy).abs() < tol * scale,
                "at ({x}, {y}): {fast:?} vs ({ux}, {uy})"
            );
        }
    }

    #[test]
    fn strip_coefficients_are_the_scalar_corner_rule_to_the_bit() {
        let (g, nu) = (8.0e10, 0.28);
        let s = 1.0 / (PI * g);
        for n in [1, 3, 4, 7, 8] {
            let edges: Vec<f64> = (0..=n).map(|e| 3e-3 - e as f64 * 0.8e-3).collect();
            let strip = Strip { edges: edges.clone(), y_lo: -0.4e-3, y_hi: 0.3e-3 };
            let px: Vec<f64> = (0..n).map(|i| 1e8 * (1.0 + 0.3 * i as f64)).collect();
            let py: Vec<f64> = (0..n).map(|i| -2e7 * (i as f64 - 2.5)).collect();
            // On an edge (X = 0), on a y-edge (Y = 0), inside, outside.
            for (x, y) in [(0.0, 0.0), (edges[1], 0.3e-3), (-2.6e-3, -0.4e-3), (1.234e-3, 5e-3), (0.02, -0.005)] {
                let mut buf = Vec::new();
                let mut c = vec![[0.0; 3]; n];
                strip_coefficients(&strip, (x, y), nu, &mut buf, &mut c);
                let (mut ux, mut uy) = (0.0, 0.0);
                for i in 0..n {
                    ux += c[i][0] * px[i] + c[i][1] * py[i];
                    uy += c[i][1] * px[i] + c[i][2] * py[i];
                }
                let reference = strip_displacement(&strip, (&px, &py), (x, y), g, nu);
                assert_eq!([s * ux, s * uy], reference, "n {n} at ({x}, {y})");
            }
        }
    }

    /// Cerruti point-load kernel (two bodies) integrated by a tensor Gauss
    /// rule on a sub-grid of the rectangle.
    fn quadrature(rect: &Rect, x: f64, y: f64, g: f64, nu: f64, n: usize) -> Influence {
        let gl = [
            (-0.906179845938664, 0.236926885056189),
            (-0.538469310105683, 0.478628670499366),
            (0.0, 0.568888888888889),
            (0.538469310105683, 0.478628670499366),
            (0.906179845938664, 0.236926885056189),
        ];
        let mut out = Influence::default();
        let (dx, dy) = (2.0 * rect.hx / n as f64, 2.0 * rect.hy / n as f64);
        for i in 0..n {
            for j in 0..n {
                let (cx, cy) = (rect.x - rect.hx + (i as f64 + 0.5) * dx, rect.y - rect.hy + (j as f64 + 0.5) * dy);
                for (u, wu) in gl {
                    for (v, wv) in gl {
                        let (px, py) = (cx + 0.5 * dx * u, cy + 0.5 * dy * v);
                        let (rx, ry) = (x - px, y - py);
                        let r = rx.hypot(ry);
                        let w = wu * wv * 0.25 * dx * dy / (PI * g);
                        out.xx += w * ((1.0 - nu) / r + nu * rx * rx / r.powi(3));
                        out.xy += w * nu * rx * ry / r.powi(3);
                        out.yy += w * ((1.0 - nu) / r + nu * ry * ry / r.powi(3));
                    }
                }
            }
        }
        out
    }

    #[test]
    fn matches_quadrature_near_and_far() {
        let (g, nu) = (8.08e10, 0.3);
        let rect = Rect { x: 0.001, y: -0.0005, hx: 3e-4, hy: 5e-4 };
        // Far field and near field (outside the rectangle, close to an edge).
        for (x, y) in [(0.02, 0.013), (-0.004, 0.002), (0.0014, 0.0001), (0.001, 0.00009)] {
            let c = influence(&rect, x, y, g, nu);
            let q = quadrature(&rect, x, y, g, nu, 40);
            for (a, b) in [(c.xx, q.xx), (c.xy, q.xy), (c.yy, q.yy)] {
                assert!((a - b).abs() <= 1e-6 * c.xx.abs(), "({x},{y}): {a} vs {b}");
            }
        }
    }

    #[test]
    fn self_influence_is_finite_and_symmetric() {
        let (g, nu) = (8.08e10, 0.3);
        let sq = Rect { x: 0.0, y: 0.0, hx: 1e-3, hy: 1e-3 };
        let c = influence(&sq, 0.0, 0.0, g, nu);
        assert!(c.xx.is_finite() && c.xx > 0.0 && c.xy.abs() < 1e-30);
        assert!((c.xx - c.yy).abs() < 1e-12 * c.xx, "square: xx = yy");
        // Closed form at the centre of a square of side 2h:
        // int int 1/r = 8 h asinh(1), int int x^2/r^3 = 4 h asinh(1).
        let h = 1e-3;
        let expect = (8.0 * h * (1.0f64).asinh() * (1.0 - nu) + nu * 4.0 * h * (1.0f64).asinh()) / (PI * g);
        assert!((c.xx - expect).abs() < 1e-12 * expect);
    }

    #[test]
    fn normal_influence_at_the_centre_of_a_square() {
        // int int 1/r over a square of side 2h at its centre: 8 h asinh(1);
        // far away: the point load (1 - nu) P / (pi G r), P = 4 h^2.
        let (g, nu, h) = (8.08e10, 0.3, 1e-3);
        let sq = Rect { x: 0.0, y: 0.0, hx: h, hy: h };
        let c = normal_influence(&sq, 0.0, 0.0, g, nu);
        let expect = (1.0 - nu) * 8.0 * h * (1.0f64).asinh() / (PI * g);
        assert!((c - expect).abs() < 1e-12 * expect);
        let r = 0.5;
        let far = normal_influence(&sq, r, 0.0, g, nu);
        let point = (1.0 - nu) * 4.0 * h * h / (PI * g * r);
        assert!((far - point).abs() < 1e-5 * point, "{far} vs {point}");
    }

    #[test]
    fn reciprocity() {
        // Influence of element A at the centre of B equals that of B at A for
        // equal-area elements (Betti), up to the element-averaging error; exact
        // for mirror-image elements.
        let (g, nu) = (8.08e10, 0.28);
        let a = Rect { x: 0.0, y: 0.0, hx: 2e-4, hy: 3e-4 };
        let b = Rect { x: 1.3e-3, y: -0.7e-3, hx: 2e-4, hy: 3e-4 };
        let ab = influence(&a, b.x, b.y, g, nu);
        let ba = influence(&b, a.x, a.y, g, nu);
        assert!((ab.xx - ba.xx).abs() < 1e-12 * ab.xx);
        assert!((ab.xy - ba.xy).abs() < 1e-12 * ab.xx);
        assert!((ab.yy - ba.yy).abs() < 1e-12 * ab.yy);
    }
}
